/* What an ?E module reads (docs/language.md §19), one answer per probe, from whatever world
 * the plant stands in: alone or with other L-systems (scene/open.c), or beside trees
 * (scene/lsys.c). Those modules keep the world up to date; this one only reads it.
 *
 *   ?E(0, q)        light: (C - s) / C of a shadow grid, in 0..1; at a segment's own end its
 *                   own shadow a does not count
 *   ?E(1, n, r)     crowding: segment ends within r of the point r ahead (r: the voxel)
 *   ?E(2, d)        distance along the heading to an obstacle or the ground (PROBE_FAR: none)
 *   ?E(3, e, rays)  sky exposure: the share of `rays` (default 16) cosine-weighted rays to
 *                   the sky that no foliage sphere or obstacle stops, in 0..1 */
#ifndef SYL_ENV_PROBE_H
#define SYL_ENV_PROBE_H
#include <stdbool.h>

#include "env/obstacles.h"
#include "env/pointgrid.h"
#include "env/shadow.h"
#include "env/sky.h"
#include "sylva/sylva.h"

#define PROBE_FAR 1e9

enum { PROBE_LIGHT = 0, PROBE_SPACE = 1, PROBE_DISTANCE = 2, PROBE_SKY = 3 };

typedef struct ProbeWorld {
    const ShadowGrid *shadow;   /* ?E(0); NULL: full light */
    const PointGrid *occ;       /* ?E(1) */
    float voxel;                /* ?E(1)'s default radius */
    const Obstacles *obstacles; /* ?E(2); NULL: none */
    float ground;               /* ?E(2)'s ground plane */
    const SkyScene *sky;        /* ?E(3); NULL: full exposure */
    float foliage;              /* the radius of a segment end's sphere in sky */
    float at[3];                /* the plant's place: probes are relative to it */
} ProbeWorld;

/* ?E(0)'s answer at pos: (C - s + (tip ? a : 0)) / C, in 0..1 (at a segment's end its own
 * shadow does not count). Inline: scene/open.c answers every apex of a step with it. */
static inline double probe_light(const ShadowGrid *g, const float pos[3], bool tip) {
    const ShadowParams *sp = &g->p;
    double v = (sp->full - shadow_value(g, shadow_index(g, pos)) + (tip ? sp->a : 0)) / sp->full;
    return v < 0 ? 0 : v < 1 ? v : 1;
}

/* The shadow grid of ?E light where no tree sets one (alone, in turn, beside trees without
 * `light shadow`): C = 1, a = 0.25, b = 2, depth 8 at the model's step; a sun at or below the
 * horizon is overhead. */
static inline ShadowParams probe_shadow_params(float voxel, const float sun[3]) {
    ShadowParams sp = {.voxel = voxel, .full = 1, .a = 0.25f, .b = 2, .depth = 8, .sun = {sun[0], sun[1], sun[2]}};
    if (!(sp.sun[1] > 0)) sp.sun[0] = sp.sun[2] = 0, sp.sun[1] = 1;
    return sp;
}
/* The radius of a segment end's sphere in sky exposure. */
static inline float probe_foliage(float voxel) { return 0.4f * voxel; }

/* The kinds the probes of a step ask for: bit k for ?E(k, ...). */
unsigned probe_kinds(const SylEnvFill *fill, const double *par);
/* Write every probe's answer into par; the step keys the sky rays' random streams. */
void probe_answer(const ProbeWorld *w, const SylEnvFill *fill, int step, double *par);
/* The foliage of sky exposure: a sphere of radius r at every segment end (own ends first,
 * then others, scene coordinates), obstacles too; the scene is rebuilt. SYL_OK or SYL_ELIMIT. */
int probe_sky_build(SkyScene *s, RTCDevice dev, const Obstacles *o, const float (*ends)[3], size_t n,
                    const float at[3], const float *others, size_t nothers, float r);

#endif
