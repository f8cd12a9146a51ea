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
 * is in, the differences are summed (prefix sums in x and z) over each plane's box of the
 * batch only, added to the shadow, and cleared. */
#ifndef SYL_ENV_SHADOW_H
#define SYL_ENV_SHADOW_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "util/budget.h"

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
    int32_t *pbox;                           /* per plane: the box of its differences (integrate) */
    size_t max_voxels;
    Budget *mem;       /* the memory budget the grids count against (NULL: none); set after init */
    uint64_t charged;
    bool refused;      /* the last grow was refused by mem (not by max_voxels) */
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

/* floor(v * inv) clamped to +-1e8 (NaN: -1e8): the voxel coordinate of v; cheaper than floorf,
 * and without branches. */
static inline int shadow_cell(float v, float inv) {
    float f = v * inv;
    f = f > -1e8f ? f : -1e8f; /* NaN too */
    f = f < 1e8f ? f : 1e8f;
    int i = (int)f;
    return i - (f < (float)i);
}
/* For many look-ups in a row (the grid unchanged): the index into g->s of the voxel holding
 * pos, -1 outside the grid; shadow_at(g, pos) is shadow_value(g, shadow_index(g, pos)). */
static inline ptrdiff_t shadow_index(const ShadowGrid *g, const float pos[3]) {
    if (!g->s) return -1;
    int I = shadow_cell(pos[0], g->inv) - g->x0, J = shadow_cell(pos[1], g->inv) - g->y0,
        K = shadow_cell(pos[2], g->inv) - g->z0;
    if (I < 0 || J < 0 || K < 0 || I >= g->nx || J >= g->ny || K >= g->nz) return -1;
    return (ptrdiff_t)(((size_t)J * (size_t)g->nz + (size_t)K) * (size_t)g->nx + (size_t)I);
}
static inline float shadow_value(const ShadowGrid *g, ptrdiff_t at) {
    return at < 0 ? 0 : (float)g->s[at] * (1.0f / SHADOW_ONE);
}

/* A set of casters replaced as a whole again and again (an open L-system's segment ends,
 * step after step), kept in the grid as a count per voxel: a caster's pyramid depends only on
 * the voxel it stands in, so a replacement casts only the voxels whose count changed, with
 * the same shadow as removing every old caster and adding every new one. */
typedef struct ShadowSet {
    uint64_t *key;             /* per slot: voxel index + 1 in the layout below; 0: free */
    uint32_t *count;           /* casters of the voxel now in the grid */
    uint32_t *want;            /* and in the replacement being built (0 between) */
    size_t cap, n;             /* slots (a power of two), used */
    int x0, y0, z0, nx, nz;    /* the grid's layout the keys were made in */
    uint64_t *delta;           /* scratch: changed voxels */
    size_t delta_cap;
} ShadowSet;

/* Replace the set's casters in the grid by n casters at pos[i] + off (added in float). False
 * when the grid would need more than max_voxels (the grid and the set are then unchanged), or
 * out of memory. */
bool shadow_set_replace(ShadowGrid *g, ShadowSet *set, const float (*pos)[3], size_t n, const float off[3]);
void shadow_set_free(ShadowSet *set);

#endif
