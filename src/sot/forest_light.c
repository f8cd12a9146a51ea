/* The forest and its environment: light per bud, shadow casting, occupancy. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sot/allocate.h"
#include "sot/forest_internal.h"
#include "util/parallel.h"
#include "lang/program.h"

enum { NODE_STRIDE = sizeof(Node) / sizeof(float) };

typedef struct LightJob {
    Forest *f;
    Tree *t;
    int year;
} LightJob;

static void bud_light(void *arg, size_t lo, size_t hi, int thread) {
    (void)thread;
    LightJob *j = arg;
    Tree *t = j->t;
    const Env *e = &j->f->env;
    const GrowParams *P = &t->P;
    for (size_t i = lo; i < hi; i++) {
        Bud *b = &t->buds[i];
        b->q = 0;
        if (!alloc_candidate(b, j->year)) continue;
        const float *pos = t->nodes[b->node].pos;
        if (P->light == LIGHT_SHADOW) { /* shadow_light, inlined: every bud, every year */
            float q = e->shadow.p.full - shadow_value(&e->shadow, shadow_index(&e->shadow, pos)) + e->shadow.p.a;
            b->q = q > 0 ? q : 0;
        } else if (P->light == LIGHT_SKY) {
            Rng r = rng_stream(b->key, (uint64_t)j->year, 1, 0);
            b->q = P->full * sky_exposure(&e->sky, pos, e->sun, P->sky_rays, &r, 1.05f * P->foliage);
        } else b->q = P->full;
    }
}

static int build_sky(Forest *f) {
    Env *e = &f->env;
    sky_reset(&e->sky);
    float r0 = 0;
    for (int i = 0; i < f->ntrees; i++) {
        const Tree *t = &f->trees[i];
        if (t->P.light == LIGHT_SKY && !r0) r0 = t->P.foliage;
        for (size_t k = 1; k < t->n; k++)
            if (!sky_add(&e->sky, t->nodes[k].pos, t->P.foliage)) return SYL_ELIMIT;
    }
    for (size_t k = 0; k < e->nstatic; k++)
        if (!sky_add(&e->sky, e->statics + 3 * k, r0)) return SYL_ELIMIT;
    return sky_commit(&e->sky, e->dev, &e->obstacles);
}

int forest_light(Forest *f, int year) {
    for (int i = 0; i < f->ntrees; i++) { /* lateral buds that did not break in time die */
        Tree *t = &f->trees[i];
        size_t dead = 0;
        for (size_t k = 0; k < t->nb; k++) {
            Bud *b = &t->buds[k];
            if (b->kind == BUD_LATERAL && year - (int)b->born > t->P.bud_life) b->alive = 0;
            dead += !b->alive;
        }
        if (dead > t->nb / 4) tree_compact_buds(t);
    }
    if (f->env.sky_on) {
        int st = build_sky(f);
        if (st) return st;
    }
    for (int i = 0; i < f->ntrees; i++) {
        Tree *t = &f->trees[i];
        if (t->start_year >= year) continue;
        LightJob j = {f, t, year};
        par_for(t->P.light == LIGHT_SKY ? f->threads : 1, t->nb, 64, bud_light, &j);
    }
    return SYL_OK;
}

int forest_space_light(Forest *f, int year) {
    size_t n = 0;
    for (int i = 0; i < f->ntrees; i++) {
        const Tree *t = &f->trees[i];
        if (t->start_year >= year || t->P.light != LIGHT_OFF || t->P.space == SPACEM_OFF) continue;
        for (size_t k = 0; k < t->nb; k++) n += alloc_candidate(&t->buds[k], year);
    }
    if (!n) return SYL_OK;
    if (!forest_space_scratch(f, n)) return SYL_ELIMIT;
    size_t m = 0;
    for (int i = 0; i < f->ntrees; i++) {
        const Tree *t = &f->trees[i];
        if (t->start_year >= year || t->P.light != LIGHT_OFF || t->P.space == SPACEM_OFF) continue;
        for (size_t k = 0; k < t->nb; k++) {
            const Bud *b = &t->buds[k];
            if (!alloc_candidate(b, year)) continue;
            forest_space_bud(t, b, &f->sb[m]);
            f->sb_cand[m++] = (uint32_t)k;
        }
    }
    SpaceQuery q = {.variant = f->space_variant, .occupancy = f->env.occupancy, .ground = f->env.ground, .nodes = &f->env.occupied,
                    .obstacles = &f->env.obstacles, .cloud = &f->env.cloud, .round = (uint64_t)year << 20,
                    .threads = f->threads};
    int st = space_round(&q, f->sb, n, f->sr);
    if (st) return st;
    m = 0;
    for (int i = 0; i < f->ntrees; i++) {
        Tree *t = &f->trees[i];
        if (t->start_year >= year || t->P.light != LIGHT_OFF || t->P.space == SPACEM_OFF) continue;
        for (size_t k = 0; k < t->nb; k++) {
            Bud *b = &t->buds[k];
            if (!alloc_candidate(b, year)) continue;
            b->q = f->sr[m++].count > 0 ? t->P.full : 0;
        }
    }
    return SYL_OK;
}

