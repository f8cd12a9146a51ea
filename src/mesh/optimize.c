/* meshoptimizer over a SylMesh: reorder triangles for the GPU's vertex cache and vertices
 * for fetch locality, and simplify toward a triangle budget. Groups are processed one at a
 * time, so a triangle never changes material. */
#include "util/lazy_meshopt.h"
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sylva/mesh.h"

/* Whether the triangles use every vertex, first in the order they are stored (so the
 * first-use remap would be the identity). */
static bool in_first_use_order(const SylMesh *m) {
    uint32_t next = 0;
    for (size_t i = 0; i < m->nidx; i++) {
        if (m->idx[i] == next) next++;
        else if (m->idx[i] > next) return false;
    }
    return next == m->nverts;
}

/* Whether the remap keeps the order of the vertices it keeps (it only drops some). */
static bool keeps_order(const unsigned *remap, size_t n) {
    size_t next = 0;
    for (size_t v = 0; v < n; v++)
        if (remap[v] != ~0u && remap[v] != next++) return false;
    return true;
}

/* Vertices in first-use order, unused ones dropped; every attribute stream remapped. */
static int reorder_vertices(SylMesh *m) {
    if (!m->nverts || !m->nidx || in_first_use_order(m)) return SYL_OK;
    unsigned *remap = malloc(m->nverts * sizeof *remap);
    float *tmp = malloc(3 * m->nverts * sizeof *tmp);
    if (!remap || !tmp) {
        free(remap), free(tmp);
        return SYL_ELIMIT;
    }
    size_t nv = meshopt_optimizeVertexFetchRemap(remap, m->idx, m->nidx, m->nverts);
    size_t same = 0; /* the mesher's output is usually in first-use order already */
    while (same < m->nverts && remap[same] == same) same++;
    if (same == m->nverts) {
        free(remap), free(tmp);
        return SYL_OK;
    }
    meshopt_remapIndexBuffer(m->idx, m->idx, m->nidx, remap);
    if (keeps_order(remap, m->nverts)) { /* only unused vertices go (triangles without area): close the gaps */
        for (size_t v = 0; v < m->nverts; v++) {
            size_t to = remap[v];
            if (to == ~0u || to == v) continue;
            memcpy(m->pos + 3 * to, m->pos + 3 * v, 3 * sizeof *m->pos);
            memcpy(m->nrm + 3 * to, m->nrm + 3 * v, 3 * sizeof *m->nrm);
            memcpy(m->uv + 2 * to, m->uv + 2 * v, 2 * sizeof *m->uv);
            if (m->node) m->node[to] = m->node[v];
        }
        m->nverts = nv;
        free(remap);
        free(tmp);
        return SYL_OK;
    }
    float *streams[3] = {m->pos, m->nrm, m->uv};
    for (int s = 0; s < 3; s++) {
        size_t k = s == 2 ? 2 : 3;
        meshopt_remapVertexBuffer(tmp, streams[s], m->nverts, k * sizeof(float), remap);
        memcpy(streams[s], tmp, nv * k * sizeof(float));
    }
    if (m->node) {
        meshopt_remapVertexBuffer(tmp, m->node, m->nverts, sizeof *m->node, remap);
        memcpy(m->node, tmp, nv * sizeof *m->node);
    }
    m->nverts = nv; /* the arrays keep their capacity (and the renderer's padding) */
    free(remap);
    free(tmp);
    return SYL_OK;
}

/* True when no order can do much better: each vertex the group uses enters the cache once (as
 * leaves drawn one after another do), or at most 2% more often than that (tubes drawn ring
 * after ring). Then the group keeps its order, which is cheaper to build. The cache is a FIFO
 * of 16, simulated exactly in one pass: a vertex is in it while fewer than 16 vertices entered
 * after it. stamp[v] is when v last entered (0: never), *clock counts the entries. */
static bool cache_optimal(const uint32_t *ix, size_t n, uint32_t *stamp, uint32_t *clock) {
    const uint32_t begin = *clock;
    size_t transformed = 0, distinct = 0;
    for (size_t i = 0; i < n; i++) {
        uint32_t *s = &stamp[ix[i]];
        if (*s > begin && *clock - *s < 16) continue; /* a hit */
        distinct += *s <= begin;
        transformed++;
        *s = ++*clock;
    }
    return transformed <= distinct + distinct / 50;
}

/* Whether two corners of triangle t lie at the very same point: it has no area and draws
 * nothing (a tube tapering to radius 0 ends in a ring of coincident vertices, its last
 * segment has one such triangle a side and its cap is all of them). */
