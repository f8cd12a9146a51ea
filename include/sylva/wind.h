/* Wind: sway of a plant's stems as a looping animation of joint rotations, for a skinned
 * mesh in a .glb (docs/mesh.md#wind). One joint per stem (axis) of the first levels (branch
 * orders below levels, as Sapling's armature); deeper stems and the organs on them follow
 * their nearest jointed ancestor. Each joint sways by Weber–Penn's two sines per axis
 * (amplitude from the stem's length over its radius, a phase per stem from a hash of its id)
 * plus Zamuda's directed bend downwind (eqs. 3.35–3.38). */
#ifndef SYLVA_WIND_H
#define SYLVA_WIND_H
#include <stdint.h>

#include "mesh.h"
#include "skeleton.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct SylWindOptions {
    float speed;    /* wind speed, m/s (> 0) */
    float dir[2];   /* where it blows to, x and z (made unit; 0, 0: +x) */
    float seconds;  /* length of the loop; 0: 4 */
    int levels;     /* stems of branch order below this get a joint; 0: 2 */
    int fps;        /* keys per second; 0: 15 */
    SylBudget *budget; /* the stems, joints and keys (twice: the file's copy) count against it
                          (NULL: none); beyond it SYL_ELIMIT, said on diag, before the keys are made */
    FILE *diag;
    const SylSink *sink; /* or as records to this sink instead (sylva.h); NULL: diag */
} SylWindOptions;

/* A stem (axis) of the skeleton. */
typedef struct SylWindStem {
    int32_t joint;       /* its joint, or its nearest jointed ancestor's (-1: none) */
    int32_t parent;      /* the stem it grows on (-1: none) */
    float base[3];       /* where it starts */
    float dir[3];        /* unit direction of its first segment (0: none) */
    float length, radius; /* along its segments; at its base */
    float parent_radius; /* of the stem it grows on, where it leaves it (0: a root) */
    float phase;         /* 0..2π, from a hash of the stem's id */
    float stiffness;     /* 22.5 r / (22.5 r + L): 1 rigid, 0 limp */
    uint16_t order;
} SylWindStem;

typedef struct SylWindJoint {
    int32_t stem, parent; /* its stem; the parent joint (-1: a root) */
    float amplitude;      /* bound of its rotation angle at any time, radians */
    float frequency;      /* of its first sine, Hz (a whole number of cycles per loop) */
    /* Blending into the parent joint at the stem's base (docs/mesh.md#wind): the weight
     * goes from the parent to this joint between blend_start and blend_start + blend_length
     * along dir from the base (0, 0 for a root joint). */
    float blend_start, blend_length;
} SylWindJoint;

typedef struct SylWind {
    SylWindStem *stems;   /* by axis id */
    int32_t nstems;
    SylWindJoint *joints; /* parents before children */
    int32_t njoints;
    int nkeys;            /* key times k * seconds / (nkeys - 1); the last key is the first */
    float seconds;
    float *rot;           /* njoints x nkeys unit quaternions x, y, z, w (joint-major) */
    struct SylWindStore *store; /* the library's own: the memory budget it counts against
                                   until syl_wind_free (NULL: none) */
} SylWind;

/* The sway of s; radius: the mesher's radius of each node (syl_mesh_radii). SYL_OK,
 * SYL_EUSAGE (bad options) or SYL_ELIMIT. The result depends on nothing but s and o. */
int syl_wind_build(const SylSkeleton *s, const float *radius, const SylWindOptions *o, SylWind *out);
void syl_wind_free(SylWind *w);
/* The stem a node belongs to, for a vertex's node (SylMesh.node; -1 or out of range: stem 0). */
static inline int32_t syl_wind_stem_of(const SylSkeleton *s, const SylWind *w, int32_t node) {
    if (node < 0 || (size_t)node >= s->nnodes) return 0;
    int32_t a = s->nodes[node].axis;
    return a >= 0 && a < w->nstems ? a : 0;
}

/* m (meshed from s with SylMeshOptions.vertex_nodes) as a skinned .glb with w's joints and
 * its "wind" animation, and the shader attributes (docs/mesh.md#wind); n sets of instanced
 * leaves (may be 0; made with vertex_nodes too) hang from the joints they follow, as child
 * nodes. SYL_OK, SYL_EUSAGE (m has no vertex nodes), SYL_ELIMIT or SYL_EIO. */
int syl_wind_write_glb(const SylMesh *m, const SylInstances *sets, int n, const SylSkeleton *s, const SylWind *w,
                       const char *path, const SylSink *sink);

/* Each vertex of m's two joints and weights, as the .glb's JOINTS_0 and WEIGHTS_0 hold them
 * (joints[2 v], joints[2 v + 1]; weights bytes summing to 255, the larger first; a second
 * weight of 0 leaves its joint unused): for exporters that skin the mesh themselves (the
 * Blender add-on's armature). m is meshed from s with SylMeshOptions.vertex_nodes. */
void syl_wind_skin(const SylMesh *m, const SylSkeleton *s, const SylWind *w, int32_t *joints, uint8_t *weights);

/* A chain of levels of detail (lod.h) with wind: every level that has vertex nodes (of s)
 * skinned to w's one set of joints and driven by the one animation; the others (crossed
 * billboards) still. */
struct SylLodChain;
int syl_wind_write_glb_lods(const struct SylLodChain *c, const SylSkeleton *s, const SylWind *w, const char *path,
                            const SylSink *sink);

#ifdef __cplusplus
}
#endif

#endif
