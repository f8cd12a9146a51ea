/* meshoptimizer over a SylMesh: reorder triangles for the GPU's vertex cache and vertices
 * for fetch locality, and simplify toward a triangle budget. Groups are processed one at a
 * time, so a triangle never changes material. */
#include <meshoptimizer.h>
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

/* True when no order can do better: each vertex the group uses enters the cache once (as
 * leaves drawn one after another do). Then the group keeps its order, which is cheaper. */
static bool cache_optimal(const uint32_t *ix, size_t n, size_t nverts) {
    if (!n) return true;
    struct meshopt_VertexCacheStatistics st = meshopt_analyzeVertexCache(ix, n, nverts, 16, 0, 0);
    uint32_t lo = UINT32_MAX, hi = 0;
    for (size_t i = 0; i < n; i++) lo = ix[i] < lo ? ix[i] : lo, hi = ix[i] > hi ? ix[i] : hi;
    /* distinct vertices: count them in a bitmap over [lo, hi] */
    size_t span = (size_t)hi - lo + 1, distinct = 0;
    uint64_t *seen = calloc((span + 63) / 64, sizeof *seen);
    if (!seen) return false;
    for (size_t i = 0; i < n; i++) {
        size_t b = ix[i] - lo;
        distinct += !(seen[b / 64] >> (b % 64) & 1);
        seen[b / 64] |= (uint64_t)1 << (b % 64);
    }
    free(seen);
    return st.vertices_transformed <= distinct;
}

int syl_mesh_optimize(SylMesh *m) {
    if (!m || !m->nidx) return SYL_OK;
    uint32_t *tmp = malloc(m->nidx * sizeof *tmp);
    if (!tmp) return SYL_ELIMIT;
    for (int g = 0; g < m->ngroups; g++) {
        uint32_t *ix = m->idx + m->groups[g].first;
        if (cache_optimal(ix, m->groups[g].count, m->nverts)) continue;
        meshopt_optimizeVertexCache(tmp, ix, m->groups[g].count, m->nverts);
        memcpy(ix, tmp, m->groups[g].count * sizeof *tmp);
    }
    free(tmp);
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
