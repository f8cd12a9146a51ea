/* What the library keeps about a mesh it made (SylMesh.store), out of the public struct: how
 * its arrays are held and the budget they count against. A mesh made by hand has none. */
#ifndef SYL_MESH_STORE_H
#define SYL_MESH_STORE_H
#include <stdbool.h>
#include <stdint.h>

#include "sylva/mesh.h"

struct SylMeshStore {
    void *block;       /* non-NULL: pos, nrm, uv and idx live in this one allocation
                          (syl_mesh_build's), freed once by syl_mesh_free */
    SylBudget *budget; /* what the arrays are counted against (NULL: nothing) */
    uint64_t charged;
    bool spare;        /* pos has room for a vertex past the last (Embree reads 16 bytes at a time) */
};

/* m's store, made when it has none; NULL when out of memory. */
struct SylMeshStore *mesh_store(SylMesh *m);
/* Say that m->pos has room for a vertex past the last, so that Embree may read it in place;
 * without memory for the store, nothing is said and a reader copies the vertices. */
void mesh_mark_spare(SylMesh *m);
static inline bool mesh_has_spare(const SylMesh *m) { return m->store && m->store->spare; }

#endif
