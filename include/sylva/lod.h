/* Levels of detail: a chain of meshes of one skeleton, each cheaper than the last, for
 * real-time engines (docs/mesh.md, "Levels of detail"). Level k drops the finest branch
 * orders and thin stems (Zamuda's truncation by branch order and radius), keeps a share of
 * the leaves and enlarges them so the foliage covers about as much (Weber–Penn's leaf
 * quality), meshes with fewer sides, and simplifies with meshoptimizer. */
#ifndef SYLVA_LOD_H
#define SYLVA_LOD_H
#include "mesh.h"
#include "skeleton.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { SYL_LOD_MAX = 8 };

typedef struct SylLodLevel {
    SylMesh *mesh;      /* level 0: the caller's mesh (not freed by syl_lod_free) */
    int level;          /* k of LODk */
    int max_order;      /* stems of this branch order or less are kept */
    float min_radius;   /* and only those at least this thick (model units) */
    float leaf_keep;    /* share of leaves kept, 0..1 */
    float leaf_scale;   /* the survivors' enlargement: 1 / sqrt(leaf_keep), at most 2 */
    float cluster_leaves; /* > 0: leaves and needles drawn as clusters (SYL_LEAVES_CLUSTERS) of
                             about this many on one card, all of them kept (leaf_keep 1) */
    float coverage;     /* MSFT_screencoverage: shown while the plant's screen height is above
                           this share of the screen; the last level's is where it is culled */
    float error;        /* meshoptimizer's deviation, model units */
    SylInstances *sets; /* with instanced leaves, the level's (level 0: the caller's, not
                           freed by syl_lod_free) */
    int nsets;
} SylLodLevel;

typedef struct SylLodChain {
    int n;              /* levels: LOD0 .. LOD(n-1) */
    SylLodLevel level[SYL_LOD_MAX + 1];
    /* A last level drawn with a picture (an impostor's billboards; not freed here): its
     * material atlas_material becomes an alpha-tested (MASK) material textured with
     * atlas, atlas_w x atlas_h RGBA; extras (JSON object text, may be NULL) goes in its
     * node's extras. */
    const uint8_t *atlas;
    int atlas_w, atlas_h, atlas_material;
    const char *extras;
} SylLodChain;

/* Build levels 1..levels (1 to SYL_LOD_MAX) from s, meshed with mo as lod0 was (with
 * instanced leaves, each level also gets its leaves' instance sets). lod0 is
 * optimised for the vertex cache in place and becomes level 0. SYL_OK, SYL_ELIMIT or
 * SYL_EUSAGE. The chain does not depend on mo->threads. */
int syl_lod_build(const SylSkeleton *s, const SylMeshOptions *mo, SylMesh *lod0, int levels, SylLodChain *out);
void syl_lod_free(SylLodChain *c);
/* The screen coverage at which level k of a chain of levels + 1 hands over to the next (for
 * k = levels: where the plant is culled). */
float syl_lod_coverage(int k, int levels);

/* The .glb of a chain: nodes NAME_LOD0 .. NAME_LODn (each with its instance sets), MSFT_lod
 * on LOD0 (docs/mesh.md). */
int syl_lod_write_glb(const SylLodChain *c, const char *path, const SylSink *sink);

/* How far a level strays from LOD0 (src/plant/lodcheck.c, `sylva mesh --lod N --stats` and
 * --image). silhouette: LOD0 and level k (1 .. n-1) rendered from one camera (from 35 degrees
 * up, or the front for a flat plant) at the size the plant has on a 1080-line screen where
 * level k switches on (32 to 1024 pixels), their silhouettes (coverage >= 1/2) compared pixel
 * by pixel. SYL_OK, SYL_EUSAGE (no such level) or the renderer's status. picture: every level
 * rendered size x size by LOD0's camera, side by side. */
typedef struct SylLodCheckOptions {
    int threads;   /* <= 0: all cores; nothing depends on it */
    int size;      /* syl_lod_draw_levels's side of a level (0: 256) */
    FILE *diag;    /* where the renderer's problems are reported; NULL: nowhere */
    const SylSink *sink; /* or as records to this sink instead (sylva.h); NULL: diag */
} SylLodCheckOptions;
typedef struct SylLodSilhouette {
    int pixels;             /* the square pictures' side */
    size_t covered, differ; /* pixels inside LOD0's silhouette; pixels inside one only */
    double percent;         /* differ / covered, in percent */
    double soft;            /* the sum of coverage differences over LOD0's coverage, percent */
} SylLodSilhouette;
int syl_lod_check_silhouette(const SylLodChain *c, int k, const SylLodCheckOptions *o, SylLodSilhouette *out);
int syl_lod_draw_levels(const SylLodChain *c, const SylLodCheckOptions *o, SylPicture *out);

#ifdef __cplusplus
}
#endif

#endif
