/* sylva derive: print the derived string. */
#include <getopt.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static const char usage[] =
    "usage: sylva derive FILE[:Model] [options]\n"
    "\n"
    "Derive the model and print the final string in canonical form: modules one after\n"
    "another, parameters in parentheses printed with %g and separated by commas.\n"
    "\n"
    "  -n, --derive N        derivation steps (default: the model's `derive`)\n"
    "  --seed S              random seed (default: the model's `seed`)\n"
    "  --set NAME=VALUE      override a `param` of the model (repeatable)\n"
    "  --steps               print every step on its own line, step 0 being the axiom\n"
    "  --interpret           apply the model's `interpret` rules before printing\n"
    "  --stats               print module counts, time and peak memory to stderr\n"
    "  -q, --quiet           do not print the string (with --stats: figures only)\n"
    "  -o, --output FILE     write to FILE instead of standard output\n"
    "  -j, --threads N       threads (default: all cores); the output never depends on N\n"
    "  --max-modules N       stop with exit code 3 beyond N modules (default 200000000)\n"
    "  --max-memory SIZE     stop with exit code 3 beyond SIZE of strings, e.g. 2G\n"
    "                        (default: half the machine's memory, at most 16G)\n"
    "\n"
    "Exit codes: 0 ok, 1 the model is wrong, 2 bad command line, 3 limit hit, 4 I/O error.\n";

typedef struct StepPrinter {
    const SylProgram *p;
    FILE *out;
    int status;
} StepPrinter;

static void print_step(void *user, int step, const SylString *s) {
    (void)step;
    StepPrinter *sp = user;
    if (!sp->status) sp->status = syl_string_write(sp->p, s, sp->out);
    if (!sp->status && fputc('\n', sp->out) == EOF) sp->status = SYL_EIO;
}

static void print_stats(const SylProgram *p, const SylString *s, int steps, double seconds, uint64_t rewritten) {
    int ns = syl_program_symbol_count(p);
    uint64_t *counts = calloc((size_t)ns, sizeof *counts);
    size_t n = syl_string_length(s);
    fprintf(stderr, "steps: %d\nmodules: %zu\nderive time: %.6f s\n", steps, n, seconds);
    if (seconds > 0) fprintf(stderr, "rate: %.2f M modules/s\n", (double)n / seconds / 1e6);
    fprintf(stderr, "rewritten: %llu modules in all steps", (unsigned long long)rewritten);
    if (seconds > 0) fprintf(stderr, " (%.2f M/s)", (double)rewritten / seconds / 1e6);
    fputc('\n', stderr);
    fprintf(stderr, "peak memory: %.2f MB\n", cli_peak_mb());
    if (!counts) return;
    syl_string_count(s, counts);
    fprintf(stderr, "symbols:");
    for (int i = 0; i < ns; i++)
        if (counts[i]) fprintf(stderr, " %s=%llu", syl_program_symbol_name(p, i), (unsigned long long)counts[i]);
    fputc('\n', stderr);
    free(counts);
}

int cmd_derive(int argc, char **argv) {
    static const struct option opts[] = {
        {"derive", required_argument, 0, 'n'},    {"seed", required_argument, 0, 's'},
        {"set", required_argument, 0, 'S'},       {"steps", no_argument, 0, 'A'},
        {"interpret", no_argument, 0, 'I'},       {"stats", no_argument, 0, 't'},
        {"output", required_argument, 0, 'o'},    {"threads", required_argument, 0, 'j'},
        {"max-modules", required_argument, 0, 'M'}, {"max-memory", required_argument, 0, 'm'},
        {"quiet", no_argument, 0, 'q'},
        {"help", no_argument, 0, 'h'},            {0, 0, 0, 0},
    };
    ModelArgs m = {0};
    SylDeriveOptions d = {.steps = -1, .diag = stderr};
    const char *output = NULL;
    bool all_steps = false, interpret = false, stats = false, quiet = false;
    double v;
    unsigned long long size;
    int c;
    optind = 1;
    while ((c = getopt_long(argc, argv, "n:o:j:qh", opts, NULL)) != -1) {
        switch (c) {
        case 'n':
            if (!cli_integer("-n", optarg, 0, 1e6, &v)) return SYL_EUSAGE;
            d.steps = (int)v;
            break;
        case 's':
            if (!cli_integer("--seed", optarg, 0, 9007199254740991.0, &v)) return SYL_EUSAGE;
            d.use_seed = 1;
            d.seed = (uint64_t)v;
            break;
        case 'S':
            if (!cli_set(&m, optarg)) return SYL_EUSAGE;
            break;
        case 'A': all_steps = true; break;
        case 'I': interpret = true; break;
        case 't': stats = true; break;
        case 'q': quiet = true; break;
        case 'o': output = optarg; break;
        case 'j':
            if (!cli_integer("-j", optarg, 1, 256, &v)) return SYL_EUSAGE;
            d.threads = (int)v;
            break;
        case 'M':
            if (!cli_integer("--max-modules", optarg, 1, 2147483647.0, &v)) return SYL_EUSAGE;
            d.max_modules = (uint64_t)v;
            break;
        case 'm':
            if (!cli_size("--max-memory", optarg, &size)) return SYL_EUSAGE;
            d.max_memory = size;
            break;
        case 'h': fputs(usage, stdout); return SYL_OK;
        default: fputs(usage, stderr); return SYL_EUSAGE;
        }
    }
    if (optind != argc - 1) {
        fprintf(stderr, "sylva derive: expects one model file\n%s", usage);
        return SYL_EUSAGE;
    }
    if (all_steps && interpret) {
        fprintf(stderr, "sylva derive: --steps and --interpret do not go together\n");
        return SYL_EUSAGE;
    }
    cli_model_spec(&m, argv[optind]);
    int status;
    SylProgram *p = cli_compile(&m, 0, &status);
    if (!p) return status;
    OutFile out;
    if (!out_open(&out, output)) {
        syl_program_free(p);
        return SYL_EIO;
    }
    StepPrinter sp = {.p = p, .out = out.f};
    if (all_steps && !quiet) {
        d.on_step = print_step;
        d.user = &sp;
    }
    SylString *s = NULL;
    double t0 = cli_now();
    status = syl_derive(p, &d, &s);
    double t1 = cli_now();
    if (!status && interpret) {
        SylString *t = NULL;
        status = syl_interpret(p, s, &d, &t);
        syl_string_free(s);
        s = t;
    }
    if (!status) status = sp.status;
    if (!status && !all_steps && !quiet) {
        status = syl_string_write(p, s, out.f);
        if (!status && fputc('\n', out.f) == EOF) status = SYL_EIO;
    }
    if (status == SYL_EIO) fprintf(stderr, "sylva: error: cannot write the output\n");
    status = out_close(&out, status);
    if (!status && stats) print_stats(p, s, d.steps >= 0 ? d.steps : syl_program_steps(p), t1 - t0, d.rewritten);
    syl_string_free(s);
    syl_program_free(p);
    return status;
}