static bool gather(Forest *f, size_t n) {
    if (3 * n <= f->occ_cap) return true;
    size_t cap = f->occ_cap ? f->occ_cap : 3 * 4096;
    while (cap < 3 * n) cap *= 2;
    float *p = realloc(f->occ, cap * sizeof *p);
    if (!p) return false;
    f->occ = p;
    f->occ_cap = cap;
    return true;
}

int forest_shadow_too_big(Forest *f) {
    f->reported = true;
    if (f->env.shadow.refused)
        diag_say(f->diag, f->sink, DIAG_ERROR, NULL, "the shadow grid would need more than the %llu MB that --max-memory allows; "
                         "raise the limit with --max-memory", (unsigned long long)budget_limit_mb(f->mem));
    else diag_say(f->diag, f->sink, DIAG_ERROR, NULL, "the shadow grid would need more than %zu voxels: the scene is too large "
                         "for its voxel size", f->env.shadow.max_voxels);
    return SYL_ELIMIT;
}

int forest_register(Forest *f, const size_t *before) {
    Env *e = &f->env;
    if (!e->shadow_on) return SYL_OK;
    for (int i = 0; i < f->ntrees; i++) {
        Tree *t = &f->trees[i];
        size_t from = before[i] > 1 ? before[i] : 1;
        if (t->n > from && !shadow_cast_strided(&e->shadow, t->nodes[from].pos, NODE_STRIDE, t->n - from, +1))
            return forest_shadow_too_big(f);
    }
    return SYL_OK;
}

int forest_drop_dead(Forest *f, Tree *t, size_t n) {
    Env *e = &f->env;
    if (!e->shadow_on) return tree_compact(t, NULL) ? SYL_OK : SYL_ELIMIT;
    /* the positions gathered by the compaction's own pass (no pass of its own over the nodes) */
    if (!gather(f, n) || !tree_compact(t, f->occ)) return SYL_ELIMIT;
    if (!shadow_cast_strided(&e->shadow, f->occ, 3, n, -1)) return forest_shadow_too_big(f);
    return SYL_OK;
}

int forest_occupancy(Forest *f) {
    Env *e = &f->env;
    if (!f->space_any) return SYL_OK;
    size_t n = e->nstatic;
    for (int i = 0; i < f->ntrees; i++) n += f->trees[i].n;
    if (!gather(f, n)) return SYL_ELIMIT;
    size_t m = 0;
    for (int i = 0; i < f->ntrees; i++)
        for (size_t k = 0; k < f->trees[i].n; k++) memcpy(f->occ + 3 * m++, f->trees[i].nodes[k].pos, 3 * sizeof(float));
    if (e->nstatic) memcpy(f->occ + 3 * m, e->statics, 3 * e->nstatic * sizeof(float));
    return pgrid_build(&e->occupied, 1.5f * e->occupancy, f->occ, 3, n) ? SYL_OK : SYL_ELIMIT;
}

int forest_register_statics(Forest *f) {
    Env *e = &f->env;
    if (e->shadow_on && !shadow_cast_strided(&e->shadow, e->statics, 3, e->nstatic, +1)) return forest_shadow_too_big(f);
    return forest_occupancy(f);
}

void forest_node_light(Forest *f, Tree *t) {
    if (t->P.light == LIGHT_SHADOW) {
        for (size_t i = 0; i < t->n; i++) t->nodes[i].light = shadow_light(&f->env.shadow, t->nodes[i].pos);
        return;
    }
    for (size_t i = 0; i < t->n; i++) t->nodes[i].light = 0;
    for (size_t k = 0; k < t->nb; k++) {
        const Bud *b = &t->buds[k];
        if (b->alive && b->q > t->nodes[b->node].light) t->nodes[b->node].light = b->q;
    }
}
