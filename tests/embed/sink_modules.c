/* The modules that work on no program reach the embedder's sink too: one error of each (an
 * output path that cannot be written, a picture size out of range, a DEM that is not one, an
 * OBJ with a bad number, a checkpoint that does not read, a level of detail the renderer
 * refuses, ...), provoked with only a sink
 * given and no FILE * anywhere; fd 2 goes to ERRFILE, which must stay empty.
 *   sink_modules MODEL.syl ECOSYSTEM.syl BAD_DEM_ECOSYSTEM.syl DIR ERRFILE
 * MODEL: an L-system that draws; ECOSYSTEM: an ecosystem block with a good DEM;
 * BAD_DEM_ECOSYSTEM: one whose DEM is not a DEM; DIR: a folder to write bad inputs into.
 * Then the calls that work on a program compiled without a sink and take one themselves: an
 * ecosystem's read, check and DEM check, the stand-alone environment of ?E, and a forest
 * whose species' look cannot be one. Run from the source tree (examples/ecosystem/meadow.asc).
 * Prints a line per module, "MODULE STATUS RECORDS LINE: MESSAGE" (the records the call made,
 * the first one's line and message), then "done". */
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <sylva/ecosystem.h>
#include <sylva/forest.h>
#include <sylva/impostor.h>
#include <sylva/metrics.h>
#include <sylva/plant.h>
#include <sylva/render.h>
#include <sylva/terrain.h>
#include <sylva/texture.h>
#include <sylva/sylva.h>
#include <sylva/wind.h>

typedef struct Heard {
    int records, line;
    char first[512];
} Heard;

static void report(void *user, const SylDiagnostic *d) {
    Heard *h = user;
    if (!h->records++) {
        snprintf(h->first, sizeof h->first, "%s", d->message);
        h->line = d->line;
    }
}

static Heard heard;
static const SylSink sink = {report, &heard};

static void said(const char *module, int status) {
    printf("%s %d %d %d: %s\n", module, status, heard.records, heard.line, heard.first);
    heard = (Heard){0};
}

static void put(const char *dir, const char *name, const char *text, char *path, size_t n) {
    snprintf(path, n, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f) exit(2);
    fputs(text, f);
    fclose(f);
}

