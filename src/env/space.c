/* Space colonization rounds: see space.h. */
#include "env/space.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "sylva/sylva.h"
#include "util/parallel.h"
#include "util/rng.h"

typedef struct Ctx {
    const SpaceQuery *q;
    const SpaceBud *buds;
    size_t n;
    PointGrid grid;    /* the buds */
    float reach;       /* the largest perception distance */
    float (*mpos)[3];  /* markers examined this round */
    uint32_t *mid;     /* global: the cloud's index of each examined marker */
    uint8_t *valid;    /* per-bud: the marker survived its bud's checks */
    int32_t *owner;    /* the bud each marker goes to, or -1 */
    size_t nm;
} Ctx;

static void basis(const float n[3], float t[3], float b[3]) {
    if (fabsf(n[0]) < 0.9f) t[0] = 0, t[1] = -n[2], t[2] = n[1];
    else t[0] = n[2], t[1] = 0, t[2] = -n[0];
    float len = sqrtf(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    for (int k = 0; k < 3; k++) t[k] /= len;
    b[0] = n[1] * t[2] - n[2] * t[1], b[1] = n[2] * t[0] - n[0] * t[2], b[2] = n[0] * t[1] - n[1] * t[0];
}

/* Per-bud markers: thrown uniformly into the cone between the occupancy radius and the
 * perception distance; dropped near a metamer or behind an obstacle. */
static void throw_markers(void *arg, size_t lo, size_t hi, int thread) {
    (void)thread;
    Ctx *c = arg;
    const SpaceQuery *q = c->q;
    for (size_t i = lo; i < hi; i++) {
        const SpaceBud *b = &c->buds[i];
        size_t first = c->mid[i];
        Rng r = rng_stream(b->key, q->round, 11, 0);
        float t[3], bb[3];
        basis(b->dir, t, bb);
        float r0 = q->occupancy < b->reach ? q->occupancy : 0, r1 = b->reach;
        float c0 = r0 * r0 * r0, c1 = r1 * r1 * r1;
        for (uint32_t k = 0; k < b->markers; k++) {
            float cz = 1 - (float)rng_unit(&r) * (1 - b->cos_half), sz = sqrtf(fmaxf(0, 1 - cz * cz));
            float a = 6.2831853f * (float)rng_unit(&r);
            float d = cbrtf(c0 + (float)rng_unit(&r) * (c1 - c0));
            float *m = c->mpos[first + k];
            for (int j = 0; j < 3; j++) m[j] = b->pos[j] + d * (b->dir[j] * cz + (t[j] * cosf(a) + bb[j] * sinf(a)) * sz);
            bool ok = m[1] >= q->ground && !(q->nodes && pgrid_any_within(q->nodes, m, q->occupancy, UINT32_MAX));
            if (ok && obstacles_any(q->obstacles)) ok = !obstacles_blocked(q->obstacles, b->pos, m, 0);
            c->valid[first + k] = ok;
        }
    }
}

/* The nearest bud that perceives marker m and sees it; -1 if none, or if the marker lies in
 * a bud's occupancy sphere. A per-bud marker starts with its own bud as the best: only buds
 * nearer than that one need a look. */
static int32_t nearest_bud(const Ctx *c, const float m[3], int32_t best, float best2) {
    const SpaceQuery *q = c->q;
    const PointGrid *g = &c->grid;
    float occ2 = q->occupancy * q->occupancy, r = best >= 0 ? sqrtf(best2) : c->reach;
    if (r < q->occupancy) r = q->occupancy;
    bool hidden = obstacles_any(q->obstacles);
    PGRID_FOR_CELLS(g, m, r, x, y, z) {
        uint32_t first = 0, cnt = pgrid_cell(g, x, y, z, &first);
        for (uint32_t k = first; k < first + cnt; k++) {
            const float *p = g->pts[k];
            float d[3] = {m[0] - p[0], m[1] - p[1], m[2] - p[2]};
            float d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if (d2 < occ2) return -1;
            if (d2 > best2) continue; /* most buds: farther than the best so far */
            int32_t id = (int32_t)g->ids[k];
            const SpaceBud *b = &c->buds[id];
            if (id == best || d2 >= b->reach * b->reach || (d2 == best2 && id > best)) continue;
            float along = d[0] * b->dir[0] + d[1] * b->dir[1] + d[2] * b->dir[2];
            if (along < b->cos_half * sqrtf(d2)) continue;
            if (hidden && obstacles_blocked(q->obstacles, p, m, 0)) continue;
            best2 = d2;
            best = id;
        }
    }
    return best;
}

static void match(void *arg, size_t lo, size_t hi, int thread) {
    (void)thread;
    Ctx *c = arg;
    if (!c->valid) { /* global markers */
        for (size_t i = lo; i < hi; i++) c->owner[i] = nearest_bud(c, c->mpos[i], -1, INFINITY);
        return;
    }
    /* per-bud markers: the bud that threw marker i (mid holds each bud's first marker) */
    size_t b = 0, lo_b = 0, hi_b = c->n;
    while (lo_b < hi_b) { /* the last bud whose first marker is <= lo */
        size_t mid = (lo_b + hi_b) / 2;
        if (c->mid[mid] <= lo) b = mid, lo_b = mid + 1;
        else hi_b = mid;
    }
    for (size_t i = lo; i < hi; i++) {
        while (b + 1 < c->n && c->mid[b + 1] <= i) b++;
        if (!c->valid[i]) {
            c->owner[i] = -1;
            continue;
        }
        const float *p = c->buds[b].pos, *m = c->mpos[i];
        float d2 = (m[0] - p[0]) * (m[0] - p[0]) + (m[1] - p[1]) * (m[1] - p[1]) + (m[2] - p[2]) * (m[2] - p[2]);
        c->owner[i] = nearest_bud(c, m, (int32_t)b, d2);
    }
}

/* Global markers: make the cells the buds look into, and list their living markers in a
 * fixed order (cells in the order they were made). */
static bool gather_global(Ctx *c) {
    const SpaceQuery *q = c->q;
    MarkerCloud *cl = q->cloud;
    for (size_t i = 0; i < c->n; i++)
        if (!markers_ensure(cl, c->buds[i].pos, c->buds[i].reach, q->nodes)) return false;
    uint8_t *touched = calloc(cl->nblocks ? cl->nblocks : 1, 1);
    if (!touched) return false;
    for (size_t i = 0; i < c->n; i++) {
        const float *p = c->buds[i].pos;
        float r = c->buds[i].reach;
        for (int x = markers_coord(cl, p[0] - r); x <= markers_coord(cl, p[0] + r); x++)
            for (int y = markers_coord(cl, p[1] - r); y <= markers_coord(cl, p[1] + r); y++)
                for (int z = markers_coord(cl, p[2] - r); z <= markers_coord(cl, p[2] + r); z++) {
                    long b = markers_block(cl, x, y, z);
                    if (b >= 0) touched[b] = 1;
                }
    }
    size_t nm = 0;
    for (size_t b = 0; b < cl->nblocks; b++)
        if (touched[b])
            for (uint32_t k = cl->blocks[b].first; k < cl->blocks[b].first + cl->blocks[b].count; k++) nm += cl->alive[k];
    c->mpos = malloc((nm ? nm : 1) * sizeof *c->mpos);
    c->mid = malloc((nm ? nm : 1) * sizeof *c->mid);
    if (!c->mpos || !c->mid) {
        free(touched);
        return false;
    }
    for (size_t b = 0; b < cl->nblocks; b++)
        if (touched[b])
            for (uint32_t k = cl->blocks[b].first; k < cl->blocks[b].first + cl->blocks[b].count; k++)
                if (cl->alive[k]) {
                    memcpy(c->mpos[c->nm], cl->pos[k], sizeof *c->mpos);
                    c->mid[c->nm++] = k;
                }
    free(touched);
    return true;
}

static bool gather_per_bud(Ctx *c) {
    /* mid[i]: the first marker of bud i */
    c->mid = malloc((c->n + 1) * sizeof *c->mid);
    if (!c->mid) return false;
    size_t nm = 0;
    for (size_t i = 0; i < c->n; i++) {
        c->mid[i] = (uint32_t)nm;
        nm += c->buds[i].markers;
    }
    c->mid[c->n] = (uint32_t)nm;
    if (nm > UINT32_MAX / 2) return false;
    c->nm = nm;
    c->mpos = malloc((nm ? nm : 1) * sizeof *c->mpos);
    c->valid = malloc(nm ? nm : 1);
    if (!c->mpos || !c->valid) return false;
    par_for(c->q->threads, c->n, 64, throw_markers, c);
    return true;
}

int space_round(const SpaceQuery *q, const SpaceBud *buds, size_t n, SpaceResult *out) {
    memset(out, 0, n * sizeof *out);
    if (!n) return SYL_OK;
    Ctx c = {.q = q, .buds = buds, .n = n};
    for (size_t i = 0; i < n; i++)
        if (buds[i].reach > c.reach) c.reach = buds[i].reach;
    if (!(c.reach > 0)) return SYL_OK;
    int st = SYL_ELIMIT;
    if (!pgrid_build(&c.grid, c.reach, buds[0].pos, sizeof *buds / sizeof(float), n)) goto done;
    if (!(q->variant == SPACE_GLOBAL ? gather_global(&c) : gather_per_bud(&c))) goto done;
    c.owner = malloc((c.nm ? c.nm : 1) * sizeof *c.owner);
    if (!c.owner) goto done;
    par_for(q->threads, c.nm, 256, match, &c);
    for (size_t m = 0; m < c.nm; m++) { /* in a fixed order: the sums never depend on threads */
        int32_t b = c.owner[m];
        if (b < 0) continue;
        float d[3] = {c.mpos[m][0] - buds[b].pos[0], c.mpos[m][1] - buds[b].pos[1], c.mpos[m][2] - buds[b].pos[2]};
        float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(len > 0)) continue;
        for (int k = 0; k < 3; k++) out[b].dir[k] += d[k] / len;
        out[b].count++;
    }
    for (size_t i = 0; i < n; i++) {
        float *d = out[i].dir, len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (len > 1e-12f)
            for (int k = 0; k < 3; k++) d[k] /= len;
        else d[0] = d[1] = d[2] = 0;
    }
    st = SYL_OK;
done:
    pgrid_free(&c.grid);
    free(c.mpos);
    free(c.mid);
    free(c.valid);
    free(c.owner);
    return st;
}
