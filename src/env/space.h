/* Space colonization, one round: buds look for markers in their perception cones, each
 * marker goes to the nearest bud that sees it, and a bud's optimal direction is the sum of
 * the unit vectors to its markers. Two kinds of markers:
 *
 *   per bud (Tázlar 2018): every bud throws its own markers into its cone, afresh each round;
 *     markers within the occupancy radius of a metamer or of another bud are dropped;
 *   global (Runions 2007, Palubicki 2009): the markers of a MarkerCloud, removed for good as
 *     metamers come near.
 *
 * Obstacles hide markers: a marker behind one is not seen by a bud. A spatial hash of the
 * buds keeps the cost linear in buds. The result does not depend on the thread count:
 * markers are made from each bud's random stream, matched in parallel, and summed in a fixed
 * order. */
#ifndef SYL_ENV_SPACE_H
#define SYL_ENV_SPACE_H
#include <stddef.h>
#include <stdint.h>

#include "env/markers.h"
#include "env/obstacles.h"
#include "env/pointgrid.h"

typedef struct SpaceBud {
    float pos[3], dir[3];  /* dir: unit */
    float reach;           /* perception distance, model units */
    float cos_half;        /* cosine of half the cone's angle */
    uint32_t markers;      /* per-bud variant: markers thrown */
    uint64_t key;          /* the bud's random stream */
} SpaceBud;

typedef struct SpaceResult {
    float dir[3];    /* unit, or 0 when no marker */
    uint32_t count;  /* markers won */
} SpaceResult;

enum { SPACE_PER_BUD, SPACE_GLOBAL };

typedef struct SpaceQuery {
    int variant;
    float occupancy;           /* model units */
    float ground;              /* no markers below */
    const PointGrid *nodes;    /* occupied points (metamer ends); may be empty */
    const Obstacles *obstacles;
    MarkerCloud *cloud;        /* SPACE_GLOBAL */
    uint64_t round;            /* mixed into the per-bud streams: (year, step) */
    int threads;
} SpaceQuery;

/* out[i] for buds[i]. SYL_OK or SYL_ELIMIT (out of memory). */
int space_round(const SpaceQuery *q, const SpaceBud *buds, size_t n, SpaceResult *out);

#endif