int main(int argc, char **argv) {
    if (argc != 6) return 2;
    const char *dir = argv[4];
    int fd = open(argv[5], O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0 || dup2(fd, 2) < 0) return 2; /* whatever the library wrote to stderr lands here */
    close(fd);
    char path[4096];
    int st;

    SylProgram *p = syl_compile(argv[1], NULL, 0, &(SylCompileOptions){.sink = &sink}, &st);
    SylPlant pl;
    if (!p || syl_plant_build(p, &(SylPlantOptions){0}, &pl)) return 3;

    snprintf(path, sizeof path, "%s/no/such/folder/plant.glb", dir);
    said("writer", syl_mesh_write(pl.mesh, path, &sink));
    uint8_t px[3 * 4] = {0};
    snprintf(path, sizeof path, "%s/no/such/folder/picture.png", dir);
    said("png", syl_png_write(path, px, 2, 2, &sink));
    said("render", syl_render_draw_mesh(pl.mesh, &(SylRenderOptions){.width = -1, .sink = &sink}, px));
    SylBudget *tiny = syl_budget_new(1);
    SylImpostor imp;
    said("impostor", syl_impostor_bake(pl.mesh, &(SylImpostorOptions){.budget = tiny, .sink = &sink}, &imp));
    float *radius = calloc(pl.skeleton->nnodes + 1, sizeof *radius);
    SylWind w;
    said("wind", syl_wind_build(pl.skeleton, radius, &(SylWindOptions){.speed = 1, .budget = tiny, .sink = &sink}, &w));
    said("wind-options", syl_wind_build(pl.skeleton, radius, &(SylWindOptions){.speed = -1, .sink = &sink}, &w));
    free(radius);
    /* the LOD check's renderer refusing a level (an index past its vertices), and an impostor
     * level for a chain whose LOD0 draws nothing */
    float three[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t past[3] = {0, 1, 7};
    SylMesh bad = {.pos = three, .nrm = three, .nverts = 3, .idx = past, .nidx = 3}, none = {0};
    SylLodChain chain = {.n = 2, .level = {{.mesh = pl.mesh}, {.mesh = &bad, .level = 1}}};
    SylLodSilhouette sil;
    said("lod-check", syl_lod_check_silhouette(&chain, 1, &(SylLodCheckOptions){.sink = &sink}, &sil));
    chain = (SylLodChain){.n = 1, .level = {{.mesh = &none}}};
    said("impostor-level", syl_impostor_add_level(&chain, pl.skeleton, &(SylMeshOptions){0},
                                                  &(SylImpostorOptions){.sink = &sink}, &imp));
    SylRenderOptions ro = {.width = 64, .height = 64};
    snprintf(path, sizeof path, "%s/snapshot.png", dir);
    said("snapshot", syl_ecosystem_render_snapshot(p, SYL_OK, &(SylSnapshotOptions){.plants = "plants.csv", .render = &ro,
                                                                                    .png = path, .sink = &sink}, NULL));
    pl.skeleton->nodes[0].parent = 0; /* its own parent: not before itself */
    SylMetrics mx;
    said("metrics", syl_metrics_compute(pl.skeleton, &(SylMetricsOptions){.mesh = pl.mesh, .sink = &sink}, &mx));
    syl_plant_free(&pl);
    syl_program_free(p);

    SylTerrain *t = NULL;
    put(dir, "dem.png", "not a PNG at all\n", path, sizeof path);
    said("terrain", syl_terrain_read(path, &(SylTerrainOptions){.sink = &sink}, &t));
    put(dir, "dem.obj", "v 0 0 0\nv 1 0 zero\n", path, sizeof path);
    said("obj", syl_terrain_read(path, &(SylTerrainOptions){.sink = &sink}, &t));
    put(dir, "state.ckpt", "not a checkpoint\n", path, sizeof path);
    SylEcoCheckpoint ck;
    said("checkpoint", syl_ecosystem_checkpoint_read(path, &ck, &sink));

    p = syl_compile(argv[2], NULL, 0, &(SylCompileOptions){.sink = &sink}, &st);
    static SylEcoModel m; /* large: off the stack */
    if (!p || syl_ecosystem_load(p, &(SylEcoOptions){.sink = &sink}, &m, &t)) return 4;
    said("simulation", syl_ecosystem_simulate(&m, t, &(SylEcoOptions){.tiles_x = 1 << 20, .sink = &sink}, NULL));
    snprintf(path, sizeof path, "%s/absent.csv", dir);
    SylEcoPlant *plants = NULL;
    size_t n = 0;
    said("table", syl_ecosystem_table_read(path, &m, t, &plants, &n, &sink));
    syl_terrain_free(t);
    syl_program_free(p);

    p = syl_compile(argv[3], NULL, 0, &(SylCompileOptions){.sink = &sink}, &st);
    if (!p) return 5;
    t = NULL;
    said("ecosystem-dem", syl_ecosystem_load(p, &(SylEcoOptions){0}, &m, &t));
    syl_terrain_free(t);
    syl_program_free(p);

    /* The calls that work on a program compiled without a sink take one themselves. */
    put(dir, "eco.syl", "ecosystem E {\n  latitude 100\n}\n", path, sizeof path);
    p = syl_compile(path, NULL, 0, NULL, &st);
    if (!p) return 6;
    said("ecosystem-read", syl_ecosystem_read(p, &m, &sink));
    said("ecosystem-validate", syl_ecosystem_validate(p, &sink));
    syl_program_free(p);
    p = syl_compile(argv[3], NULL, 0, NULL, &st);
    if (!p) return 7;
    said("ecosystem-terrain", syl_ecosystem_check_terrain(p, &sink));
    syl_program_free(p);
    put(dir, "grid.syl",
        "lsystem T {\n  axiom A\n  step 0.000001\n  derive 3\n"
        "  A -> F(1000000) [+F(1000000) ?E(0, 0) B] ?E(0, 0) B\n  B -> F(1000000) ?E(0, 0) B\n}\n",
        path, sizeof path);
    p = syl_compile(path, NULL, 0, NULL, &st);
    if (!p) return 8;
    SylEnvStandalone *alone = syl_env_standalone_new(p, &sink);
    SylString *str = NULL;
    said("standalone", syl_derive(p, &(SylDeriveOptions){.steps = -1, .queries = syl_env_standalone_ops(),
                                                        .queries_user = alone}, &str));
    syl_string_free(str);
    syl_env_standalone_free(alone);
    syl_program_free(p);
    /* a species whose look is another ecosystem: the forest refuses it, to its sink */
    FILE *f = fopen(argv[2], "r");
    char text[8192];
    size_t len = f ? fread(text, 1, sizeof text - 1, f) : 0;
    if (f) fclose(f);
    text[len] = 0;
    char *model = strstr(text, "  model ");
    if (!model) return 9;
    char *end = strchr(model, '\n');
    char eco[9000];
    snprintf(eco, sizeof eco, "%.*s  model Other%s\necosystem Other {\n}\n", (int)(model - text), text, end);
    snprintf(path, sizeof path, "%s/meadow.syl", dir);
    put(dir, "meadow.syl", eco, path, sizeof path);
    f = fopen("examples/ecosystem/meadow.asc", "r"); /* the DEM beside it */
    static char dem[1 << 20];
    len = f ? fread(dem, 1, sizeof dem - 1, f) : 0;
    if (f) fclose(f);
    dem[len] = 0;
    char dempath[4096];
    put(dir, "meadow.asc", dem, dempath, sizeof dempath);
    p = syl_compile(path, NULL, 0, &(SylCompileOptions){.model = "Meadow"}, &st);
    t = NULL;
    if (!p || syl_ecosystem_load(p, &(SylEcoOptions){.sink = &sink}, &m, &t)) return 11;
    SylForest *forest = NULL;
    said("forest", syl_forest_new(p, &m, t, &(SylForestOptions){.threads = 1, .sink = &sink}, &forest));
    syl_forest_free(forest);
    syl_terrain_free(t);
    syl_program_free(p);
    syl_budget_free(tiny);
    printf("done\n");
    return 0;
}
