/* sylva view: an ecosystem block, years of it. The simulation runs once per version of the
 * model (the library's syl_ecosystem_load and _simulate, as `sylva ecosystem` runs them), keeping
 * the yearly counts (species.csv's) and every year's plants; the page then scrubs the years:
 * each year's forest is the .glb syl_forest_write_glb writes (`sylva ecosystem --glb`), its
 * chart the counts, its maps the factors' PNGs of syl_terrain_write_map. */
#include <stdlib.h>
#include <string.h>

#include "cli/view.h"
#include "sylva/ecosystem.h"
#include "sylva/forest.h"
#include "sylva/impostor.h"
#include "sylva/stream.h"
#include "sylva/terrain.h"
#include "util/json.h"

/* The plants kept over all years; past it every other kept year is let go (the page then
 * scrubs in steps of 2, 4, ... years). */
enum { KEEP_PLANTS = 4000000 };

typedef struct EcoYear {
    int year;
    SylEcoPlant *plants;
    size_t n;
} EcoYear;

struct ViewEco {
    uint64_t key;               /* what it was run from (the model, text, seed, --set, gen) */
    SylProgram *p;
    SylEcoModel model;
    SylTerrain *t;
    SylForest *forest;
    SylBudget *budget;
    SylEcoYear *years;          /* the yearly counts, years[0 .. nyears) */
    int nyears, cap;
    EcoYear *kept;              /* the years' plants kept, by increasing year */
    int nkept, stride;
    size_t plants;              /* in kept */
    int last;                   /* the run's last year */
    char **imp;                 /* each look's impostor .glb (its billboards), made when asked */
    size_t *imp_len;
};

void view_eco_free(ViewEco *e) {
    if (!e) return;
    for (int k = 0; e->imp && k < syl_forest_looks(e->forest); k++) free(e->imp[k]);
    free(e->imp);
    free(e->imp_len);
    for (int i = 0; i < e->nkept; i++) free(e->kept[i].plants);
    free(e->kept);
    free(e->years);
    syl_forest_free(e->forest);
    syl_terrain_free(e->t);
    syl_budget_free(e->budget);
    syl_program_free(e->p);
    free(e);
}

static uint64_t fnv(uint64_t h, const void *data, size_t n) {
    const unsigned char *s = data;
    for (size_t i = 0; i < n; i++) h = (h ^ s[i]) * 1099511628211ull;
    return h;
}

/* Everything but the year: one simulation serves every year of it. */
static uint64_t eco_key(const View *v, const ViewRequest *rq, unsigned gen) {
    uint64_t h = fnv(1469598103934665603ull, &gen, sizeof gen);
    h = fnv(h, rq->model, strlen(rq->model) + 1);
    if (rq->text) h = fnv(h, rq->text, rq->text_len);
    h = fnv(h, &rq->use_seed, sizeof rq->use_seed);
    if (rq->use_seed) h = fnv(h, &rq->seed, sizeof rq->seed);
    for (int i = 0; i < rq->nsets; i++) {
        h = fnv(h, rq->sets[i].name, strlen(rq->sets[i].name) + 1);
        h = fnv(h, &rq->sets[i].value, sizeof rq->sets[i].value);
    }
    return fnv(h, &v->max_memory, sizeof v->max_memory);
}

static void on_year(void *user, const SylEcoYear *y) {
    ViewEco *e = user;
    if (e->nyears == e->cap) {
        int cap = e->cap ? 2 * e->cap : 64;
        SylEcoYear *n = realloc(e->years, (size_t)cap * sizeof *n);
        if (!n) return; /* the chart then ends early; on_snapshot reports the memory */
        e->years = n, e->cap = cap;
    }
    e->years[e->nyears++] = *y;
}

static int on_snapshot(void *user, int year, const SylEcoPlant *plants, size_t n) {
    ViewEco *e = user;
    if (year % e->stride && year != e->last) return SYL_OK;
    while (e->plants + n > KEEP_PLANTS && e->nkept > 1) { /* let every other kept year go */
        int k = 0;
        e->stride *= 2;
        e->plants = 0;
        for (int i = 0; i < e->nkept; i++) {
            if (e->kept[i].year % e->stride == 0) e->kept[k++] = e->kept[i], e->plants += e->kept[i].n;
            else free(e->kept[i].plants);
        }
        e->nkept = k;
        if (year % e->stride && year != e->last) return SYL_OK;
    }
    EcoYear *grown = realloc(e->kept, (size_t)(e->nkept + 1) * sizeof *grown);
    SylEcoPlant *copy = malloc((n ? n : 1) * sizeof *copy);
    if (!grown || !copy) return free(copy), SYL_ELIMIT;
    e->kept = grown;
    if (n) memcpy(copy, plants, n * sizeof *copy);
    e->kept[e->nkept++] = (EcoYear){year, copy, n};
    e->plants += n;
    return SYL_OK;
}

