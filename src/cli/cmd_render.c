/* sylva render: derive a model, draw it, mesh it and ray-trace a PNG picture. */
#include <getopt.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "sylva/mesh.h"
#include "sylva/render.h"

static const char usage[] =
    "usage: sylva render FILE[:Model] [-o OUT.png] [options]\n"
    "\n"
    "Derive the model, draw it with the 3D turtle, mesh it and ray-trace a picture: sunlight\n"
    "with shadows, sky light with ambient occlusion, a grass ground, procedural bark, leaf\n"
    "and flower textures, the camera framed so the plant fills about 80% of the picture.\n"
    "The picture never depends on the number of threads.\n"
    "\n"
    "  -o, --output FILE     the PNG file (default: the model's name with .png, in the\n"
    "                        current directory; - is standard output)\n"
    "  --view V              iso (from 35 degrees up, 45 around), front (looking along -Z),\n"
    "                        side (along -X) or top (down from +Y); default: front for a\n"
    "                        plant drawn in a plane, iso otherwise\n"
    "  --size WxH            picture size in pixels, 1 to 16384 each (default 1024x1024)\n"
    "  --samples N           anti-aliasing samples per pixel, 1 to 64 (default 4)\n"
    "  --ao N                ambient occlusion rays per pixel, 0 (none) to 64 (default 8)\n"
    "  --no-shadows          no sun shadows\n"
    "  --stats               print counts and times to stderr\n"
    CLI_DERIVE_HELP
    "\n"
    "A progress bar is shown on stderr when it is a terminal and the picture takes more than\n"
    "a second.\n"
    "\n"
    "Exit codes: 0 ok, 1 the model is wrong, 2 bad command line, 3 limit hit, 4 I/O error.\n";

enum { OPT_VIEW = 1000, OPT_SIZE, OPT_SAMPLES, OPT_AO, OPT_NO_SHADOWS, OPT_STATS };

int cmd_render(int argc, char **argv) {
    static const struct option opts[] = {
        CLI_DERIVE_OPTIONS,
        {"output", required_argument, 0, 'o'},        {"view", required_argument, 0, OPT_VIEW},
        {"size", required_argument, 0, OPT_SIZE},      {"samples", required_argument, 0, OPT_SAMPLES},
        {"ao", required_argument, 0, OPT_AO},          {"no-shadows", no_argument, 0, OPT_NO_SHADOWS},
        {"stats", no_argument, 0, OPT_STATS},
        {"help", no_argument, 0, 'h'},                 {0, 0, 0, 0},
    };
    ModelArgs m = {0};
    SylDeriveOptions d = {.steps = -1, .diag = stderr};
    SylRenderOptions ro = {.diag = stderr, .view = SYL_VIEW_AUTO};
    const char *output = NULL;
    bool stats = false;
    double v;
    int c;
    optind = 1;
    while ((c = getopt_long(argc, argv, CLI_DERIVE_SHORT "o:h", opts, NULL)) != -1) {
        int done = cli_derive_option(c, optarg, &m, &d);
        if (done < 0) return SYL_EUSAGE;
        if (done) continue;
        switch (c) {
        case 'o': output = optarg; break;
        case OPT_VIEW:
            if (!cli_view(optarg, &ro.view)) return SYL_EUSAGE;
            break;
        case OPT_SIZE:
            if (!cli_picture_size(optarg, &ro.width, &ro.height)) return SYL_EUSAGE;
            break;
        case OPT_SAMPLES:
            if (!cli_integer("--samples", optarg, 1, 64, &v)) return SYL_EUSAGE;
            ro.samples = (int)v;
            break;
        case OPT_AO:
            if (!cli_integer("--ao", optarg, 0, 64, &v)) return SYL_EUSAGE;
            ro.ao_samples = v > 0 ? (int)v : -1;
            break;
        case OPT_NO_SHADOWS: ro.shadows = -1; break;
        case OPT_STATS: stats = true; break;
        case 'h': fputs(usage, stdout); return SYL_OK;
        default: fputs(usage, stderr); return SYL_EUSAGE;
        }
    }
    if (optind != argc - 1) {
        fprintf(stderr, "sylva render: expects one model file\n%s", usage);
        return SYL_EUSAGE;
    }
    ro.threads = d.threads;
    int status = SYL_OK;
    Plant pl = {0};
    SylMesh *mesh = NULL;
    double t3;
    char *out_path = NULL;
    cli_model_spec(&m, argv[optind]);
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
            status = syl_render(mesh, &ro, rgb);
            t5 = cli_now();
            if (!status) status = syl_write_png(out_path, rgb, w, h, stderr);
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
