/* sylva FILE: the one-command way — write out/NAME.png and out/NAME.glb. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"
#include "sylva/render.h"

const CliCommand cli_plant_command = {
    .name = "FILE",
    .what = "write out/NAME.png and out/NAME.glb",
    .run = cmd_plant,
    .usage = "sylva FILE[:Model] [options]",
    .about = "Derive the model, draw it, and write a picture and a mesh of it: DIR/NAME.png\n"
             "(1024x1024, as `sylva render` makes it) and DIR/NAME.glb (as `sylva mesh` makes it),\n"
             "NAME being the file's name without .syl (or Model, for FILE:Model). A grow block is\n"
             "grown (-n: years, at most 10000); a file with a scene, named without :Model, makes the\n"
             "whole scene (docs/growth.md).\n",
    .options = (const CliUse[]){
        {.option = CLI_OPT_OUT},
        {.option = CLI_OPT_VIEW, .help = "iso, front, side or top (default: chosen from the plant's shape)"},
        {.option = CLI_OPT_SIZE},
        {.group = cli_derive_uses},
        {.group = cli_grow_limits},
        {0},
    },
    .epilogue = "\n" CLI_EXIT_CODES,
};

int cmd_plant(int argc, char **argv) {
    ModelArgs m = {0};
    SylDeriveOptions d = {.steps = -1, .diag = stderr};
    SylRenderOptions ro = {.diag = stderr, .view = SYL_VIEW_AUTO};
    CliArgs a = {.m = &m, .d = &d, .ro = &ro, .dir = "out"};
    int done = cli_parse(&cli_plant_command, argc, argv, &a);
    if (done != CLI_RUN) return done;
    const char *dir = a.dir;
    if (mkdir(dir, 0777) && errno != EEXIST) {
        fprintf(stderr, "sylva: error: cannot make the directory '%s': %s\n", dir, strerror(errno));
        return SYL_EIO;
    }
    cli_model_spec(&m, a.files[0]);
    SylBudget *budget = syl_budget_new(d.max_memory); /* one --max-memory for every engine */
    d.budget = budget;
    SylMeshOptions mo = {.threads = d.threads, .diag = stderr, .budget = budget, .one_sided = 1}; /* for the .glb */
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
    if (!status) status = syl_mesh_write_glb(pl.mesh, glb, &cli_sink);
    if (!status) {
        Progress prog;
        cli_progress_start(&prog, "rendering");
        ro.threads = d.threads;
        ro.progress = cli_progress;
        ro.user = &prog;
        status = syl_render_write_png(pl.mesh, &ro, png);
    }
    if (!status) printf("%s\n%s\n", png, glb);
    free(png);
    free(glb);
    cli_plant_free(&pl);
    syl_budget_free(budget);
    return status;
}
