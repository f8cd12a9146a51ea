/* Resource allocation and shoot lengths.
 *
 * Demand: a bud's light (or space) q becomes z = g * q^c: c is the light sensitivity
 * (Longay 2012), g the gravimorphism factor of a lateral bud (1 for an apical one).
 *
 * Extended Borchert–Honda (Palubicki 2009; Tázlar 2018 §3.4.3): demands are summed toward
 * the base; the base receives v = alpha * total, and at every node the resource v entering
 * it is split between the main axis (demand M) and the laterals (total demand L):
 *   v_main = v * lambda M / (lambda M + (1 - lambda) L),   v_lat = v * (1 - lambda) L / (...)
 * with each lateral taking v_lat in proportion to its own demand — nothing is lost at a fork.
 *
 * Priority model (Palubicki 2009, as a priority list over the whole tree): buds are ranked
 * by demand; the weight of rank r falls linearly from wmax at the top to wmin at a fraction
 * kappa of the list and stays there; v_b = alpha * total * w_b z_b / sum(w z).
 *
 * Shoot length: relative (Tázlar's correction of Longay): n = floor(v / (v_max + eps) *
 * (max + 1)), metamers of the internode length; vigor (Palubicki): n = floor(v) (at most
 * max), each v / n internodes long (at most 2). */
#ifndef SYL_SOT_ALLOCATE_H
#define SYL_SOT_ALLOCATE_H
#include "sot/tree.h"

/* Is bud b a candidate this year (alive, and born before it)? */
static inline bool alloc_candidate(const Bud *b, int year) { return b->alive && (int)b->born < year; }
void alloc_demand(Tree *t, int year);
bool alloc_resources(Tree *t, int year);   /* false: out of memory */
void alloc_shoots(Tree *t, int year);

#endif
