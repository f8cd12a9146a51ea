/* meshoptimizer over a SylMesh: reorder triangles for the GPU's vertex cache and vertices
 * for fetch locality, and simplify toward a triangle budget. Groups are processed one at a
 * time, so a triangle never changes material. */
#include <meshoptimizer.h>
#include <stdlib.h>
#include <string.h>

#include "sylva/mesh.h"

/* Vertices in first-use order, unused ones dropped; every attribute stream remapped. */
static int reorder_vertices(SylMesh *m) {
    if (!m->nverts || !m->nidx) return SYL_OK;
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
    if (m->node) {
        meshopt_remapVertexBuffer(tmp, m->node, m->nverts, sizeof *m->node, remap);
        memcpy(m->node, tmp, nv * sizeof *m->node);
    }
    m->nverts = nv; /* the arrays keep their capacity (and the renderer's padding) */
    free(remap);
    free(tmp);
    return SYL_OK;
}

int syl_mesh_optimize(SylMesh *m) {
    if (!m || !m->nidx) return SYL_OK;
    uint32_t *tmp = malloc(m->nidx * sizeof *tmp);
    if (!tmp) return SYL_ELIMIT;
    for (int g = 0; g < m->ngroups; g++) {
        uint32_t *ix = m->idx + m->groups[g].first;
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
