/* sylva grow: grow a self-organizing tree (a `grow` block) or a file's scene, and write a
 * picture, a mesh or a skeleton of it; --stats times every phase. */
#include <errno.h>
#include <getopt.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "cli.h"

static const char usage[] =
    "usage: sylva grow FILE[:Model] [options]\n"
    "\n"
    "Grow the model's tree year by year (docs/growth.md) — or, for a file with a scene and\n"
    "no Model named, every plant of the scene in one shared environment — and write it.\n"
    "Without -o: DIR/NAME.png and DIR/NAME.glb, as `sylva FILE` does.\n"
    "\n"
    "  -o, --output FILE     one file, by its extension: .png (picture), .glb .obj .ply\n"
    "                        (mesh), .csv .json (skeleton)\n"
    "  --out DIR             where to write without -o (default: out)\n"
    "  --years N             years to grow (default: the model's `years`; a scene: each\n"
    "                        plant's)\n"
    "  --seed S              random seed (a scene: S + the plant's number)\n"
    "  --set NAME=VALUE      override a `param` of the model (repeatable)\n"
    "  -j, --threads N       threads (default: all cores); the result never depends on N\n"
    CLI_GROW_LIMIT_HELP
    CLI_LIMIT_HELP
    "  --view V              iso, front, side or top (default: chosen from the shape)\n"
    "  --size WxH            picture size (default 1024x1024)\n"
    "  --stats               print counts and the time of every phase to stderr\n"
    "\n"
    "Exit codes: 0 ok, 1 the model is wrong, 2 bad command line, 3 limit hit, 4 I/O error.\n";

enum { OPT_OUT = 1000, OPT_YEARS, OPT_VIEW, OPT_SIZE, OPT_STATS };

typedef enum { W_DEFAULT, W_PNG, W_MESH, W_CSV, W_JSON } What;

static What what_of(const char *path) {
    const char *dot = strrchr(path, '.');
    if (!dot || strchr(dot, '/')) return W_DEFAULT;
    if (!strcasecmp(dot, ".png")) return W_PNG;
    if (!strcasecmp(dot, ".glb") || !strcasecmp(dot, ".obj") || !strcasecmp(dot, ".ply")) return W_MESH;
    if (!strcasecmp(dot, ".csv")) return W_CSV;
    if (!strcasecmp(dot, ".json")) return W_JSON;
    return W_DEFAULT;
}

static void print_stats(const Plant *pl, double write_s) {
    const SylGrowStats *g = &pl->grow;
    fprintf(stderr, "plants: %d\nyears: %d\nmetamers: %llu\ngrown: %llu\nbuds: %llu\n", g->plants, g->years,
            (unsigned long long)g->metamers, (unsigned long long)g->grown, (unsigned long long)g->buds);
    fprintf(stderr, "shed branches: %llu\nshed metamers: %llu\norgans: %llu\n", (unsigned long long)g->shed_branches,
            (unsigned long long)g->shed_metamers, (unsigned long long)g->organs);
    fprintf(stderr, "light time: %.6f s\nspace time: %.6f s\nallocation time: %.6f s\ngrowth time: %.6f s\n",
            g->light_s, g->space_s, g->alloc_s, g->growth_s);
    if (g->rule_shoots)
        fprintf(stderr, "rule shoots: %llu\nrule time: %.6f s\n", (unsigned long long)g->rule_shoots, g->rule_s);
    fprintf(stderr, "shedding time: %.6f s\nother time: %.6f s\ngrow time: %.6f s\n", g->shed_s, g->other_s,
            g->total_s);
    fprintf(stderr, "internodes/s: %.0f\n", g->total_s > 0 ? (double)g->grown / g->total_s : 0.0);
    if (pl->mesh)
        fprintf(stderr, "triangles: %zu\nmesh time: %.6f s\n", pl->mesh->nidx / 3, pl->mesh_s);
    fprintf(stderr, "write time: %.6f s\npeak memory: %.1f MB\n", write_s, cli_peak_mb());
}

static int write_skeleton(const SylSkeleton *sk, const char *path, bool json) {
    OutFile o;
    if (!out_open(&o, path)) return SYL_EIO;
    int st = json ? syl_skeleton_write_json(sk, o.f) : syl_skeleton_write_csv(sk, o.f);
    return out_close(&o, st);
}

static int render(const Plant *pl, SylRenderOptions *ro, const char *path) {
    Progress prog;
    cli_progress_start(&prog, "rendering");
    ro->progress = cli_progress;
    ro->user = &prog;
    return syl_render_png(pl->mesh, ro, path);
}