/* Read the block, its terrain and its species' looks, and run every year. */
static int eco_run(View *v, SylProgram *p, ViewEco *e, FILE *diag) {
    e->p = p;
    e->stride = 1;
    e->budget = syl_budget_new(v->max_memory);
    SylEcoOptions o = {.threads = v->threads, .budget = e->budget, .diag = diag, .on_year = on_year,
                       .on_snapshot = on_snapshot, .user = e, .max_plants = 100000000};
    int st = e->budget ? syl_ecosystem_load(p, &o, &e->model, &e->t) : SYL_ELIMIT;
    if (st) return st;
    e->last = e->model.years;
    int *every = malloc((size_t)(e->last > 0 ? e->last : 1) * sizeof *every);
    if (!every) return SYL_ELIMIT;
    for (int y = 0; y < e->last; y++) every[y] = y + 1;
    o.snapshots = every, o.nsnapshots = e->last;
    st = syl_forest_new(p, &e->model, e->t, &(SylForestOptions){.threads = v->threads, .diag = diag}, &e->forest);
    if (!st) st = syl_ecosystem_simulate(&e->model, e->t, &o, NULL);
    free(every);
    if (!st && e->nyears < e->last) st = SYL_ELIMIT;
    if (st == SYL_ELIMIT) fprintf(diag, "sylva: error: the ecosystem does not fit in memory\n");
    return st;
}

/* The kept year nearest to year (< 0: the last). */
static const EcoYear *kept_year(const ViewEco *e, int year) {
    const EcoYear *best = e->nkept ? &e->kept[e->nkept - 1] : NULL;
    if (year < 0) return best;
    for (int i = 0; i < e->nkept; i++)
        if (abs(e->kept[i].year - year) < abs(best->year - year)) best = &e->kept[i];
    return best;
}

typedef struct ForestAt {
    const ViewEco *e;
    const EcoYear *y;
} ForestAt;

static int write_forest(void *ctx, const char *path, FILE *diag) {
    const ForestAt *f = ctx;
    return syl_forest_write_glb(f->e->forest, f->y->plants, f->y->n, 0, path, cli_text_sink(diag));
}

/* The page's figures: the chart's counts, the year shown, the maps, the terrain's extent. */
static char *eco_json(const ViewEco *e, const EcoYear *y, double seconds) {
    char *s = NULL;
    size_t n = 0;
    FILE *f = open_memstream(&s, &n);
    if (!f) return NULL;
    const SylTerrain *t = e->t;
    const SylEcoModel *m = &e->model;
    size_t shown[SYL_ECO_MAX_SPECIES] = {0};
    for (size_t i = 0; i < y->n; i++) shown[y->plants[i].species]++;
    fprintf(f, "{\"kind\":\"%s\",", syl_model_kind_keyword(syl_program_kind(e->p)));
    view_caps_json(f, syl_program_kind(e->p));
    fprintf(f, ",\"year\":%d,\"years\":%d,\"stride\":%d,\"plants\":%zu,\"simulate_time\":%.6f,",
            y->year, e->last, e->stride, y->n, seconds);
    fprintf(f, "\"terrain\":{\"x0\":%g,\"z0\":%g,\"width\":%g,\"depth\":%g,\"cell\":%g},\"species\":[", t->x0, t->z0,
            t->nx * t->cell, t->nz * t->cell, t->cell);
    for (int s = 0; s < m->nspecies; s++) {
        fputs(s ? "," : "", f);
        fputs("{\"name\":", f);
        json_string_file(f, m->species[s].name);
        fputs(",\"model\":", f);
        json_string_file(f, m->species[s].model);
        fprintf(f, ",\"plants\":%zu,\"count\":[", shown[s]);
        for (int k = 0; k < e->nyears; k++) fprintf(f, "%s%u", k ? "," : "", e->years[k].count[s]);
        fputs("],\"cover\":[", f);
        for (int k = 0; k < e->nyears; k++) fprintf(f, "%s%.6f", k ? "," : "", e->years[k].cover[s]);
        fputs("]}", f);
    }
    fputs("],\"looks\":[", f); /* the forest's looks, in the order of /api/impostor?look=K */
    for (int k = 0; k < syl_forest_looks(e->forest); k++) {
        int sp, cl, va;
        syl_forest_look(e->forest, k, &sp, &cl, &va);
        fprintf(f, "%s{\"species\":", k ? "," : "");
        json_string_file(f, m->species[sp].name);
        fprintf(f, ",\"class\":%d,\"variant\":%d}", cl, va);
    }
    fputs("],\"chart_years\":[", f);
    for (int k = 0; k < e->nyears; k++) fprintf(f, "%s%d", k ? "," : "", e->years[k].year);
    fputs("],\"kept\":[", f);
    for (int k = 0; k < e->nkept; k++) fprintf(f, "%s%d", k ? "," : "", e->kept[k].year);
    fputs("],\"maps\":[", f);
    for (int k = 0, first = 1; k < SYL_TERRAIN_FACTORS; k++)
        if (t->factor[k]) {
            fputs(first ? "" : ",", f);
            json_string_file(f, syl_terrain_factor_name((SylTerrainFactor)k));
            first = 0;
        }
    fputs("]}", f);
    fclose(f);
    return s;
}

