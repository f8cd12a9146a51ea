/* The shared environment of a scene: one per scene, read and written by every plant in it.
 *
 *   light    a shadow-propagation grid (shadow.h) or sky exposure by rays (sky.h)
 *   space    the occupied points (every metamer end), the global marker cloud (markers.h),
 *            and rounds of space colonization over them (space.h)
 *   obstacles triangle meshes from OBJ files in an Embree scene (obstacles.h)
 *   ground   a plane at a height; terrain meshes are obstacles
 *
 * Plants register their metamers here (shadow casters, occupants). L-system plants drawn by
 * the turtle are static occupants: registered once when they are drawn before the trees grow,
 * or replaced every year when they derive in lockstep with the trees (scene/lsys.c).
 *
 * The same type is the world of an open L-system drawn alone or in turn (scene/open.c): then
 * only its shadow grid and ?E's probes are used, and Embree starts when sky exposure is first
 * asked (env_device). What a plant brings — where it stands, its own casters — stays with it;
 * ?E answers read the world through a ProbeWorld (env_probe_world). */
#ifndef SYL_ENV_H
#define SYL_ENV_H
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "sylva/sylva.h"
#include "util/lazy_embree.h"

#include "env/markers.h"
#include "env/obstacles.h"
#include "env/pointgrid.h"
#include "env/probe.h"
#include "env/shadow.h"
#include "env/sky.h"

/* ?E's view beyond the shadow grid: the points crowding and sky exposure see, their grid and
 * the sky scene of their spheres, rebuilt in steps that ask. */
typedef struct EnvProbes {
    float (*pts)[3];
    size_t pts_cap;
    PointGrid occ;
    SkyScene sky;
} EnvProbes;

typedef struct Env {
    RTCDevice dev;
    SylSink sink;          /* where it reports (copied; report NULL: nowhere) */
    int threads;
    float ground;          /* the ground plane's height */
    float sun[3];          /* unit, towards the sun */
    Obstacles obstacles;
    bool shadow_on;
    ShadowGrid shadow;
    bool sky_on;
    SkyScene sky;
    bool cloud_on;
    MarkerCloud cloud;
    float occupancy;       /* radius, model units */
    PointGrid occupied;    /* metamer ends of every plant, rebuilt once a year */
    float *statics;        /* static occupants (L-system segment ends): 3 floats each */
    size_t nstatic, static_cap;
    EnvProbes probes;      /* ?E's points, point grid and sky scene */
} Env;

/* SYL_OK, or SYL_ELIMIT when Embree cannot start. */
int env_init(Env *e, int threads, const SylSink *sink);
/* An environment whose Embree device starts when first asked for (env_device): a plant's world
 * for ?E, with a shadow grid of probe_shadow_params. */
void env_init_probes(Env *e, const ShadowParams *shadow, float ground, const SylSink *sink);
void env_free(Env *e);
/* The Embree device, started now if not yet (NULL when it cannot start). */
RTCDevice env_device(Env *e);
/* Room for n of ?E's points (e->probes.pts); false when out of memory. */
bool env_probe_points(Env *e, size_t n);
/* The read-only view of ?E answers: e's shadow grid (when on), ?E's point grid and sky
 * scene; the obstacles, ground and default radius given, probes relative to at. */
ProbeWorld env_probe_world(const Env *e, float voxel, float ground, const Obstacles *o, const float at[3]);
bool env_add_static(Env *e, const float pos[3]);
/* Forget the static occupants (keeping their memory), to add this year's. */
static inline void env_clear_statics(Env *e) { e->nstatic = 0; }
/* Is p below the ground plane? */
static inline bool env_below_ground(const Env *e, const float p[3]) { return p[1] < e->ground; }

#endif
