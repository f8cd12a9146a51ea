/* Shedding and radii.
 *
 * Pipe model: a tip's radius is `tip`; further down, r^n = the sum of the children's r^n
 * plus the memory of the branches shed there (Palubicki 2009: the width of a branch keeps
 * the trace of what it once carried).
 *
 * Shedding (Palubicki 2009 after Takenaka; Tázlar 2018 §3.4.8): a lateral branch — the whole
 * crown part above the node where it starts — whose light per metamer (the sum of its nodes'
 * light over their number) is below the threshold is shed. Sums run toward the base first;
 * then branches are tested from the base up, so a failing branch goes whole, as low as
 * possible. Independently, `bare_trunk` clears the trunk below that height of branches and
 * of lateral buds. */
#ifndef SYL_SOT_SHED_H
#define SYL_SOT_SHED_H
#include <math.h>

#include "env/shadow.h"
#include "sot/tree.h"

/* A[i] = r^n of the metamer ending at node i (into t->acc). */
bool pipe_areas(Tree *t);
static inline float pipe_radius(const GrowParams *P, double area) {
    return area > 0 ? (float)pow(area, 1.0 / P->pipe_exponent) : 0;
}
/* Mark the nodes to shed (NODE_DEAD, using each node's light: looked up in shadow, else
 * Node.light) and remember their pipes in their parents. Returns how many nodes it marked;
 * (size_t)-1 when out of memory. */
size_t shed_mark(Tree *t, const ShadowGrid *shadow);

#endif
