/* sylva render: derive a model, draw it, mesh it and ray-trace a PNG picture. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli.h"
#include "sylva/mesh.h"
#include "sylva/render.h"

const CliCommand cli_render_command = {
    .name = "render",
    .what = "draw a model and ray-trace a PNG picture of it",
    .run = cmd_render,
    .usage = "sylva render FILE[:Model] [-o OUT.png] [options]",
    .about = "Derive the model, draw it with the 3D turtle, mesh it and ray-trace a picture: sunlight\n"
             "with shadows, sky light with ambient occlusion, a grass ground, procedural bark, leaf\n"
             "and flower textures, the camera framed so the plant fills about 80% of the picture.\n"
             "The picture never depends on the number of threads.\n"
             "\n"
             "With --plants DIR/plants-YEAR.csv, FILE is an ecosystem block and the picture is its\n"
             "snapshot: the plant table that `sylva ecosystem` wrote, rendered as its view-YEAR.png\n"
             "(the same bytes for the same --view, --size, --samples and --no-shadows). Under\n"
             "`mpirun -np N` (a build with MPI) the picture's rows are split over the ranks and\n"
             "gathered by rank 0, which writes the same PNG (docs/distributed.md).\n",
    .options = (const CliUse[]){
        {.option = CLI_OPT_OUTPUT,
         .help = "the PNG file (default: the model's name with .png, in the\n"
                 "current directory; - is standard output)"},
        {.option = CLI_OPT_RENDER_VIEW,
         .help = "iso (from 35 degrees up, 45 around), front (looking along -Z),\n"
                 "side (along -X) or top (down from +Y); default: front for a\n"
                 "plant drawn in a plane, otherwise eye level (6 degrees up, 45\n"
                 "around: the trunk under the crown, the horizon above the middle).\n"
                 "With --plants: bird\n"
                 "(default) or walker, as sylva ecosystem --view"},
        {.option = CLI_OPT_SIZE, .help = "picture size in pixels, 1 to 16384 each (default 1024x1024;\n"
                                         "with --plants 1280x720)"},
        {.option = CLI_OPT_SAMPLES},
        {.option = CLI_OPT_AO},
        {.option = CLI_OPT_NO_SHADOWS},
        {.option = CLI_OPT_STATS},
        {.option = CLI_OPT_PLANTS},
        {.option = CLI_OPT_GLB, .help = "with --plants, also write the snapshot as OUT.glb (the terrain\n"
                                        "and the plants instanced, as sylva ecosystem --glb)"},
        {.group = cli_derive_uses},
        {0},
    },
    .epilogue = "\nA progress bar is shown on stderr when it is a terminal and the picture takes more than\n"
                "a second.\n\n" CLI_EXIT_CODES,
    .args_error = "expects one model file",
};

int cmd_render(int argc, char **argv) {
    ModelArgs m = {0};
    SylDeriveOptions d = {.steps = -1, .diag = stderr};
    SylRenderOptions ro = {.diag = stderr, .view = SYL_VIEW_AUTO};
    CliArgs a = {.m = &m, .d = &d, .ro = &ro};
    int done = cli_parse(&cli_render_command, argc, argv, &a);
    if (done != CLI_RUN) return done;
    ro.threads = d.threads;
    if (a.plants) return cli_render_snapshot(&a, &m, &d, &ro);
    if (a.eco_view_set || a.glb) {
        fprintf(stderr, "sylva: error: %s renders an ecosystem snapshot: give its plant table, --plants CSV\n",
                a.glb ? "--glb" : "--view bird|walker");
        return SYL_EUSAGE;
    }
    const char *output = a.output;
    bool stats = a.stats;
    ro.threads = d.threads;
    int status = SYL_OK;
    Plant pl = {0};
    SylMesh *mesh = NULL;
    double t3;
    char *out_path = NULL;
    cli_model_spec(&m, a.files[0]);
    out_path = output ? strdup(output) : cli_output_name(&m, NULL, "png");
    SylBudget *budget = syl_budget_new(d.max_memory); /* one --max-memory for every engine */
    d.budget = budget;
    SylMeshOptions mo = {.threads = d.threads, .diag = stderr, .budget = budget};
    ro.budget = budget;
    status = cli_plant(&m, &d, &mo, &pl);
    if (status) {
        free(out_path);
        syl_budget_free(budget);
        return status;
    }
    mesh = pl.mesh;
    t3 = cli_now();
    if (!out_path && !status) {
        fprintf(stderr, "sylva: error: out of memory\n");
        status = SYL_ELIMIT;
    }
    Progress prog;
    cli_progress_start(&prog, "rendering");
    ro.progress = cli_progress;
    ro.user = &prog;
    double t4 = t3, t5 = t3;
    if (!status) {
        int w = ro.width ? ro.width : 1024, h = ro.height ? ro.height : 1024;
        uint8_t *rgb = malloc((size_t)w * (size_t)h * 3);
        if (!rgb) {
            fprintf(stderr, "sylva: error: out of memory for a %dx%d picture\n", w, h);
            status = SYL_ELIMIT;
        } else {
            t4 = cli_now();
            status = syl_render_draw_mesh(mesh, &ro, rgb);
            t5 = cli_now();
            if (!status) status = syl_png_write(out_path, rgb, w, h, &cli_sink);
            free(rgb);
        }
    }
    double t6 = cli_now();
    if (!status && stats) {
        fprintf(stderr, "modules: %zu\nderive time: %.6f s\nturtle time: %.6f s\nmesh time: %.6f s\n",
                    pl.modules, pl.derive_s, pl.turtle_s, pl.mesh_s);
        fprintf(stderr, "vertices: %zu\ntriangles: %zu\n", mesh->nverts, mesh->nidx / 3);
        fprintf(stderr, "render time: %.6f s\nwrite time: %.6f s\npeak memory: %.2f MB\n", t5 - t4, t6 - t5,
                cli_peak_mb());
    }
    free(out_path);
    cli_plant_free(&pl);
    syl_budget_free(budget);
    return status;
}
