/* The environment of an open L-system (docs/language.md, "Open L-systems"): answers the ?E
 * modules of every step at the turtle's position and heading.
 *
 *   ?E(0, q)     light: Q = C - s, in 0..C, of a shadow grid (probe_shadow_params) holding the plant's own segment ends of this step and the scene's
 *                static casters; at a segment's end, that end's own shadow a does not count
 *   ?E(1, n, r)  space: how many segment ends (own and the scene's) lie within r of the
 *                point r ahead along the heading (r defaults to the voxel)
 *   ?E(2, d)     obstacle distance along the heading: the nearest obstacle surface or the
 *                ground plane, OPEN_FAR when neither is hit
 *   ?E(3, e, n)  sky exposure: the share of n rays to the sky that no segment end's sphere
 *                (radius 0.4 voxel) or obstacle stops (env/probe.h)
 *
 * Stand-alone (no scene), the plant is alone on the ground plane y = 0 with no obstacles. The
 * shadow grid is updated incrementally (last step's casters replaced by this step's: only
 * voxels whose count of ends changed are cast, exact in fixed point), and only in steps that
 * ask for light; the point grid only in steps that ask for space. Positions are the plant's,
 * moved by `at` into the scene. */
#ifndef SYL_ENV_OPEN_H
#define SYL_ENV_OPEN_H
#include <stdio.h>

#include "env/env.h"
#include "sylva/sylva.h"
#include "turtle/turtle.h"

#define OPEN_FAR PROBE_FAR

typedef struct OpenEnvParams {
    float voxel;                /* the shadow grid's voxel and the default space radius */
    float ground;               /* the ground plane's height */
    float sun[3];               /* towards the sun: (0, 1, 0) overhead */
    float at[3];                /* where the plant stands */
    const Obstacles *obstacles; /* NULL: none */
    const float *statics;       /* the scene's other plants: 3 floats each, scene coordinates */
    size_t nstatic;
    FILE *diag;
    const SylSink *sink;        /* or as records to this sink instead; NULL: diag */
} OpenEnvParams;

typedef struct OpenEnv {
    OpenEnvParams P;
    Env world;        /* its shadow grid (the ?E parameters), ?E's points and sky scene */
    bool statics_cast;
    ShadowSet own;    /* own segment ends now in the shadow grid */
    SylEnvFill fill;    /* what the turtle collects for the answers */
    SylOpenFill probes; /* open_env_fill's light probes */
} OpenEnv;

void open_env_init(OpenEnv *e, const OpenEnvParams *p);
void open_env_free(OpenEnv *e);
/* Answer the probes the turtle collected in fill: e's world brought up to date first. */
int open_env_answer(OpenEnv *e, int step, const SylEnvFill *fill, double *par);
/* The turtle's reading of s and the answers in one, as the turtle's query pass and
 * open_env_answer give them (fill: the SylEnvFill they would use), in less time and memory:
 * light probes are kept compact (syl_turtle_fill). */
int open_env_fill(OpenEnv *e, const SylProgram *p, SylString *s, SylEnvFill *fill, int step);
/* The query environment of an OpenEnv (user: the OpenEnv): open_env_fill for models with ?E,
 * the turtle's query pass alone for the others. */
extern const SylQueryOps open_env_ops;

#endif
