/* A piece's vertices put in the order its own triangles first use them, right after it is
 * emitted (in cache, on the thread that wrote it). Pieces are laid out in the order their
 * triangles come, so when each piece is in first-use order the whole mesh is, and
 * syl_mesh_optimize's vertex-fetch pass (meshoptimizer's remap, which copied every attribute
 * of a million-vertex mesh through fresh memory) finds nothing to do. It gives the same
 * vertices in the same order as that pass: the files do not change. A piece it cannot reorder
 * (out of memory) is left as it was, for that pass to do. */
#include <stdlib.h>
#include <string.h>

#include "mesh/mesh_internal.h"

void mesh_first_use_free(MeshFirstUse *f) {
    free(f->id);
    free(f->tmp);
    *f = (MeshFirstUse){0};
}

/* Whether the piece's triangles use its nv vertices from vert on in order (and none outside). */
static bool ordered(const SylMesh *m, size_t vert, size_t nv, const MeshRun *runs, size_t nruns, bool *inside) {
    size_t next = vert;
    bool in_order = true;
    *inside = true;
    for (size_t r = 0; r < nruns; r++) {
        const uint32_t *ix = m->idx + runs[r].idx;
        for (size_t i = 0; i < 3 * (size_t)runs[r].tris; i++) {
            if (ix[i] < vert || ix[i] >= vert + nv) return *inside = false, false;
            if (ix[i] == next) next++;
            else if (ix[i] > next) in_order = false;
        }
    }
    return in_order && next == vert + nv;
}

static void permute(float *a, int k, size_t nv, const uint32_t *id, float *tmp) {
    memcpy(tmp, a, nv * (size_t)k * sizeof *a);
    for (size_t l = 0; l < nv; l++) memcpy(a + (size_t)k * id[l], tmp + (size_t)k * l, (size_t)k * sizeof *a);
}

void mesh_first_use(MeshFirstUse *f, SylMesh *m, size_t vert, size_t nv, const MeshRun *runs, size_t nruns) {
    bool inside;
    if (!nv || ordered(m, vert, nv, runs, nruns, &inside) || !inside) return;
    if (nv > f->cap) {
        uint32_t *id = realloc(f->id, nv * sizeof *id);
        if (id) f->id = id;
        float *tmp = id ? realloc(f->tmp, 3 * nv * sizeof *tmp) : NULL;
        if (!tmp) return;
        f->tmp = tmp, f->cap = nv;
    }
    uint32_t *id = f->id, next = 0;
    memset(id, 0xff, nv * sizeof *id);
    for (size_t r = 0; r < nruns; r++) {
        uint32_t *ix = m->idx + runs[r].idx;
        for (size_t i = 0; i < 3 * (size_t)runs[r].tris; i++) {
            uint32_t *l = &id[ix[i] - vert];
            if (*l == UINT32_MAX) *l = next++;
            ix[i] = (uint32_t)vert + *l;
        }
    }
    for (size_t l = 0; l < nv; l++) /* vertices no triangle uses: last, in their order */
        if (id[l] == UINT32_MAX) id[l] = next++;
    permute(m->pos + 3 * vert, 3, nv, id, f->tmp);
    permute(m->nrm + 3 * vert, 3, nv, id, f->tmp);
    permute(m->uv + 2 * vert, 2, nv, id, f->tmp);
}
