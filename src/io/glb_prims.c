/* A mesh's glTF primitives: one per material group while the mesh has at most 65,535
 * vertices; above, each group is cut into runs of triangles whose vertices lie in a window
 * of at most 65,535, so that every primitive's indices are 16-bit (half the bytes of 32-bit
 * ones). The mesh is in first-use vertex order (syl_mesh_optimize), so consecutive
 * triangles use nearby vertices and the windows overlap little. */
#include <stdlib.h>

#include "io/glb.h"

enum { WINDOW = 65535 }; /* vertices a 16-bit primitive may use: 65,535 itself is the restart value */

/* Append a primitive; false when out of memory. */
static bool add(GlbPrims *p, size_t *cap, GlbPrim prim) {
    if (p->n == *cap) {
        size_t c = *cap ? 2 * *cap : 16;
        GlbPrim *a = realloc(p->prim, c * sizeof *a);
        if (!a) return false;
        p->prim = a, *cap = c;
    }
    p->prim[p->n++] = prim;
    return true;
}

bool glb_primitives(const SylMesh *m, GlbPrims *out) {
    *out = (GlbPrims){0};
    size_t cap = 0;
    out->split = m->nverts > WINDOW;
    for (int g = 0; g < m->ngroups; g++) {
        const SylMeshGroup *gr = &m->groups[g];
        if (!out->split) {
            if (!add(out, &cap, (GlbPrim){gr->first, gr->count, 0, m->nverts, g})) goto fail;
            continue;
        }
        uint32_t at = gr->first, end = gr->first + gr->count;
        while (at < end) {
            uint32_t lo = m->idx[at], hi = lo, t = at;
            for (; t < end; t += 3) { /* grow the run while its window fits */
                uint32_t a = m->idx[t], b = m->idx[t + 1], c = m->idx[t + 2];
                uint32_t l = a < b ? a : b, h = a > b ? a : b;
                l = l < c ? l : c, h = h > c ? h : c;
                l = l < lo ? l : lo, h = h > hi ? h : hi;
                if (h - l >= WINDOW) break;
                lo = l, hi = h;
            }
            if (t == at) { /* one triangle spans more than a window: 32-bit indices, one primitive a group */
                free(out->prim);
                *out = (GlbPrims){.wide = true};
                cap = 0;
                for (int k = 0; k < m->ngroups; k++)
                    if (!add(out, &cap, (GlbPrim){m->groups[k].first, m->groups[k].count, 0, m->nverts, k})) goto fail;
                return true;
            }
            if (!add(out, &cap, (GlbPrim){at, t - at, lo, (size_t)(hi - lo) + 1, g})) goto fail;
            at = t;
        }
    }
    return true;
fail:
    free(out->prim);
    *out = (GlbPrims){0};
    return false;
}
