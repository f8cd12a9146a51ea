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
    meshopt_remapIndexBuffer(m->idx, m->idx, m->nidx, remap);
    float *streams[3] = {m->pos, m->nrm, m->uv};
    for (int s = 0; s < 3; s++) {
        size_t k = s == 2 ? 2 : 3;
        meshopt_remapVertexBuffer(tmp, streams[s], m->nverts, k * sizeof(float), remap);
        memcpy(streams[s], tmp, nv * k * sizeof(float));
    }
    m->nverts = nv; /* the arrays keep their capacity (and the renderer's padding) */
    free(remap);
    free(tmp);
    return SYL_OK;
}

/* A group already as good as any order can be: each vertex fetched once (ACMR, vertices
 * transformed per triangle, equals its used vertices per triangle), as the mesher emits
 * leaves (small fans of their own vertices). Reordering those took a third of the time of
 * meshing a willow and gained nothing. */
static bool at_best_order(const uint32_t *ix, size_t count, size_t nverts) {
    if (count < 3) return true;
    uint8_t *seen = calloc(nverts / 8 + 1, 1);
    if (!seen) return false; /* then optimize, which reports the shortage */
    size_t used = 0;
    for (size_t i = 0; i < count; i++)
        if (!(seen[ix[i] >> 3] & (1u << (ix[i] & 7)))) seen[ix[i] >> 3] |= (uint8_t)(1u << (ix[i] & 7)), used++;
    free(seen);
    struct meshopt_VertexCacheStatistics st = meshopt_analyzeVertexCache(ix, count, nverts, 16, 0, 0);
    return st.vertices_transformed <= used;
}

int syl_mesh_optimize(SylMesh *m) {
    if (!m || !m->nidx) return SYL_OK;
    uint32_t *tmp = malloc(m->nidx * sizeof *tmp);
    if (!tmp) return SYL_ELIMIT;
    for (int g = 0; g < m->ngroups; g++) {
        uint32_t *ix = m->idx + m->groups[g].first;
        if (at_best_order(ix, m->groups[g].count, m->nverts)) continue;
        meshopt_optimizeVertexCache(tmp, ix, m->groups[g].count, m->nverts);
        memcpy(ix, tmp, m->groups[g].count * sizeof *tmp);
    }
    free(tmp);
    return reorder_vertices(m);
}

int syl_mesh_simplify(SylMesh *m, double ratio, float max_error, float *error) {
    float worst = 0;
    if (error) *error = 0;
    if (!m || !m->nidx || ratio >= 1) return syl_mesh_optimize(m);
    uint32_t *out = malloc(m->nidx * sizeof *out);
    if (!out) return SYL_ELIMIT;
    size_t at = 0;
    int ng = 0;
    for (int g = 0; g < m->ngroups; g++) {
        const SylMeshGroup *gr = &m->groups[g];
        size_t target = (size_t)((double)gr->count / 3 * ratio) * 3, n = gr->count;
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