static bool degenerate(const SylMesh *m, const uint32_t *t) {
    const float *a = m->pos + 3 * (size_t)t[0], *b = m->pos + 3 * (size_t)t[1], *c = m->pos + 3 * (size_t)t[2];
    return !memcmp(a, b, 3 * sizeof *a) || !memcmp(b, c, 3 * sizeof *b) || !memcmp(a, c, 3 * sizeof *a);
}

/* Drop the triangles without area, group by group (the vertices they alone used go with
 * reorder_vertices); a group left empty is dropped. */
static void drop_degenerate(SylMesh *m) {
    size_t at = 0;
    int ng = 0;
    for (int g = 0; g < m->ngroups; g++) {
        const SylMeshGroup gr = m->groups[g];
        size_t first = at;
        for (size_t i = gr.first; i < (size_t)gr.first + gr.count; i += 3)
            if (!degenerate(m, m->idx + i)) memmove(m->idx + at, m->idx + i, 3 * sizeof *m->idx), at += 3;
        if (at > first) m->groups[ng++] = (SylMeshGroup){(uint32_t)first, (uint32_t)(at - first), gr.material};
    }
    m->nidx = at;
    m->ngroups = ng;
}

int syl_mesh_optimize(SylMesh *m) {
    if (m) drop_degenerate(m);
    if (!m || !m->nidx) return SYL_OK;
    uint32_t *tmp = malloc(m->nidx * sizeof *tmp), *stamp = calloc(m->nverts, sizeof *stamp), clock = 0;
    if (!tmp || !stamp || m->nidx >= UINT32_MAX) {
        free(tmp), free(stamp);
        return SYL_ELIMIT;
    }
    for (int g = 0; g < m->ngroups; g++) {
        uint32_t *ix = m->idx + m->groups[g].first;
        if (cache_optimal(ix, m->groups[g].count, stamp, &clock)) continue;
        meshopt_optimizeVertexCache(tmp, ix, m->groups[g].count, m->nverts);
        memcpy(ix, tmp, m->groups[g].count * sizeof *tmp);
    }
    free(tmp);
    free(stamp);
    return reorder_vertices(m);
}

int syl_mesh_simplify(SylMesh *m, double ratio, float max_error, float *error) {
    return syl_mesh_simplify_kind(m, -1, ratio, max_error, error);
}

int syl_mesh_simplify_kind(SylMesh *m, int kind, double ratio, float max_error, float *error) {
    float worst = 0;
    if (error) *error = 0;
    if (!m || !m->nidx || ratio >= 1) return syl_mesh_optimize(m);
    uint32_t *out = malloc(m->nidx * sizeof *out);
    if (!out) return SYL_ELIMIT;
    size_t at = 0;
    int ng = 0;
    for (int g = 0; g < m->ngroups; g++) {
        const SylMeshGroup *gr = &m->groups[g];
        bool chosen = kind < 0 || m->materials[gr->material].kind == kind;
        size_t target = chosen ? (size_t)((double)gr->count / 3 * ratio) * 3 : gr->count, n = gr->count;
        float e = 0;
        if (target < n) {
            n = meshopt_simplify(out + at, m->idx + gr->first, gr->count, m->pos, m->nverts, 3 * sizeof(float), target,
                                 max_error, 0, &e);
            /* Many small parts (leaves, twigs) cannot collapse edge by edge below a few
             * triangles each: the sloppy simplifier merges them on a grid instead. */
            if (n > target + target / 2) {
                float es = 0;
                size_t ns = meshopt_simplifySloppy(out + at, m->idx + gr->first, gr->count, m->pos, m->nverts,
                                                   3 * sizeof(float), target, max_error, &es);
                if (ns > 0 && ns < n) n = ns, e = es;
                else n = meshopt_simplify(out + at, m->idx + gr->first, gr->count, m->pos, m->nverts,
                                          3 * sizeof(float), target, max_error, 0, &e);
            }
        } else {
            memcpy(out + at, m->idx + gr->first, n * sizeof *out);
        }
        if (e > worst) worst = e;
        if (!n) continue;
        m->groups[ng] = (SylMeshGroup){(uint32_t)at, (uint32_t)n, gr->material};
        ng++;
        at += n;
    }
    memcpy(m->idx, out, at * sizeof *out);
    free(out);
    m->nidx = at;
    m->ngroups = ng;
    if (error) *error = worst * meshopt_simplifyScale(m->pos, m->nverts, 3 * sizeof(float));
    return syl_mesh_optimize(m);
}
