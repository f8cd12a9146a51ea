/* Eight leaves' turns in the lanes of lanes.h: a plain leaf's segment frame turned by its
 * rotation and down angle, then every leaf bent by LeafBend. One code (leaf_turn_math.h) for
 * two widths: as two sets of four lanes side by side, the x86-64 baseline's (leaves.c), and
 * as eight, AVX2's (leaf_turn_avx2.c, chosen when the processor has it); each lane's results
 * are the same either way. */
#ifndef WEBER_LEAF_TURN_H
#define WEBER_LEAF_TURN_H
#include <stdbool.h>
#include <stddef.h>

#include "weber/lanes.h"

/* Lane k: leaf k's axes, base and stem. Before the turn a plain leaf's lanes hold its
 * segment's axes and rot, down its angles (radians); a fan's leaf's, its own axes. */
typedef struct Leaves8 {
    v8f x[3], y[3], z[3];
    v8f rot, down;
    v8f tx, ty; /* the base's horizontal place, for LeafBend */
    double t[8][3], dist[8];
    int id[8];
} Leaves8;

/* The turns, in place; bend is LeafBend, turned true for a fan's leaves (already turned). */
void weber_leaf_turn_avx2(Leaves8 *q, bool turned, float bend);
bool weber_leaf_avx2(void); /* whether to call it: built so, and the processor has AVX2 */

#define LANES_F v4f
#define LANES_N 4
#define LANES(name) v4_##name
#include "weber/leaf_turn_math.h"
#define LANES_F v8f
#define LANES_N 8
#define LANES(name) v8_##name
#include "weber/leaf_turn_math.h"

#endif