int cmd_grow(int argc, char **argv) {
    static const struct option opts[] = {
        {"output", required_argument, 0, 'o'},   {"out", required_argument, 0, OPT_OUT},
        {"years", required_argument, 0, OPT_YEARS}, {"seed", required_argument, 0, 's'},
        {"set", required_argument, 0, 'S'},      {"threads", required_argument, 0, 'j'},
        CLI_LIMIT_OPTIONS,                       CLI_GROW_LIMITS,
        {"view", required_argument, 0, OPT_VIEW},
        {"size", required_argument, 0, OPT_SIZE}, {"stats", no_argument, 0, OPT_STATS},
        {"help", no_argument, 0, 'h'},           {0, 0, 0, 0},
    };
    ModelArgs m = {0};
    SylDeriveOptions d = {.steps = -1, .diag = stderr};
    SylRenderOptions ro = {.diag = stderr, .view = SYL_VIEW_AUTO};
    const char *output = NULL, *dir = "out";
    bool stats = false;
    double v;
    int c;
    optind = 1;
    while ((c = getopt_long(argc, argv, "o:j:h", opts, NULL)) != -1) {
        if (c != 'n') { /* grow counts years with --years */
            int done = cli_derive_option(c, optarg, &m, &d);
            if (done < 0) return SYL_EUSAGE;
            if (done) continue;
        }
        switch (c) {
        case 'o': output = optarg; break;
        case OPT_OUT: dir = optarg; break;
        case OPT_YEARS:
            if (!cli_integer("--years", optarg, 0, SYL_GROW_MAX_YEARS, &v)) return SYL_EUSAGE;
            d.steps = (int)v;
            break;
        case OPT_VIEW:
            if (!cli_view(optarg, &ro.view)) return SYL_EUSAGE;
            break;
        case OPT_SIZE:
            if (!cli_picture_size(optarg, &ro.width, &ro.height)) return SYL_EUSAGE;
            break;
        case OPT_STATS: stats = true; break;
        case 'h': fputs(usage, stdout); return SYL_OK;
        default: fputs(usage, stderr); return SYL_EUSAGE;
        }
    }
    if (optind != argc - 1) {
        fprintf(stderr, "sylva grow: expects one model file\n%s", usage);
        return SYL_EUSAGE;
    }
    What what = output ? what_of(output) : W_DEFAULT;
    if (output && what == W_DEFAULT) {
        fprintf(stderr, "sylva: error: cannot tell the format of '%s': name it *.png, *.glb, *.obj, *.ply, *.csv "
                        "or *.json\n", output);
        return SYL_EUSAGE;
    }
    if (!output && mkdir(dir, 0777) && errno != EEXIST) {
        fprintf(stderr, "sylva: error: cannot make the directory '%s': %s\n", dir, strerror(errno));
        return SYL_EIO;
    }
    cli_model_spec(&m, argv[optind]);
    SylBudget *budget = syl_budget_new(d.max_memory); /* one --max-memory for every engine */
    d.budget = budget;
    SylMeshOptions mo = {.threads = d.threads, .diag = stderr, .budget = budget};
    ro.threads = d.threads;
    ro.budget = budget;
    Plant pl;
    int status = cli_plant(&m, &d, what == W_CSV || what == W_JSON ? NULL : &mo, &pl);
    if (status) {
        syl_budget_free(budget);
        return status;
    }
    if (!pl.grown) {
        fprintf(stderr, "sylva: error: '%s' is an lsystem, not a grow block: draw it with `sylva %s`\n", pl.name,
                m.spec);
        cli_plant_free(&pl);
        syl_budget_free(budget);
        return SYL_EUSAGE;
    }
    double t0 = cli_now();
    if (what == W_PNG) status = render(&pl, &ro, output);
    else if (what == W_MESH) status = syl_write_mesh(pl.mesh, output, stderr);
    else if (what == W_CSV || what == W_JSON) status = write_skeleton(pl.sk, output, what == W_JSON);
    else {
        char *png = cli_output_name(&m, dir, "png"), *glb = cli_output_name(&m, dir, "glb");
        if (!png || !glb) {
            fprintf(stderr, "sylva: error: out of memory\n");
            status = SYL_ELIMIT;
        }
        if (!status) status = syl_write_glb(pl.mesh, glb, stderr);
        if (!status) status = render(&pl, &ro, png);
        if (!status) printf("%s\n%s\n", png, glb);
        free(png);
        free(glb);
    }
    if (!status && stats) print_stats(&pl, cli_now() - t0);
    cli_plant_free(&pl);
    syl_budget_free(budget);
    return status;
}
