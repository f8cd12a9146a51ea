/* syl_forest_*: the looks of an ecosystem's species, meshed once per age class, the terrain as
 * a mesh, the plants as instances of those looks, and the two cameras. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sylva/forest.h"
#include "sylva/plant.h"
#include "forest/forest_internal.h"
#include "kinds/kinds.h"
#include "lang/kinds.h"
#include "lang/program.h"
#include "lang/schema.h"
#include "mesh/store.h"
#include "util/rng.h"

/* The terrain as triangles between its cells' centres, one grass-coloured material. */
static SylMesh *terrain_mesh(const SylTerrain *t) {
    SylMesh *g = calloc(1, sizeof *g);
    size_t nx = (size_t)t->nx, nz = (size_t)t->nz, nv = nx * nz;
    size_t ntri = nx > 1 && nz > 1 ? 2 * (nx - 1) * (nz - 1) : 0;
    if (!g) return NULL;
    g->pos = malloc((nv + 2) * 3 * sizeof(float)); /* room past the end: Embree reads 16 bytes */
    g->nrm = malloc((nv + 2) * 3 * sizeof(float));
    g->idx = malloc((ntri ? ntri : 1) * 3 * sizeof(uint32_t));
    g->groups = calloc(1, sizeof *g->groups);
    if (!g->pos || !g->nrm || !g->idx || !g->groups || nv > 0xffffffffu) {
        syl_mesh_free(g);
        return NULL;
    }
    g->nverts = nv;
    mesh_mark_spare(g);
    const float *h = t->height;
    for (size_t k = 0; k < nz; k++)
        for (size_t i = 0; i < nx; i++) {
            float *p = g->pos + 3 * (k * nx + i), *n = g->nrm + 3 * (k * nx + i);
            p[0] = (float)(t->x0 + ((double)i + 0.5) * t->cell);
            p[1] = h[k * nx + i];
            p[2] = (float)(t->z0 + ((double)k + 0.5) * t->cell);
            size_t i0 = i ? i - 1 : i, i1 = i + 1 < nx ? i + 1 : i, k0 = k ? k - 1 : k, k1 = k + 1 < nz ? k + 1 : k;
            double dx = i1 > i0 ? (h[k * nx + i1] - h[k * nx + i0]) / ((double)(i1 - i0) * t->cell) : 0;
            double dz = k1 > k0 ? (h[k1 * nx + i] - h[k0 * nx + i]) / ((double)(k1 - k0) * t->cell) : 0;
            double len = sqrt(dx * dx + 1 + dz * dz);
            n[0] = (float)(-dx / len), n[1] = (float)(1 / len), n[2] = (float)(-dz / len);
        }
    memset(g->pos + 3 * nv, 0, 6 * sizeof(float));
    size_t w = 0;
    for (size_t k = 0; k + 1 < nz; k++)
        for (size_t i = 0; i + 1 < nx; i++) { /* counter-clockwise seen from above (+y) */
            uint32_t a = (uint32_t)(k * nx + i), b = a + 1, c = a + (uint32_t)nx, d = c + 1;
            uint32_t q[6] = {a, c, b, b, c, d};
            memcpy(g->idx + w, q, sizeof q), w += 6;
        }
    g->nidx = w;
    g->ngroups = 1;
    g->groups[0] = (SylMeshGroup){.first = 0, .count = (uint32_t)w, .material = 0};
    g->materials[0] = (SylMaterial){.rgb = {0.33f, 0.45f, 0.20f}, .kind = SYL_MATERIAL_PLAIN};
    g->nmaterials = 1;
    snprintf(g->name, sizeof g->name, "terrain");
    return g;
}

/* Base at the origin, height 1: an instance's scale is then its plant's height. */
static void normalise(SylMesh *m, float y0, float k) {
    for (size_t i = 0; m && i < m->nverts; i++) {
        float *p = m->pos + 3 * i;
        p[0] *= k, p[1] = (p[1] - y0) * k, p[2] *= k;
    }
}

