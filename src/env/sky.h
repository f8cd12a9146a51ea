/* Sky exposure, the second light model: the share of rays from a bud that reach the sky,
 * cosine-weighted about the sun's direction, through an Embree scene of the obstacles and
 * of every plant's foliage (a sphere of a given radius at each metamer's end). The scene is
 * rebuilt once a year; rays come from the bud's own random stream, so the answer does not
 * depend on threads. */
#ifndef SYL_ENV_SKY_H
#define SYL_ENV_SKY_H
#include <stdbool.h>
#include <stddef.h>

#include "util/lazy_embree.h"

#include "env/obstacles.h"
#include "util/rng.h"

typedef struct SkyScene {
    RTCScene scene;
    float *spheres; /* 4 per sphere: x, y, z, radius */
    size_t n, cap;
} SkyScene;

/* Start a new year's scene: spheres are added, then sky_commit. */
void sky_reset(SkyScene *s);
bool sky_add(SkyScene *s, const float pos[3], float radius);
int sky_commit(SkyScene *s, RTCDevice dev, const Obstacles *o);
void sky_free(SkyScene *s);
/* The share of rays (0..1) from pos that escape; rays start beyond tnear (the bud's own
 * foliage). */
float sky_exposure(const SkyScene *s, const float pos[3], const float sun[3], int rays, Rng *rng, float tnear);

#endif