int view_eco_build(View *v, const ViewRequest *rq, SylProgram *p, unsigned gen, FILE *diag, ViewBuild *slot) {
    uint64_t key = eco_key(v, rq, gen);
    double t0 = cli_now();
    if (!v->eco || v->eco->key != key) {
        view_eco_free(v->eco);
        v->eco = calloc(1, sizeof *v->eco);
        if (!v->eco) return syl_program_free(p), SYL_ELIMIT;
        int st = eco_run(v, p, v->eco, diag);
        v->eco->key = key;
        if (st) {
            view_eco_free(v->eco);
            v->eco = NULL;
            return st;
        }
    } else {
        syl_program_free(p);
    }
    double seconds = cli_now() - t0;
    ViewEco *e = v->eco;
    const EcoYear *y = kept_year(e, rq->steps);
    if (!y) {
        fprintf(diag, "sylva: error: the ecosystem has no years to show\n");
        return SYL_EMODEL;
    }
    FILE *out = view_bytes_open(&slot->glb, &slot->glb_len);
    if (!out) return SYL_ELIMIT;
    int st = view_write_via_file(write_forest, &(ForestAt){e, y}, "forest.glb", out, diag);
    fclose(out);
    slot->csv = strdup("");
    slot->stats = eco_json(e, y, seconds);
    return st ? st : slot->stats && slot->csv ? SYL_OK : SYL_ELIMIT;
}

typedef struct MapOf {
    const SylTerrain *t;
    int factor;
} MapOf;

static int write_map(void *ctx, const char *path, FILE *diag) {
    const MapOf *m = ctx;
    return syl_terrain_write_map(m->t, (SylTerrainFactor)m->factor, path, cli_text_sink(diag));
}

int view_eco_map(View *v, const char *name, char **png, size_t *len) {
    *png = NULL, *len = 0;
    if (!v->eco || !name) return SYL_EUSAGE;
    int k = 0;
    while (k < SYL_TERRAIN_FACTORS && strcmp(syl_terrain_factor_name((SylTerrainFactor)k), name)) k++;
    if (k == SYL_TERRAIN_FACTORS || !v->eco->t->factor[k]) return SYL_EUSAGE;
    FILE *out = open_memstream(png, len);
    if (!out) return SYL_ELIMIT;
    FILE *diag = fopen("/dev/null", "w");
    int st = view_write_via_file(write_map, &(MapOf){v->eco->t, k}, "map.png", out, diag);
    if (diag) fclose(diag);
    fclose(out);
    if (st) free(*png), *png = NULL, *len = 0;
    return st;
}

/* Look k's impostor: its crossed billboards (three quads, sylva mesh --billboards 3) baked by
 * the library from the look's mesh, as the .glb of a one-level chain; made once a run. */
int view_eco_impostor(View *v, int look, const char **glb, size_t *len) {
    ViewEco *e = v->eco;
    *glb = NULL, *len = 0;
    int n = e ? syl_forest_looks(e->forest) : 0;
    if (look < 0 || look >= n) return SYL_EUSAGE;
    if (!e->imp) {
        e->imp = calloc((size_t)n, sizeof *e->imp);
        e->imp_len = calloc((size_t)n, sizeof *e->imp_len);
        if (!e->imp || !e->imp_len) return free(e->imp), free(e->imp_len), e->imp = NULL, e->imp_len = NULL, SYL_ELIMIT;
    }
    if (!e->imp[look]) {
        const SylMesh *m = syl_forest_look(e->forest, look, NULL, NULL, NULL);
        if (!m || !m->nidx) return SYL_EMODEL;
        FILE *diag = fopen("/dev/null", "w");
        SylImpostor imp = {0};
        SylImpostorOptions io = {.grid = -1, .view = 128, .billboards = 3, .threads = v->threads, .diag = diag};
        int st = syl_impostor_bake(m, &io, &imp);
        if (!st) {
            SylLodChain c = {.n = 1, .atlas = imp.bb_color, .atlas_w = imp.bb_width, .atlas_h = imp.view,
                             .atlas_material = SYL_IMPOSTOR_MATERIAL};
            c.level[0] = (SylLodLevel){.mesh = imp.bb_mesh, .coverage = 1};
            FILE *out = view_bytes_open(&e->imp[look], &e->imp_len[look]);
            st = out ? syl_wind_write_glb_lods_stream(&c, NULL, NULL, out, cli_text_sink(diag)) : SYL_ELIMIT;
            if (out) fclose(out);
            if (st) free(e->imp[look]), e->imp[look] = NULL;
        }
        syl_impostor_free(&imp);
        if (diag) fclose(diag);
        if (st) return st;
    }
    *glb = e->imp[look], *len = e->imp_len[look];
    return SYL_OK;
}