static int build_look(SylGrowth *g, const SylProgram *q, int frame, int variant, const SylForestOptions *o,
                      Look *look) {
    SylMeshOptions mo = {.threads = o->threads, .diag = o->diag, .sink = o->sink, .budget = o->budget};
    SylPlantOptions po = {.threads = o->threads, .diag = o->diag, .budget = o->budget, .mesh = &mo, .drop_string = 1,
                          .use_seed = variant > 0, .seed = 7919 * (uint64_t)variant}; /* variant 0: the model's own */
    SylPlant pl = {0};
    int st = g ? syl_growth_build(g, frame, &pl) : syl_plant_build(q, &po, &pl);
    if (st) return st;
    SylMesh *m = pl.mesh;
    pl.mesh = NULL;
    float lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; m && i < m->nverts; i++) lo = fminf(lo, m->pos[3 * i + 1]), hi = fmaxf(hi, m->pos[3 * i + 1]);
    if (m && m->nidx && o->coarse >= 0 && pl.skeleton && syl_lod_build(pl.skeleton, &mo, m, 1, &look->lod))
        memset(&look->lod, 0, sizeof look->lod); /* no coarse level: the full mesh everywhere */
    float k = hi > lo ? 1 / (hi - lo) : 1;
    normalise(m, lo, k);
    if (look->lod.n > 1) normalise(look->lod.level[1].mesh, lo, k);
    look->mesh = m;
    syl_plant_free(&pl);
    return SYL_OK;
}

/* A species' classes: an L-system's derivation steps, a grown tree's years, a strands
 * block's ages spread over the growth, variant v of class c at frame round(N (c + (v + 1) / V)
 * / C); a Weber–Penn tree has no growth: its variants are other seeds of one tree, scaled. */
/* A species' model, compiled once for every species that names it (programs[s]; freed by
 * syl_forest_new), its block read once: the kind's check keeps its reading, as syl_compile's
 * hook does, for every look built from it (quietly: a block that fails it is read again by
 * the build, which reports why). */
static SylProgram *look_program(const SylForest *f, const SylProgram *p, int s, SylProgram **programs,
                                const SylForestOptions *o, int *st) {
    for (int k = 0; k < s; k++)
        if (programs[k] && !strcmp(f->m->species[k].model, f->m->species[s].model)) return programs[k];
    SylProgram *q = lang_compile_sibling(p, f->m->species[s].model, o->diag, o->sink, st);
    if (!q) return NULL;
    sch_count_into(q, p);
    const KindOps *ops = kinds_ops(syl_program_kind(q));
    if (lang_kind_is(syl_program_kind(q), KF_LOOK) && ops->validate) ops->validate(q, NULL);
    return q;
}

static int species_looks(SylForest *f, const SylProgram *p, int s, SylProgram **programs, const SylForestOptions *o) {
    const SylEcoSpecies *sp = &f->m->species[s];
    for (int c = 0; c < SYL_FOREST_CLASSES; c++)
        for (int v = 0; v < FOREST_VARIANTS; v++) f->proto_of[s][c][v] = -1;
    if (!sp->model[0]) return SYL_OK;
    int st;
    SylProgram *q = programs[s] = look_program(f, p, s, programs, o, &st);
    if (!q) return st ? st : SYL_EMODEL;
    if (!lang_kind_is(syl_program_kind(q), KF_LOOK)) {
        lang_kind_refuse(q, o->diag, syl_program_name(q), syl_program_kind(q), true);
        return SYL_EUSAGE;
    }
    SylGrowth *g = NULL;
    SylMeshOptions mo = {.threads = o->threads, .diag = o->diag, .sink = o->sink, .budget = o->budget};
    SylPlantOptions po = {.threads = o->threads, .diag = o->diag, .budget = o->budget, .mesh = &mo};
    if (lang_kind_is(syl_program_kind(q), KF_RULES | KF_GROWS | KF_AGES) && syl_growth_new(q, &po, &g)) g = NULL;
    int frames = g ? syl_growth_count(g) : 1;
    st = SYL_OK;
    int last_frame = -1, last_k = -1;
    for (int c = 0; c < SYL_FOREST_CLASSES && !st; c++)
        for (int v = 0; v < FOREST_VARIANTS && !st; v++) {
            double at = c + (double)(v + 1) / FOREST_VARIANTS;
            int frame = g ? (int)lround((double)(frames - 1) * at / SYL_FOREST_CLASSES) : 0;
            if (g ? frame == last_frame : c > 0) { /* the same look as one before */
                f->proto_of[s][c][v] = g ? last_k : f->proto_of[s][0][v];
                continue;
            }
            int k = f->nprotos;
            st = build_look(g, q, frame, g ? 0 : v, o, &f->looks[k]);
            if (st) break;
            f->protos[k].mesh = f->looks[k].mesh;
            f->protos[k].coarse = f->looks[k].lod.n > 1 ? f->looks[k].lod.level[1].mesh : NULL;
            /* a species name is at most 47 bytes; the class and variant are small: cut the name so it fits */
            snprintf(f->looks[k].mesh->name, sizeof f->looks[k].mesh->name, "%.40s_class%d_v%d", sp->name, c & 0xff,
                     v & 0xff);
            f->proto_species[k] = s, f->proto_class[k] = c, f->proto_variant[k] = v;
            f->proto_of[s][c][v] = k;
            last_frame = frame, last_k = k;
            f->nprotos++;
        }
    syl_growth_free(g);
    return st;
}

