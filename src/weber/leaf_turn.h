/* Eight leaves' turns in the lanes of lanes.h: a plain leaf's segment frame turned by its
 * rotation and down angle, then every leaf bent by LeafBend. The same code twice: for the
 * x86-64 baseline (leaves.c) and with AVX2's wider registers (leaf_turn_avx2.c), chosen when
 * the processor has them; each lane's results are the same either way. */
#ifndef WEBER_LEAF_TURN_H
#define WEBER_LEAF_TURN_H
#include <stdbool.h>

#include "weber/lanes.h"

/* Lane k: leaf k's axes, base and stem. Before the turn a plain leaf's lanes hold its
 * segment's axes and rot, down its angles (radians); a fan's leaf's, its own axes. */
typedef struct Leaves8 {
    v8f x[3], y[3], z[3];
    v8f rot, down;
    double t[8][3], dist[8];
    int id[8];
} Leaves8;

/* The turns, in place; bend is LeafBend, turned true for a fan's leaves (already turned). */
void weber_leaf_turn_avx2(Leaves8 *q, bool turned, float bend);
bool weber_leaf_avx2(void); /* whether to call it: built so, and the processor has AVX2 */

/* Plain leaves: each one's segment frame turned by rot about its z, then by down about the
 * new x (radians), as weber_child_direction turns a child. Then (bend) outward, about the
 * vertical, and up, about their x, toward the light. */
static inline void weber_leaf_turn_lanes(Leaves8 *q, bool turned, float b) {
    if (!turned) {
        v8f cr, sr, cd, sd;
        v8_sincos(q->rot, &cr, &sr);
        v8_sincos(q->down, &cd, &sd);
        for (int i = 0; i < 3; i++) {
            v8f fx = q->x[i], fy = q->y[i], fz = q->z[i];
            v8f y = cr * fy - sr * fx;
            q->x[i] = cr * fx + sr * fy;
            q->y[i] = cd * y + sd * fz;
            q->z[i] = cd * fz - sd * y;
        }
    }
    if (b == 0) return;
    v8f tx, ty, c, s, a;
    for (int k = 0; k < 8; k++) tx[k] = (float)q->t[k][0], ty[k] = (float)q->t[k][1];
    a = b * (v8_atan2(ty, tx) - v8_atan2(q->y[1], q->y[0]));
    v8_sincos(a, &c, &s);
    v8f *axes[3] = {q->x, q->y, q->z};
    for (int i = 0; i < 3; i++) {
        v8f *v = axes[i], x = v[0], y = v[1];
        v[0] = c * x - s * y;
        v[1] = s * x + c * y;
    }
    const v8f *y = q->y;
    a = b * v8_atan2(v8_sqrt(y[0] * y[0] + y[1] * y[1]), y[2]);
    v8_sincos(a, &c, &s);
    for (int i = 0; i < 3; i++) {
        v8f p = q->y[i], r = q->z[i];
        q->y[i] = c * p + s * r;
        q->z[i] = c * r - s * p;
    }
}

#endif
