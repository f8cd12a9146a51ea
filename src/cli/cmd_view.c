/* sylva view: serve a model file to the browser and follow its edits (docs/view.md). */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <malloc.h>
#include "cli/mhd_lazy.h"
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli/view.h"

#ifndef SYL_WEB_DIR
#define SYL_WEB_DIR "web"
#endif

extern char **environ;

const CliCommand cli_view_command = {
    .name = "view",
    .what = "show a model file in the browser, live: it follows the file's edits",
    .run = cmd_view,
    .usage = "sylva view FILE [--port N] [--host ADDR] [--open]",
    .about = "Start a web server on this machine and print its address: a page that draws the file's\n"
             "models from the .glb `sylva mesh` writes, shows the messages of `sylva check` and the\n"
             "counts and times of `sylva mesh`, gives every parameter a slider, and exports .glb, .obj, .png and\n"
             "the skeleton through the CLI's writers. When the file, or a file it names, changes on\n"
             "disk the page is updated, keeping its camera. Only requests that carry the printed\n"
             "address's token are answered. Ctrl-C stops it. docs/view.md describes the page.\n",
    .options = (const CliUse[]){
        {.option = CLI_OPT_PORT},
        {.option = CLI_OPT_HOST},
        {.option = CLI_OPT_OPEN},
        {.option = CLI_OPT_THREADS},
        {.option = CLI_OPT_MAX_MEMORY},
        {.option = CLI_OPT_MAX_MODULES},
        {0},
    },
    .epilogue = "\nThe page's files: SYLVA_WEB=DIR, else PREFIX/share/sylva/web beside an installed PREFIX/bin/sylva,\n"
                "else " SYL_WEB_DIR ".\n" CLI_EXIT_CODES,
    .args_error = "expects one model file",
};

static bool make_token(char *out) {
    unsigned char raw[VIEW_TOKEN / 2];
    int fd = open("/dev/urandom", O_RDONLY | O_CLOEXEC);
    bool ok = fd >= 0 && read(fd, raw, sizeof raw) == (ssize_t)sizeof raw;
    if (fd >= 0) close(fd);
    for (size_t i = 0; ok && i < sizeof raw; i++) sprintf(out + 2 * i, "%02x", raw[i]);
    return ok;
}

static void open_browser(const char *url) {
    pid_t pid;
    char *argv[] = {"xdg-open", (char *)url, NULL};
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
    if (posix_spawnp(&pid, "xdg-open", &fa, NULL, argv, environ))
        fprintf(stderr, "sylva view: cannot start xdg-open; open the address above yourself\n");
    posix_spawn_file_actions_destroy(&fa);
}

/* PREFIX/share/sylva/web when this program is PREFIX/bin/sylva and make install put the page
 * there (found from /proc/self/exe, so a DESTDIR or a moved prefix works too); false else. */
static bool installed_web(char *out, size_t n) {
    char exe[PATH_MAX];
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (len <= 0) return false;
    exe[len] = 0;
    char *slash = strrchr(exe, '/');
    if (!slash) return false;
    *slash = 0; /* PREFIX/bin */
    char probe[PATH_MAX + 64];
    snprintf(probe, sizeof probe, "%s/../share/sylva/web/node_modules/three/build/three.module.js", exe);
    if (access(probe, R_OK) || (size_t)snprintf(out, n, "%s/../share/sylva/web", exe) >= n) return false;
    return true;
}

