/* A mesh's private record (mesh/store.h). */
#include <stdlib.h>

#include "mesh/store.h"

struct SylMeshStore *mesh_store(SylMesh *m) {
    if (!m->store) m->store = calloc(1, sizeof *m->store);
    return m->store;
}

void mesh_mark_spare(SylMesh *m) {
    struct SylMeshStore *st = mesh_store(m);
    if (st) st->spare = true;
}
