/* Pafčo's generator (Pafčo 2007, §4.2–4.5; docs/pafco.md): the skeleton of a tree straight
 * from its 42 parameters. */
#ifndef PAFCO_PAFCO_H
#define PAFCO_PAFCO_H
#include <stdint.h>

#include "pafco/params.h"
#include "sylva/skeleton.h"
#include "sylva/sylva.h"
#include "util/budget.h"

/* What a build made, for the tests of its invariants: each branch's generation (0 trunk),
 * its first and last node, its parent branch and the parent's control point it grows from,
 * its length and its bound (first generation: the crown profile's; then V2G_MAX/V3G_MAX as
 * they fall toward the parent's tip). */
typedef struct PafcoBranch {
    int gen;
    int32_t first, last;
    int parent;
    int32_t attach;
    float length, bound, height_frac;
} PafcoBranch;

typedef struct PafcoLog {
    PafcoBranch *branches;
    int n, cap;
} PafcoLog;

/* Build P's tree into sk (empty, from syl_skeleton_new) with seed. The most nodes and leaves
 * it can have (pafco_bounds) are charged to mem and reserved before a node is made. log (may be
 * NULL) receives the branches (free log->branches). SYL_OK, or SYL_ELIMIT beyond the budget
 * (pafco_fits false: nothing made) or out of memory; SYL_ECANCELED when cancel (NULL: never),
 * asked before the trunk and before each trunk point's whorl, said stop (sk holds part of it). */
int pafco_build(const PafcoParams *P, uint64_t seed, Budget *mem, SylSkeleton *sk, PafcoLog *log,
                const SylCancel *cancel);

/* The most nodes and leaves P's tree can have, whatever the seed (bound.c); once nodes pass
 * cap, the count stops there (the tree is too large anyway). */
void pafco_bounds(const PafcoParams *P, double cap, double *nodes, double *leaves);
/* Whether that bound, *bytes of nodes and leaves, fits in what mem (NULL: no limit) has left;
 * *partial (may be NULL): the count stopped past it, the numbers are then the least it is. */
bool pafco_fits(const PafcoParams *P, const Budget *mem, double *nodes, double *leaves, double *bytes, bool *partial);

/* The crown profile at relative height f in the crown (0 its base, 1 the top): the share of
 * the longest first-generation branch a branch there may reach. */
double pafco_crown_profile(bool round, double f);

#endif