int cmd_view(int argc, char **argv) {
    SylDeriveOptions d = {.steps = -1};
    CliArgs a = {.d = &d, .port = 8470, .host = "127.0.0.1"};
    int done = cli_parse(&cli_view_command, argc, argv, &a);
    if (done != CLI_RUN) return done;
    static View v; /* its locks and the daemon's threads live as long as the command */
    if (strlen(a.files[0]) >= sizeof v.path) {
        fprintf(stderr, "sylva view: error: the path is too long\n");
        return SYL_EUSAGE;
    }
    snprintf(v.path, sizeof v.path, "%s", a.files[0]);
    struct stat st;
    if (stat(v.path, &st) || !S_ISREG(st.st_mode)) {
        fprintf(stderr, "sylva: error: cannot read '%s': %s\n", v.path, errno ? strerror(errno) : "not a file");
        return SYL_EIO;
    }
    const char *slash = strrchr(v.path, '/');
    snprintf(v.dir, sizeof v.dir, "%.*s", slash ? (int)(slash - v.path) : 1, slash ? v.path : ".");
    if (!v.dir[0]) snprintf(v.dir, sizeof v.dir, "/");
    const char *web = getenv("SYLVA_WEB");
    if (web && *web) snprintf(v.web, sizeof v.web, "%s", web);
    else if (!installed_web(v.web, sizeof v.web)) snprintf(v.web, sizeof v.web, "%s", SYL_WEB_DIR);
    char probe[sizeof v.web + 64];
    snprintf(probe, sizeof probe, "%s/node_modules/three/build/three.module.js", v.web);
    if (access(probe, R_OK)) {
        fprintf(stderr, "sylva view: error: the page's files are missing: no %s (make deps installs three.js "
                        "with npm ci --prefix web)\n", probe);
        return SYL_EIO;
    }
    if (!make_token(v.token)) {
        fprintf(stderr, "sylva view: error: cannot read /dev/urandom for the token\n");
        return SYL_EIO;
    }
    v.threads = d.threads, v.max_memory = d.max_memory, v.max_modules = d.max_modules;
    /* Every build allocates what the last one freed (strings, meshes, the .glb): keep freed
     * memory in one heap for the next instead of giving it back to the system and taking it
     * again page fault by page fault (a third of a build's time on a virtual machine). */
    mallopt(M_ARENA_MAX, 1);
    mallopt(M_MMAP_MAX, 0);
    mallopt(M_TRIM_THRESHOLD, INT_MAX);
    pthread_mutex_init(&v.lock, NULL);
    pthread_mutex_init(&v.gen_lock, NULL);
    pthread_mutex_init(&v.keep_lock, NULL);
    pthread_condattr_t ca;
    pthread_condattr_init(&ca);
    pthread_cond_init(&v.changed, &ca);
    /* Ctrl-C and kill are taken by sigwait below, not by a handler in whichever thread */
    sigset_t stop;
    sigemptyset(&stop);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGTERM);
    sigaddset(&stop, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &stop, NULL);
    signal(SIGPIPE, SIG_IGN); /* a closed tab is a failed write, not the end of the server */
    pthread_t watcher;
    int watch_stop = -1;
    if (!view_watch_start(&v, &watcher, &watch_stop))
        fprintf(stderr, "sylva view: warning: cannot follow the files (inotify): reload the page by hand\n");
    pthread_t prebuilder;
    bool prebuilding = view_prebuild_start(&v, &prebuilder); /* without it, a save is built when asked */
    int port = 0;
    struct MHD_Daemon *daemon = view_http_start(&v, a.host, a.port, &port);
    if (!daemon) {
        if (watch_stop >= 0) view_watch_stop(watcher, watch_stop);
        pthread_mutex_lock(&v.gen_lock);
        v.stopping = true;
        pthread_cond_broadcast(&v.changed);
        pthread_mutex_unlock(&v.gen_lock);
        if (prebuilding) pthread_join(prebuilder, NULL);
        return SYL_EIO;
    }
    char url[256];
    snprintf(url, sizeof url, "http://%s:%d/?token=%s", a.host, port, v.token);
    printf("%s\n", url);
    fflush(stdout);
    fprintf(stderr, "sylva view: serving %s; Ctrl-C stops\n", v.path);
    if (strcmp(a.host, "127.0.0.1"))
        fprintf(stderr, "sylva view: warning: listening on %s: other machines can reach it (the token guards it)\n",
                a.host);
    if (a.open) open_browser(url);
    int sig = 0;
    while (sigwait(&stop, &sig) && errno == EINTR) {
    }
    fprintf(stderr, "sylva view: stopping\n");
    pthread_mutex_lock(&v.gen_lock);
    v.stopping = true;
    pthread_cond_broadcast(&v.changed);
    pthread_mutex_unlock(&v.gen_lock);
    MHD_stop_daemon(daemon);
    if (watch_stop >= 0) view_watch_stop(watcher, watch_stop);
    if (prebuilding) pthread_join(prebuilder, NULL);
    view_cache_free(&v);
    return SYL_OK;
}
