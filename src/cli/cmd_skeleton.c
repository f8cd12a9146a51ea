/* sylva skeleton: derive a model, draw it with the turtle and export the skeleton. */
#include <getopt.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "sylva/skeleton.h"

static const char usage[] =
    "usage: sylva skeleton FILE[:Model] [options]\n"
    "\n"
    "Derive the model, apply its `interpret` rules, draw the string with the 3D turtle\n"
    "(docs/turtle.md) and write the skeleton: one row per node (segment ends and roots),\n"
    "then one per organ, with the columns id,parent,x,y,z,radius,order,kind.\n"
    "\n"
    "  -o, --output FILE     write to FILE: CSV for *.csv, JSON for *.json\n"
    "                        (default: CSV on standard output)\n"
    "  --format csv|json     the format, whatever the file name\n"
    "  --stats               print counts, bounds and times to stderr\n"
    CLI_DERIVE_HELP
    "\n"
    "Exit codes: 0 ok, 1 the model is wrong, 2 bad command line, 3 limit hit, 4 I/O error.\n";

enum { FMT_NONE, FMT_CSV, FMT_JSON };

static int format_named(const char *name) {
    if (!strcmp(name, "csv")) return FMT_CSV;
    if (!strcmp(name, "json")) return FMT_JSON;
    return FMT_NONE;
}

/* The format a file name asks for, by its extension. */
static int format_of(const char *path) {
    const char *dot = strrchr(path, '.');
    if (!dot || strchr(dot, '/')) return FMT_NONE;
    char ext[8];
    size_t n = strlen(dot + 1);
    if (n >= sizeof ext) return FMT_NONE;
    for (size_t i = 0; i <= n; i++) ext[i] = (char)(dot[1 + i] >= 'A' && dot[1 + i] <= 'Z' ? dot[1 + i] + 32 : dot[1 + i]);
    return format_named(ext);
}

static void print_stats(const SylSkeleton *sk, size_t modules, double derive_s, double turtle_s) {
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
    fprintf(stderr, "derive time: %.6f s\nturtle time: %.6f s\npeak memory: %.2f MB\n", derive_s, turtle_s,
            cli_peak_mb());
}

int cmd_skeleton(int argc, char **argv) {
    static const struct option opts[] = {
        CLI_DERIVE_OPTIONS,
        {"output", required_argument, 0, 'o'}, {"format", required_argument, 0, 'f'},
        {"stats", no_argument, 0, 't'},        {"help", no_argument, 0, 'h'},
        {0, 0, 0, 0},
    };
    ModelArgs m = {0};
    SylDeriveOptions d = {.steps = -1, .diag = stderr};
    const char *output = NULL;
    int format = FMT_NONE;
    bool stats = false;
    int c;
    optind = 1;
    while ((c = getopt_long(argc, argv, CLI_DERIVE_SHORT "o:h", opts, NULL)) != -1) {
        int done = cli_derive_option(c, optarg, &m, &d);
        if (done < 0) return SYL_EUSAGE;
        if (done) continue;
        switch (c) {
        case 'o': output = optarg; break;
        case 'f':
            format = format_named(optarg);
            if (!format) {
                fprintf(stderr, "sylva: error: --format expects csv or json, not '%s'\n", optarg);
                return SYL_EUSAGE;
            }
            break;
        case 't': stats = true; break;
        case 'h': fputs(usage, stdout); return SYL_OK;
        default: fputs(usage, stderr); return SYL_EUSAGE;
        }
    }
    if (optind != argc - 1) {
        fprintf(stderr, "sylva skeleton: expects one model file\n%s", usage);
        return SYL_EUSAGE;
    }
    if (!format) {
        format = output && strcmp(output, "-") ? format_of(output) : FMT_CSV;
        if (!format) {
            fprintf(stderr, "sylva: error: cannot tell the format of '%s': name it *.csv or *.json, or use --format\n",
                    output);
            return SYL_EUSAGE;
        }
    }
    cli_model_spec(&m, argv[optind]);
    SylBudget *budget = syl_budget_new(d.max_memory); /* one --max-memory for every engine */
    d.budget = budget;
    Plant pl;
    int status = cli_plant(&m, &d, NULL, &pl);
    if (!status) {
        OutFile out;
        if (!out_open(&out, output)) status = SYL_EIO;
        else {
            SylSkeleton *sk = pl.sk;
            status = format == FMT_JSON ? syl_skeleton_write_json(sk, out.f) : syl_skeleton_write_csv(sk, out.f);
            status = out_close(&out, status);
            if (!status && stats) print_stats(sk, pl.modules, pl.derive_s, pl.turtle_s);
        }
    }
    cli_plant_free(&pl);
    syl_budget_free(budget);
    return status;
}
