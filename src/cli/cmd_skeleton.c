/* sylva skeleton: any model's skeleton (drawn, grown or built from parameters), exported. */
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "sylva/skeleton.h"
#include "util/clock.h"

const CliCommand cli_skeleton_command = {
    .name = "skeleton",
    .what = "build any model's skeleton and export it (CSV, JSON)",
    .run = cmd_skeleton,
    .usage = "sylva skeleton FILE[:Model] [options]",
    .about = "Build the model's skeleton and write it: an lsystem is derived, its `interpret` rules\n"
             "applied and its string drawn with the 3D turtle (docs/turtle.md); a grow block or a scene\n"
             "grows (-n years); a weber or strands block builds its tree from its parameters. One row\n"
             "per node (segment ends and roots), then one per organ, with the columns\n"
             "id,parent,x,y,z,radius,order,kind.\n",
    .options = (const CliUse[]){
        {.option = CLI_OPT_OUTPUT,
         .help = "write to FILE: CSV for *.csv, JSON for *.json\n"
                 "(default: CSV on standard output)"},
        {.option = CLI_OPT_FORMAT},
        {.option = CLI_OPT_STATS, .help = "print counts, bounds and times to stderr"},
        {.group = cli_derive_uses},
        {0},
    },
    .epilogue = "\n" CLI_EXIT_CODES,
    .args_error = "expects one model file",
};

/* The format a file name asks for, by its extension. */
static int format_of(const char *path) {
    const char *dot = strrchr(path, '.');
    if (!dot || strchr(dot, '/')) return CLI_FORMAT_NONE;
    char ext[8];
    size_t n = strlen(dot + 1);
    if (n >= sizeof ext) return CLI_FORMAT_NONE;
    for (size_t i = 0; i <= n; i++) ext[i] = (char)(dot[1 + i] >= 'A' && dot[1 + i] <= 'Z' ? dot[1 + i] + 32 : dot[1 + i]);
    return cli_format_named(ext);
}

static void print_stats(const SylSkeleton *sk, size_t modules, double derive_s, double turtle_s, double write_s,
                        double write_cpu) {
    float lo[3], hi[3];
    syl_skeleton_bounds(sk, lo, hi);
    size_t roots = 0;
    unsigned max_order = 0;
    for (size_t i = 0; i < sk->nnodes; i++) {
        roots += sk->nodes[i].kind == SYL_KIND_ROOT;
        if (sk->nodes[i].order > max_order) max_order = sk->nodes[i].order;
    }
    fprintf(stderr, "modules: %zu\nnodes: %zu (%zu roots)\norgans: %zu\npolygons: %zu\nmax order: %u\n", modules,
            sk->nnodes, roots, sk->norgans, sk->npolys, max_order);
    fprintf(stderr, "bounds: %g %g %g .. %g %g %g\n", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
    fprintf(stderr, "derive time: %.6f s\nturtle time: %.6f s\nwrite time: %.6f s (cpu %.6f s)\npeak memory: %.2f MB\n",
            derive_s, turtle_s, write_s, write_cpu, cli_peak_mb());
}

int cmd_skeleton(int argc, char **argv) {
    ModelArgs m = {0};
    SylDeriveOptions d = {.steps = -1, .diag = stderr};
    CliArgs a = {.m = &m, .d = &d};
    int done = cli_parse(&cli_skeleton_command, argc, argv, &a);
    if (done != CLI_RUN) return done;
    const char *output = a.output;
    int format = a.format;
    bool stats = a.stats;
    if (!format) {
        format = output && strcmp(output, "-") ? format_of(output) : CLI_FORMAT_CSV;
        if (!format) {
            fprintf(stderr, "sylva: error: cannot tell the format of '%s': name it *.csv or *.json, or use --format\n",
                    output);
            return SYL_EUSAGE;
        }
    }
    cli_model_spec(&m, a.files[0]);
    SylBudget *budget = syl_budget_new(d.max_memory); /* one --max-memory for every engine */
    d.budget = budget;
    Plant pl;
    int status = cli_plant(&m, &d, NULL, &pl);
    if (!status) {
        OutFile out;
        if (!out_open(&out, output)) status = SYL_EIO;
        else {
            SylSkeleton *sk = pl.sk;
            double w0 = clock_wall(), c0 = clock_cpu();
            status = format == CLI_FORMAT_JSON ? syl_skeleton_write_json(sk, out.f) : syl_skeleton_write_csv(sk, out.f);
            status = out_close(&out, status);
            if (!status && stats) print_stats(sk, pl.modules, pl.derive_s, pl.turtle_s, clock_wall() - w0, clock_cpu() - c0);
        }
    }
    cli_plant_free(&pl);
    syl_budget_free(budget);
    return status;
}
