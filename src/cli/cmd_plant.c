/* sylva FILE: the one-command way — write out/NAME.png and out/NAME.glb. */
#include <errno.h>
#include <getopt.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "sylva/render.h"

static const char usage[] =
    "usage: sylva FILE[:Model] [options]\n"
    "\n"
    "Derive the model, draw it, and write a picture and a mesh of it: DIR/NAME.png\n"
    "(1024x1024, as `sylva render` makes it) and DIR/NAME.glb (as `sylva mesh` makes it),\n"
    "NAME being the file's name without .syl (or Model, for FILE:Model). A grow block is\n"
    "grown (-n: years, at most 10000); a file with a scene, named without :Model, makes the\n"
    "whole scene (docs/growth.md).\n"
    "\n"
    "  --out DIR             where to write (default: out)\n"
    "  --view V              iso, front, side or top (default: chosen from the plant's shape)\n"
    "  --size WxH            picture size (default 1024x1024)\n"
    CLI_DERIVE_HELP
    CLI_GROW_LIMIT_HELP
    "\n"
    "Exit codes: 0 ok, 1 the model is wrong, 2 bad command line, 3 limit hit, 4 I/O error.\n";

enum { OPT_OUT = 1000, OPT_VIEW, OPT_SIZE };

int cmd_plant(int argc, char **argv) {
    static const struct option opts[] = {
        CLI_DERIVE_OPTIONS, CLI_GROW_LIMITS,
        {"out", required_argument, 0, OPT_OUT}, {"view", required_argument, 0, OPT_VIEW},
        {"size", required_argument, 0, OPT_SIZE}, {"help", no_argument, 0, 'h'}, {0, 0, 0, 0},
    };
    ModelArgs m = {0};
    SylDeriveOptions d = {.steps = -1, .diag = stderr};
    SylRenderOptions ro = {.diag = stderr, .view = SYL_VIEW_AUTO};
    const char *dir = "out";
    int c;
    optind = 1;
    while ((c = getopt_long(argc, argv, CLI_DERIVE_SHORT "h", opts, NULL)) != -1) {
        int done = cli_derive_option(c, optarg, &m, &d);
        if (done < 0) return SYL_EUSAGE;
        if (done) continue;
        switch (c) {
        case OPT_OUT: dir = optarg; break;
        case OPT_VIEW:
            if (!cli_view(optarg, &ro.view)) return SYL_EUSAGE;
            break;
        case OPT_SIZE:
            if (!cli_picture_size(optarg, &ro.width, &ro.height)) return SYL_EUSAGE;
            break;
        case 'h': fputs(usage, stdout); return SYL_OK;
        default: fputs(usage, stderr); return SYL_EUSAGE;
        }
    }
    if (optind != argc - 1) {
        fputs(usage, stderr);
        return SYL_EUSAGE;
    }
    if (mkdir(dir, 0777) && errno != EEXIST) {
        fprintf(stderr, "sylva: error: cannot make the directory '%s': %s\n", dir, strerror(errno));
        return SYL_EIO;
    }
    cli_model_spec(&m, argv[optind]);
    SylBudget *budget = syl_budget_new(d.max_memory); /* one --max-memory for every engine */
    d.budget = budget;
    SylMeshOptions mo = {.threads = d.threads, .diag = stderr, .budget = budget};
    ro.budget = budget;
    Plant pl;
    int status = cli_plant(&m, &d, &mo, &pl);
    if (status) {
        syl_budget_free(budget);
        return status;
    }
    char *png = cli_output_name(&m, dir, "png"), *glb = cli_output_name(&m, dir, "glb");
    if (!png || !glb) {
        fprintf(stderr, "sylva: error: out of memory\n");
        status = SYL_ELIMIT;
    }
    if (!status) status = syl_write_glb(pl.mesh, glb, stderr);
    if (!status) {
        Progress prog;
        cli_progress_start(&prog, "rendering");
        ro.threads = d.threads;
        ro.progress = cli_progress;
        ro.user = &prog;
        status = syl_render_png(pl.mesh, &ro, png);
    }
    if (!status) printf("%s\n%s\n", png, glb);
    free(png);
    free(glb);
    cli_plant_free(&pl);
    syl_budget_free(budget);
    return status;
}
