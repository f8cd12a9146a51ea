/* The global marker cloud of space colonization (Runions et al. 2007, Palubicki et al. 2009):
 * points spread uniformly through the free space, removed for good once a metamer comes
 * within the occupancy radius. The cloud has no edges: a cell of markers is made the first
 * time a bud looks into it, from a random stream keyed by the cell, so the cloud is the
 * same whatever order cells are made in, and costs memory only where plants grow. */
#ifndef SYL_ENV_MARKERS_H
#define SYL_ENV_MARKERS_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "env/pointgrid.h"
#include "util/budget.h"

typedef struct MarkerBlock {
    uint64_t key;
    uint32_t first, count;
} MarkerBlock;

typedef struct MarkerCloud {
    float cell, inv;     /* cell edge (the largest perception distance) */
    float per_cell;      /* mean markers per cell */
    float kill;          /* occupancy radius */
    float ground;        /* no markers below */
    uint64_t seed;
    uint64_t *keys;      /* hash table: cell key -> block */
    uint32_t *slot_block;
    size_t mask, used;
    MarkerBlock *blocks;
    size_t nblocks, bcap;
    float (*pos)[3];
    uint8_t *alive;
    size_t n, cap;
    Budget *mem;         /* the markers count against it (NULL: nothing); set after init */
    uint64_t charged;
} MarkerCloud;

/* density: markers per cubic model unit. */
void markers_init(MarkerCloud *c, float cell, float density, float kill, float ground, uint64_t seed);
void markers_free(MarkerCloud *c);
/* Make the cells overlapping pos ± r; new markers within kill of an occupied point are
 * removed at once. False when out of memory. */
bool markers_ensure(MarkerCloud *c, const float pos[3], float r, const PointGrid *occupied);
/* The block of a cell, or -1 if it was never made. */
long markers_block(const MarkerCloud *c, int x, int y, int z);
/* Remove the markers within kill of pos. */
void markers_kill_near(MarkerCloud *c, const float pos[3]);
static inline int markers_coord(const MarkerCloud *c, float v) {
    float f = floorf(v * c->inv);
    return f < -1e6f ? -1000000 : f > 1e6f ? 1000000 : (int)f;
}
size_t markers_alive(const MarkerCloud *c);

#endif
