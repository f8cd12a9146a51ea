/* sylva: the command line. Each subcommand lives in its own file. */
#include <errno.h>
#include <limits.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli/cli.h"
#include "util/closest.h"

/* The named temporary files of this run (util/outfile reports them), removed when SIGINT,
 * SIGTERM or SIGHUP stops it. A slot's path is written before it is marked live, so the
 * handler, on whatever thread, sees only whole paths; it uses only unlink and raise. */
enum { MAX_TEMPS = 16 };
static char temp_path[MAX_TEMPS][PATH_MAX + 64];
static atomic_int temp_live[MAX_TEMPS];

static void temp_created(void *ctx, const char *tmp) {
    (void)ctx;
    if (strlen(tmp) >= sizeof temp_path[0]) return; /* too long to keep: outfile would fail anyway */
    for (int i = 0; i < MAX_TEMPS; i++)
        if (!atomic_load(&temp_live[i])) {
            strcpy(temp_path[i], tmp);
            atomic_store(&temp_live[i], 1);
            return;
        }
}

static void temp_gone(void *ctx, const char *tmp) {
    (void)ctx;
    for (int i = 0; i < MAX_TEMPS; i++)
        if (atomic_load(&temp_live[i]) && !strcmp(temp_path[i], tmp)) {
            atomic_store(&temp_live[i], 0);
            return;
        }
}

const OutHooks cli_temp_hooks = {temp_created, temp_gone, NULL};

static void remove_temps(void) {
    for (int i = 0; i < MAX_TEMPS; i++)
        if (atomic_exchange(&temp_live[i], 0)) unlink(temp_path[i]);
}

static void stop_on_signal(int sig) {
    /* ffmpeg, which writes into a temporary file, is stopped and waited for before the
     * temporary files go, or it would write its file after they went */
    int child = cli_child_take(), saved = errno;
    if (child > 0 && !kill(child, SIGKILL))
        while (waitpid(child, NULL, 0) < 0 && errno == EINTR) {
        }
    errno = saved;
    remove_temps();
    raise(sig); /* SA_RESETHAND: the default action, once this handler returns */
}

static void on_signal(int sig) {
    if (!cli_child_defer(sig)) stop_on_signal(sig);
}

/* A library bound on first use (util/lazylib.h) that cannot be loaded: said once, the
 * temporary files removed, exit code 5 (docs/cli.md). There is no way back from the middle
 * of the call that needed it, and other threads may be running: _exit. */
static void missing_library(const char *soname, const char *what, const char *why) {
    fprintf(stderr, "sylva: error: cannot load %s, which %s needs: %s\n", soname, what, why);
    fflush(stderr);
    remove_temps();
    _exit(5);
}

static void install_signals(void) {
    cli_child_on_signal(stop_on_signal);
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP};
    for (size_t i = 0; i < sizeof sigs / sizeof *sigs; i++) {
        struct sigaction sa = {0}, old;
        sa.sa_handler = on_signal;
        sa.sa_flags = SA_RESETHAND;
        sigemptyset(&sa.sa_mask);
        /* A signal the caller ignores (nohup, `&` in a script) stays ignored. */
        if (!sigaction(sigs[i], NULL, &old) && old.sa_handler != SIG_IGN) sigaction(sigs[i], &sa, NULL);
    }
    /* Beyond `ulimit -f` a write then fails with EFBIG, reported and exit 4, instead of a core. */
    signal(SIGXFSZ, SIG_IGN);
}

static void help(FILE *out) {
    fprintf(out, "usage: sylva COMMAND [options]\n\nSylva %s: plant models from grammar files.\n\ncommands:\n",
            SYLVA_VERSION);
    for (const CliCommand *const *c = cli_commands; *c; c++) fprintf(out, "  %-9s %s\n", (*c)->name, (*c)->what);
    fprintf(out, "\n`sylva FILE` alone writes out/NAME.png and out/NAME.glb (see `sylva FILE --help`).\n"
                 "`sylva COMMAND --help` describes a command. A model is named FILE or FILE:Model\n"
                 "when a file holds several. Exit codes: 0 ok, 1 the model is wrong, 2 bad command\n"
                 "line, 3 a resource limit was hit, 4 an I/O error.\n");
}

int main(int argc, char **argv) {
    install_signals();
    syl_missing_library_set(missing_library);
    if (argc < 2) {
        help(stderr);
        return SYL_EUSAGE;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h") || !strcmp(cmd, "help")) {
        if (argc > 2 && strcmp(cmd, "help") == 0)
            for (const CliCommand *const *c = cli_commands; *c; c++)
                if (!strcmp((*c)->name, argv[2])) {
                    char *args[] = {argv[2], "--help", NULL};
                    return (*c)->run(2, args);
                }
        help(stdout);
        return SYL_OK;
    }
    if (!strcmp(cmd, "--version") || !strcmp(cmd, "-V")) {
        printf("sylva %s\n", SYLVA_VERSION);
        return SYL_OK;
    }
    for (const CliCommand *const *c = cli_commands; *c; c++)
        if (!strcmp((*c)->name, cmd)) {
            char name[64]; /* getopt's messages begin with argv[0]: "sylva derive: ..." */
            snprintf(name, sizeof name, "sylva %s", cmd);
            argv[1] = name;
            return (*c)->run(argc - 1, argv + 1);
        }
    ModelArgs m; /* `sylva FILE[:Model]`: a picture and a mesh in out/ */
    cli_model_spec(&m, cmd);
    if (access(m.path, R_OK) == 0 || !strcmp(cmd, "-")) return cmd_plant(argc, argv);
    const char *names[64];
    int n = 0;
    for (const CliCommand *const *c = cli_commands; *c && n < 64; c++) names[n++] = (*c)->name;
    char near[160];
    if (closest_list(cmd, names, n, near, sizeof near)) { /* a typo: one line, not the whole list */
        fprintf(stderr, "sylva: unknown command '%s' (did you mean %s?)\n", cmd, near);
        return SYL_EUSAGE;
    }
    fprintf(stderr, "sylva: unknown command '%s'\n\n", cmd);
    help(stderr);
    return SYL_EUSAGE;
}
