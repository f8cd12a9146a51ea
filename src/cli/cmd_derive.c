/* sylva derive: print the derived string. */
#include <stdlib.h>
#include <string.h>

#include "cli/testfaults.h"
#include "cli/cli.h"

const CliCommand cli_derive_command = {
    .name = "derive",
    .what = "derive a model and print the resulting string",
    .run = cmd_derive,
    .usage = "sylva derive FILE[:Model] [options]",
    .about = "Derive the model and print the final string in canonical form: modules one after\n"
             "another, parameters in parentheses printed with %g and separated by commas.\n",
    .options = (const CliUse[]){
        {.option = CLI_OPT_STEPS},
        {.option = CLI_OPT_INTERPRET},
        {.option = CLI_OPT_STATS, .help = "print module counts, time and peak memory to stderr"},
        {.option = CLI_OPT_QUIET},
        {.option = CLI_OPT_OUTPUT},
        {.group = cli_derive_uses},
        {0},
    },
    .epilogue = "\n" CLI_EXIT_CODES,
    .args_error = "expects one model file",
};

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

/* The passes split among threads (docs/architecture.md, "Threads"): what their chunks and joins
 * cost, and the schedule on as many free cores as chunks, where each pass takes its longest
 * chunk and its longest copy, and the rest of the run (on the calling thread) stays as it is. */
static void print_split(const SylDeriveOptions *d, double cpu) {
    if (!d->split_passes) return;
    double ms = 1e-6, chunks = (double)d->chunk_ns * ms, cmax = (double)d->chunk_max_ns * ms;
    double joins = (double)d->join_ns * ms, jmax = (double)d->join_max_ns * ms;
    double sched = cpu * 1e3 - (chunks - cmax) - (joins - jmax);
    fprintf(stderr, "split passes: %llu, chunks %.3f ms (longest of each pass: %.3f), joins %.3f ms (%.3f)\n",
            (unsigned long long)d->split_passes, chunks, cmax, joins, jmax);
    fprintf(stderr, "schedule on free cores: %.3f ms\n", sched);
}

static void print_stats(const SylProgram *p, const SylString *s, int steps, double seconds, double cpu,
                        uint64_t rewritten) {
    int ns = syl_program_symbol_count(p);
    uint64_t *counts = calloc((size_t)ns, sizeof *counts);
    size_t n = syl_string_length(s);
    fprintf(stderr, "steps: %d\nmodules: %zu\nderive time: %.6f s\nderive cpu time: %.6f s\n", steps, n, seconds, cpu);
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
    ModelArgs m = {0};
    SylDeriveOptions d = {.steps = -1, .diag = stderr};
    CliArgs a = {.m = &m, .d = &d};
    int done = cli_parse(&cli_derive_command, argc, argv, &a);
    if (done != CLI_RUN) return done;
    d.split_ns = cli_test_split_ns();
    const char *output = a.output;
    bool all_steps = a.steps, interpret = a.interpret, stats = a.stats, quiet = a.quiet;
    if (all_steps && interpret) {
        fprintf(stderr, "sylva derive: --steps and --interpret do not go together\n");
        return SYL_EUSAGE;
    }
    cli_model_spec(&m, a.files[0]);
    int status;
    SylProgram *p = cli_compile(&m, SYL_WARN_MISTAKES, &status);
    if (!p) return status;
    OutFile out;
    if (!out_open(&out, output)) {
        syl_program_free(p);
        return SYL_EIO;
    }
    SylBudget *budget = syl_budget_new(d.max_memory); /* one --max-memory for every engine */
    d.budget = budget;

    StepPrinter sp = {.p = p, .out = out.f};
    if (all_steps && !quiet) {
        d.on_step = print_step;
        d.user = &sp;
    }
    SylString *s = NULL;
    double t0 = cli_now(), c0 = cli_cpu_now();
    SylEnvStandalone *alone = syl_env_standalone_new(p, d.diag ? &(SylSink){syl_diagnostic_print, d.diag} : NULL); /* the plant alone, for ?E */
    d.queries = syl_env_standalone_ops();
    d.queries_user = alone;
    status = alone ? syl_derive(p, &d, &s) : SYL_ELIMIT;
    if (!alone) fprintf(stderr, "sylva: error: out of memory\n");
    syl_env_standalone_free(alone);
    double t1 = cli_now(), c1 = cli_cpu_now();
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
    status = out_close(&out, status);
    if (!status && stats) {
        print_stats(p, s, d.steps >= 0 ? d.steps : syl_program_steps(p), t1 - t0, c1 - c0, d.rewritten);
        print_split(&d, c1 - c0);
    }
    syl_string_free(s);
    syl_program_free(p);
    syl_budget_free(budget);
    return status;
}