int syl_forest_new(const SylProgram *p, const SylEcoModel *m, const SylTerrain *t, const SylForestOptions *o,
                   SylForest **out) {
    static const SylForestOptions defaults = {0};
    if (!o) o = &defaults;
    *out = NULL;
    SylForest *f = calloc(1, sizeof *f);
    if (!f) return SYL_ELIMIT;
    f->m = m, f->t = t, f->textures = o->textures;
    int st = (f->ground = terrain_mesh(t)) ? SYL_OK : SYL_ELIMIT;
    SylProgram *programs[SYL_ECO_MAX_SPECIES] = {0};
    for (int s = 0; s < m->nspecies && !st; s++) st = species_looks(f, p, s, programs, o);
    for (int s = 0; s < m->nspecies; s++) { /* each once: species may share one */
        bool first = true;
        for (int k = 0; k < s; k++) first &= programs[k] != programs[s];
        if (first) syl_program_free(programs[s]);
    }
    if (st) {
        syl_forest_free(f);
        return st;
    }
    *out = f;
    return SYL_OK;
}

void syl_forest_free(SylForest *f) {
    if (!f) return;
    for (int k = 0; k < f->nprotos; k++) {
        syl_lod_free(&f->looks[k].lod);
        syl_mesh_free(f->looks[k].mesh);
    }
    syl_mesh_free(f->ground);
    free(f);
}

int forest_class_of(const SylEcoSpecies *sp, float h) {
    int c = sp->height_max > 0 ? (int)(h / sp->height_max * SYL_FOREST_CLASSES) : SYL_FOREST_CLASSES - 1;
    return c < 0 ? 0 : c >= SYL_FOREST_CLASSES ? SYL_FOREST_CLASSES - 1 : c;
}

void syl_forest_instances(const SylForest *f, const SylEcoPlant *plants, size_t n, SylRenderInstance *inst) {
    for (size_t i = 0; i < n; i++) {
        const SylEcoPlant *p = &plants[i];
        int sp = p->species < f->m->nspecies ? p->species : -1;
        uint64_t hash = rng_mix(p->id ^ 0x7f4a7c159e3779b9ull); /* the turn and the look: the plant's own */
        int v = (int)((hash & 0xffff) % FOREST_VARIANTS);
        int k = sp >= 0 ? f->proto_of[sp][forest_class_of(&f->m->species[sp], p->height)][v] : -1;
        double y = syl_terrain_factor_at(f->t, SYL_TERRAIN_ALTITUDE, p->x, p->z);
        inst[i] = (SylRenderInstance){.t = {p->x, (float)y, p->z},
                                      .yaw = (float)((double)(hash >> 40) * 0x1p-24 * 2 * M_PI),
                                      .scale = k >= 0 ? p->height : 0,
                                      .proto = k >= 0 ? (uint32_t)k : 0};
    }
}

int syl_forest_render(const SylForest *f, const SylEcoPlant *plants, size_t n, const SylRenderCamera *cam,
                      const SylRenderOptions *ro, const int (*windows)[4], int nwindows, uint8_t *rgb,
                      SylRenderCounts *counts) {
    SylRenderInstance *inst = malloc((n ? n : 1) * sizeof *inst);
    if (!inst) return SYL_ELIMIT;
    syl_forest_instances(f, plants, n, inst);
    /* the ones drawn as nothing are left out here: the renderer wants a prototype each */
    size_t kept = 0;
    for (size_t i = 0; i < n; i++)
        if (inst[i].scale > 0 && f->nprotos) inst[kept++] = inst[i];
    int st = syl_render_draw_instances(f->ground, f->protos, f->nprotos, inst, kept, cam, ro, windows, nwindows, rgb, counts);
    free(inst);
    return st;
}

int syl_forest_looks(const SylForest *f) { return f ? f->nprotos : 0; }

const SylMesh *syl_forest_look(const SylForest *f, int k, int *species, int *age_class, int *variant) {
    if (!f || k < 0 || k >= f->nprotos) return NULL;
    if (species) *species = f->proto_species[k];
    if (age_class) *age_class = f->proto_class[k];
    if (variant) *variant = f->proto_variant[k];
    return f->looks[k].mesh;
}
