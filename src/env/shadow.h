/* Shadow propagation (Palubicki et al. 2009): a voxel grid of shadow values. Every caster
 * (a metamer's end) adds a*b^-q to the voxels (I±p, J-q, K±p), p <= q, q = 0..depth: a
 * pyramid below it, sheared away from the sun when the sun is not overhead. A bud's light
 * is Q = max(C - s + a, 0): adding a back cancels its own shadow.
 *
 * Shadow is kept in fixed point (1/4096), so adding and removing a caster (when a branch is
 * shed) are exact and the grid never depends on the order of updates. The grid grows with
 * the scene: it always holds every pyramid whole, down to the ground.
 *
 * Updates are incremental and cost O(depth) per caster, not O(depth^3): a level of a pyramid
 * is a square, written as its four corners into a difference grid; once a batch of casters
 * is in, the differences are summed (prefix sums in x and z) over the batch's bounding box
 * only, added to the shadow, and cleared. */
#ifndef SYL_ENV_SHADOW_H
#define SYL_ENV_SHADOW_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

enum { SHADOW_MAX_DEPTH = 64, SHADOW_ONE = 4096 };

typedef struct ShadowParams {
    float voxel;  /* edge, model units */
    float full;   /* C: light in the open */
    float a, b;   /* a caster's own shadow and the falloff per level */
    int depth;    /* q_max */
    float sun[3]; /* towards the sun; (0, 1, 0): straight down */
} ShadowParams;

typedef struct ShadowGrid {
    ShadowParams p;
    float inv;                               /* 1 / voxel */
    int32_t layer[SHADOW_MAX_DEPTH + 1];     /* a*b^-q in fixed point */
    int shift_x[SHADOW_MAX_DEPTH + 1], shift_z[SHADOW_MAX_DEPTH + 1]; /* the sun's shear */
    int reach;                               /* depth + the largest shear: the pyramid's half width */
    int x0, y0, z0, nx, ny, nz;              /* voxel coordinates of the first voxel; sizes */
    int ymin;                                /* the ground's level: pyramids stop there */
    int32_t *s;
    uint32_t *d;                             /* the difference grid: zero between batches */
    uint32_t *row;                           /* a row of running sums */
    size_t max_voxels;
} ShadowGrid;

void shadow_init(ShadowGrid *g, const ShadowParams *p, float ground_y);
void shadow_free(ShadowGrid *g);
/* Add (sign +1) or remove (-1) the pyramids of n casters. False when the grid would need
 * more than max_voxels (nothing is changed then). */
bool shadow_cast(ShadowGrid *g, const float (*pos)[3], size_t n, int sign);
/* Like shadow_cast for points given by stride (pos of caster i at base + i * stride floats). */
bool shadow_cast_strided(ShadowGrid *g, const float *base, size_t stride, size_t n, int sign);
float shadow_at(const ShadowGrid *g, const float pos[3]);    /* s */
float shadow_light(const ShadowGrid *g, const float pos[3]); /* Q = max(C - s + a, 0) */
/* The direction of least shadow: minus the gradient of s (central differences), not
 * normalised; zero in uniform light. */
void shadow_gradient(const ShadowGrid *g, const float pos[3], float out[3]);
size_t shadow_voxels(const ShadowGrid *g);

#endif
