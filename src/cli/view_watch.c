/* sylva view: follow the model file and every file it names (a species' XML, an obstacle's
 * OBJ, a DEM, a texture: any quoted name in the source that is a file) with inotify. The
 * directories are watched, not the files, so that an editor that saves by writing a new file
 * and renaming it over the old one (vim, many IDEs) is seen too. */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <sys/inotify.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/view.h"

enum { MAX_FILES = 256, MAX_DIRS = 64 };

typedef struct Watch {
    View *v;
    int ifd, stop_fd;
    char *files[MAX_FILES]; /* the files followed, as paths (the model's directory joined) */
    int nfiles;
    struct {
        int wd;
        char *dir;
    } dirs[MAX_DIRS];
    int ndirs;
} Watch;

void view_changed(View *v) {
    pthread_mutex_lock(&v->gen_lock);
    v->gen++;
    pthread_cond_broadcast(&v->changed);
    pthread_mutex_unlock(&v->gen_lock);
}

static void watch_dir(Watch *w, const char *file) {
    char *slash = strrchr(file, '/');
    char *dir = slash ? strndup(file, (size_t)(slash - file)) : strdup(".");
    if (!dir) return;
    if (!*dir) free(dir), dir = strdup("/");
    for (int i = 0; dir && i < w->ndirs; i++)
        if (!strcmp(w->dirs[i].dir, dir)) return free(dir);
    if (!dir || w->ndirs == MAX_DIRS) return free(dir);
    int wd = inotify_add_watch(w->ifd, dir, IN_CLOSE_WRITE | IN_MOVED_TO | IN_CREATE | IN_DELETE | IN_MODIFY);
    if (wd < 0) return free(dir);
    w->dirs[w->ndirs].wd = wd;
    w->dirs[w->ndirs++].dir = dir;
}

static void add_file(Watch *w, const char *path) {
    for (int i = 0; i < w->nfiles; i++)
        if (!strcmp(w->files[i], path)) return;
    if (w->nfiles == MAX_FILES) return;
    char *c = strdup(path);
    if (!c) return;
    w->files[w->nfiles++] = c;
    watch_dir(w, c);
}

/* The model file, and every quoted name in it that is a file (relative to its directory). */
static void rescan(Watch *w) {
    add_file(w, w->v->path);
    size_t len = 0;
    char *text = syl_read_file(w->v->path, &len);
    if (!text) return;
    for (char *s = strchr(text, '"'); s; s = strchr(s + 1, '"')) {
        char *e = strchr(s + 1, '"');
        if (!e) break;
        size_t n = (size_t)(e - s - 1);
        char path[sizeof w->v->dir + 1024];
        if (n > 0 && n < 1024 && !memchr(s + 1, '\n', n)) {
            if (s[1] == '/') snprintf(path, sizeof path, "%.*s", (int)n, s + 1);
            else snprintf(path, sizeof path, "%s/%.*s", w->v->dir, (int)n, s + 1);
            struct stat st;
            if (!stat(path, &st) && S_ISREG(st.st_mode)) add_file(w, path);
        }
        s = e;
    }
    free(text);
}

/* Whether the event is about a followed file. */
static bool followed(const Watch *w, const struct inotify_event *ev) {
    if (!ev->len) return false;
    for (int d = 0; d < w->ndirs; d++) {
        if (w->dirs[d].wd != ev->wd) continue;
        size_t dl = strlen(w->dirs[d].dir);
        for (int i = 0; i < w->nfiles; i++) {
            const char *f = w->files[i];
            bool here = !strncmp(f, w->dirs[d].dir, dl) && f[dl] == '/' ? !strcmp(f + dl + 1, ev->name)
                        : !strchr(f, '/') && !strcmp(w->dirs[d].dir, ".") && !strcmp(f, ev->name);
            if (here) return true;
        }
    }
    return false;
}

/* Read what is there; true when a followed file changed. *whole: one of them was a whole save
 * (closed after writing, or renamed over the file, as editors save): nothing more of it comes. */
static bool drain(Watch *w, bool *whole) {
    char buf[8192] __attribute__((aligned(__alignof__(struct inotify_event))));
    bool hit = false;
    for (;;) {
        ssize_t n = read(w->ifd, buf, sizeof buf);
        if (n <= 0) break;
        for (char *p = buf; p < buf + n;) {
            const struct inotify_event *ev = (const struct inotify_event *)p;
            if (followed(w, ev)) {
                hit = true;
                if (ev->mask & (IN_CLOSE_WRITE | IN_MOVED_TO)) *whole = true;
            }
            p += sizeof *ev + ev->len;
        }
    }
    return hit;
}

static void *run(void *arg) {
    Watch *w = arg;
    rescan(w);
    for (;;) {
        struct pollfd fds[2] = {{.fd = w->ifd, .events = POLLIN}, {.fd = w->stop_fd, .events = POLLIN}};
        if (poll(fds, 2, -1) < 0 && errno != EINTR) break;
        if (fds[1].revents) break;
        bool whole = false;
        if (!(fds[0].revents & POLLIN) || !drain(w, &whole)) continue;
        /* one save is several events (truncate, write, close; or create, rename): let them
         * come, then say it once — at once when the save is whole (closed or renamed): its
         * 30 ms of waiting were a third of issue 30's save-to-frame time of a small model */
        while (!whole && poll(fds, 1, 30) > 0 && (fds[0].revents & POLLIN)) drain(w, &whole);
        rescan(w); /* the file may name new files now */
        view_changed(w->v);
    }
    for (int i = 0; i < w->nfiles; i++) free(w->files[i]);
    for (int d = 0; d < w->ndirs; d++) free(w->dirs[d].dir);
    close(w->ifd);
    close(w->stop_fd);
    free(w);
    return NULL;
}

bool view_watch_start(View *v, pthread_t *thread, int *stop_fd) {
    int pipefd[2];
    Watch *w = calloc(1, sizeof *w);
    if (!w || pipe2(pipefd, O_CLOEXEC)) return free(w), false;
    w->v = v;
    w->ifd = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    w->stop_fd = pipefd[0];
    if (w->ifd < 0 || pthread_create(thread, NULL, run, w)) {
        if (w->ifd >= 0) close(w->ifd);
        close(pipefd[0]), close(pipefd[1]);
        free(w);
        return false;
    }
    *stop_fd = pipefd[1];
    return true;
}

void view_watch_stop(pthread_t thread, int stop_fd) {
    if (write(stop_fd, "x", 1) < 0) { /* the thread then waits for nothing */
    }
    pthread_join(thread, NULL);
    close(stop_fd);
}
