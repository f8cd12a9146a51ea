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

/* Looks per species and age class, one of which each plant wears (by a hash of its id), so a
 * stand is not one clone: growing models at ages spread through the class, others with other
 * seeds. */
enum { FOREST_VARIANTS = 3, FOREST_LOOKS = SYL_ECO_MAX_SPECIES * SYL_FOREST_CLASSES * FOREST_VARIANTS };

struct SylForest {
    const SylEcoModel *m;
    const SylTerrain *t;
    SylMesh *ground;
    Look looks[FOREST_LOOKS];
    int proto_of[SYL_ECO_MAX_SPECIES][SYL_FOREST_CLASSES][FOREST_VARIANTS]; /* -1: nothing drawn */
    SylRenderProto protos[FOREST_LOOKS];
    int nprotos;
    int proto_species[FOREST_LOOKS], proto_class[FOREST_LOOKS], proto_variant[FOREST_LOOKS];
    SylTextureCache *textures; /* the caller's (SylForestOptions), may be NULL */
};

/* A plant's age class for its species: floor(C h / height_max), clamped. */
int forest_class_of(const SylEcoSpecies *sp, float h);

#endif
