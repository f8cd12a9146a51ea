/* sylva grow: grow a self-organizing tree (a `grow` block) or a file's scene, and write a
 * picture, a mesh or a skeleton of it; --stats times every phase. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "cli/cli.h"

const CliCommand cli_grow_command = {
    .name = "grow",
    .what = "grow a self-organizing tree or a scene; picture, mesh or skeleton",
    .run = cmd_grow,
    .usage = "sylva grow FILE[:Model] [options]",
    .about = "Grow the model's tree year by year (docs/growth.md) — or, for a file with a scene and\n"
             "no Model named, every plant of the scene in one shared environment — and write it.\n"
             "Without -o: DIR/NAME.png and DIR/NAME.glb, as `sylva FILE` does.\n",
    .options = (const CliUse[]){
        {.option = CLI_OPT_OUTPUT,
         .help = "one file, by its extension: .png (picture), .glb .obj .ply\n"
                 "(mesh), .csv .json (skeleton)"},
        {.option = CLI_OPT_OUT, .help = "where to write without -o (default: out)"},
        {.option = CLI_OPT_YEARS},
        {.option = CLI_OPT_SEED, .help = "random seed (a scene: S + the plant's number)"},
        {.option = CLI_OPT_SET},
        {.option = CLI_OPT_ALLOW_PATH},
        {.option = CLI_OPT_THREADS, .help = "threads (default: all cores); the result never depends on N"},
        {.group = cli_grow_limits},
        {.group = cli_limits},
        {.option = CLI_OPT_VIEW},
        {.option = CLI_OPT_SIZE},
        {.option = CLI_OPT_STATS, .help = "print counts and the time of every phase to stderr"},
        {0},
    },
    .epilogue = "\n" CLI_EXIT_CODES,
    .args_error = "expects one model file",
};

typedef enum { W_DEFAULT, W_PNG, W_MESH, W_CSV, W_JSON } What;

static What what_of(const char *path) {
    const char *dot = strrchr(path, '.');
    if (!dot || strchr(dot, '/')) return W_DEFAULT;
    if (!strcasecmp(dot, ".png")) return W_PNG;
    if (syl_mesh_format(path, NULL)) return W_MESH;
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
    return syl_render_write_png(pl->mesh, ro, path);
}

int cmd_grow(int argc, char **argv) {
    ModelArgs m = {0};
    SylDeriveOptions d = {.steps = -1, .diag = stderr};
    SylRenderOptions ro = {.diag = stderr, .view = SYL_VIEW_AUTO};
    CliArgs a = {.m = &m, .d = &d, .ro = &ro, .dir = "out"};
    int done = cli_parse(&cli_grow_command, argc, argv, &a);
    if (done != CLI_RUN) return done;
    const char *output = a.output, *dir = a.dir;
    bool stats = a.stats;
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
    cli_model_spec(&m, a.files[0]);
    SylBudget *budget = syl_budget_new(d.max_memory); /* one --max-memory for every engine */
    d.budget = budget;
    SylMeshOptions mo = {.threads = d.threads, .diag = stderr, .budget = budget};
    /* a .glb is written by default */
    mo.one_sided = what == W_DEFAULT || (what == W_MESH && (syl_mesh_format(output, NULL)->can & SYL_FORMAT_DOUBLE_SIDED));
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
    else if (what == W_MESH) status = syl_mesh_write(pl.mesh, output, &cli_sink);
    else if (what == W_CSV || what == W_JSON) status = write_skeleton(pl.sk, output, what == W_JSON);
    else {
        char *png = cli_output_name(&m, dir, "png"), *glb = cli_output_name(&m, dir, "glb");
        if (!png || !glb) {
            fprintf(stderr, "sylva: error: out of memory\n");
            status = SYL_ELIMIT;
        }
        if (!status) status = syl_mesh_write_glb(pl.mesh, glb, &cli_sink);
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
