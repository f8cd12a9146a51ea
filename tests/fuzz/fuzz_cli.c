/* libFuzzer harness: the command line. The input is split into arguments at newlines and
 * NUL bytes; the first byte picks a command (or `sylva FILE`-less dispatch: --help,
 * --version, an unknown word). The command runs for real — getopt, --set, -o, every number
 * and size parser — in a private temporary directory holding a small model.syl, with its
 * output on /dev/null. To keep it safe and quick, arguments that name another directory
 * (any '/') and options that would make the work large (-n, -j, --max-*, --derive,
 * --threads, --size, --image, --seeds, --years) are left out: their parsers are fuzzed by
 * fuzz_cli's own calls below, with the value from the input. The harness changes directory on
 * its first input: give libFuzzer absolute corpus paths (tests/fuzz/run does). */
#include <dirent.h>
#include <fcntl.h>
#include <getopt.h>
#include <unistd.h>

#include "fuzz.h"

#define main sylva_main
#include "cli/main.c"
#undef main

static const char model[] =
    "param a = 30\nparam k = 0.8\n"
    "lsystem Tree {\n  derive 3\n  angle (a)\n  seed 2\n  axiom A(1)\n"
    "  A(x) -> F(x)[+A(x * k)][-A(x * k)] : 1\n  A(x) -> F(x)A(x * k) : 1\n}\n"
    "lsystem Line {\n  axiom F(1)F(2)\n}\n";

static const char *commands_fuzzed[] = {"derive", "check", "compile", "skeleton", "mesh", "compare", "help"};

/* The work a command may do stays small: no option that scales it. */
static bool allowed(const char *arg) {
    static const char *const big[] = {"--max", "--de", "--th", "--si", "--im", "--seeds", "--ye", "--ou"};
    if (strchr(arg, '/')) return false;
    for (size_t i = 0; i < sizeof big / sizeof *big; i++)
        if (!strncmp(arg, big[i], strlen(big[i]))) return false;
    if (arg[0] == '-' && arg[1] != '-' && (strchr(arg, 'n') || strchr(arg, 'j'))) return false;
    return true;
}

static char dir[64];

/* What a command wrote: every file but model.syl goes. */
static void clean_dir(void) {
    DIR *d = opendir(".");
    if (!d) return;
    struct dirent *e;
    while ((e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..") && strcmp(e->d_name, "model.syl")) {
            if (unlink(e->d_name)) {
                char sub[300]; /* a --out directory */
                snprintf(sub, sizeof sub, "rm -rf -- '%s'", e->d_name);
                if (!strchr(e->d_name, '\'') && system(sub)) {}
            }
        }
    closedir(d);
}

/* The work directory goes when the process ends (a replay, or a fuzzer's run): no litter in /tmp. */
static void teardown(void) {
    if (chdir(dir) != 0) return;
    clean_dir();
    unlink("model.syl");
    if (chdir("/") == 0) rmdir(dir);
}

static void setup(void) {
    strcpy(dir, "/tmp/sylva-fuzz-cli-XXXXXX");
    if (!mkdtemp(dir) || chdir(dir)) abort();
    atexit(teardown);
    FILE *f = fopen("model.syl", "w");
    if (!f || fputs(model, f) < 0 || fclose(f)) abort();
    int null = open("/dev/null", O_RDWR);
    if (null < 0 || dup2(null, 0) < 0 || dup2(null, 1) < 0) abort();
    close(null);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (!dir[0]) setup();
    if (size < 1 || size > 2048) return 0;
    char *text = fuzz_text(data + 1, size - 1);
    enum { MAXARGS = 24 };
    char *argv[MAXARGS + 3];
    int argc = 0;
    argv[argc++] = "sylva";
    unsigned pick = data[0] % (sizeof commands_fuzzed / sizeof *commands_fuzzed + 1);
    if (pick < sizeof commands_fuzzed / sizeof *commands_fuzzed) argv[argc++] = (char *)commands_fuzzed[pick];
    for (char *s = text, *end = text + size - 1; s < end && argc < MAXARGS;) {
        size_t n = strcspn(s, "\n");
        s[n] = 0;
        if (allowed(s)) argv[argc++] = s;
        s += n + 1;
        while (s < end && !*s) s++;
    }
    argv[argc] = NULL;
    /* `sylva FILE[:Model]` (and `sylva -`) render a full-size picture: too slow to fuzz here */
    if (pick >= sizeof commands_fuzzed / sizeof *commands_fuzzed && argc > 1 &&
        (argv[1][0] != '-' || !strcmp(argv[1], "-"))) {
        free(text);
        return 0;
    }
    int saved_err = -1;
    if (!getenv("SYLVA_FUZZ_VERBOSE")) {
        fflush(stderr);
        saved_err = dup(2);
        int null = open("/dev/null", O_WRONLY);
        dup2(null, 2);
        close(null);
    }
    /* the value parsers, on every argument as a value */
    ModelArgs m = {0};
    for (int i = 1; i < argc; i++) {
        double v;
        unsigned long long sz;
        int w, h;
        SylView view;
        SylDeriveOptions d = {0};
        char copy[2048];
        snprintf(copy, sizeof copy, "%s", argv[i]);
        (void)cli_number("--x", argv[i], -1e300, 1e300, &v);
        (void)cli_integer("--x", argv[i], 0, 1e6, &v);
        (void)cli_size("--x", argv[i], &sz);
        (void)cli_picture_size(argv[i], &w, &h);
        (void)cli_view(argv[i], &view);
        cli_model_spec(&m, argv[i]);
        (void)cli_set(&m, copy);
        SylMeshOptions mo = {0};
        SylRenderOptions ro = {0};
        CliArgs a = {.m = &m, .d = &d, .mo = &mo, .ro = &ro};
        for (int o = 1; o < CLI_OPT_COUNT; o++) { /* every option's reader */
            snprintf(copy, sizeof copy, "%s", argv[i]);
            (void)cli_apply((CliOptionId)o, cli_options[o].arg ? copy : NULL, &a);
        }
    }
    /* the command itself */
    /* Start getopt afresh, as a new process would (cli_parse does too, with optind = 0: 1 would
     * keep glibc's pointer into the last input's arguments when they stopped inside "-abc"). */
    optind = 0;
    char *dummy[] = {"sylva", NULL};
    (void)getopt(1, dummy, "");
    (void)sylva_main(argc, argv);
    fflush(stdout);
    if (saved_err >= 0) {
        fflush(stderr);
        dup2(saved_err, 2);
        close(saved_err);
    }
    clean_dir();
    free(text);
    return 0;
}
