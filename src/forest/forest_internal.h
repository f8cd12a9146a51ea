/* Inside the forest module: what forest.c makes and forest_glb.c writes. */
#ifndef SYL_FOREST_INTERNAL_H
#define SYL_FOREST_INTERNAL_H
#include "sylva/forest.h"
#include "sylva/lod.h"

/* One look: a species' model at an age class, scaled to height 1 with its base at the origin. */
typedef struct Look {
    SylMesh *mesh;
    SylLodChain lod; /* lod.level[1].mesh: the coarse mesh, or n == 0 */
} Look;

struct SylForest {
    const SylEcoModel *m;
    const SylTerrain *t;
    SylMesh *ground;
    Look looks[SYL_ECO_MAX_SPECIES * SYL_FOREST_CLASSES];
    int proto_of[SYL_ECO_MAX_SPECIES][SYL_FOREST_CLASSES]; /* -1: nothing drawn */
    SylRenderProto protos[SYL_ECO_MAX_SPECIES * SYL_FOREST_CLASSES];
    int nprotos;
    int proto_species[SYL_ECO_MAX_SPECIES * SYL_FOREST_CLASSES], proto_class[SYL_ECO_MAX_SPECIES * SYL_FOREST_CLASSES];
};

/* A plant's age class for its species: floor(C h / height_max), clamped. */
int forest_class_of(const SylEcoSpecies *sp, float h);

#endif
