/* Holton's strand model as Zamuda's modeller builds it (Algorithm 2): the tree of a
 * `strands` block's parameters, into a skeleton. */
#ifndef STRANDS_STRANDS_H
#define STRANDS_STRANDS_H
#include <stdint.h>

#include "strands/params.h"
#include "sylva/skeleton.h"

/* A right-handed frame at a point: y is the branch's direction (Zamuda's convention). */
typedef struct StrandsFrame {
    double pos[3], x[3], y[3], z[3];
} StrandsFrame;

/* What a tree of strands S' = t^2 S makes: 2S' - 1 segments, S' terminal ones. */
typedef struct StrandsCounts {
    int64_t strands;     /* S' after the age */
    double trunk_length; /* l_0' after the age */
    uint64_t nodes, organs;
} StrandsCounts;

/* S' and l_0' for age t (eqs. 3.33-3.34; t <= 0 or t >= 1: full grown) and the node and
 * organ counts the tree will have. */
StrandsCounts strands_counts(const StrandsParams *P, double age);

/* How many segments are made between two asks of the caller's cancel (a first ask before any) */
enum { STRANDS_CANCEL_EVERY = 4096 };

/* Append the tree to sk: a root node, then one node per segment (its end), and the leaves.
 * strands_of (NULL: not wanted) receives, per node appended, the strands of the segment it
 * ends (the root: S'). SYL_OK, SYL_ELIMIT when the skeleton cannot grow, or SYL_ECANCELED
 * when cancel (NULL: never) asked to stop (sk then holds part of the tree: free it). */
int strands_build(const StrandsParams *P, double age, SylSkeleton *sk, int64_t *strands_of, const SylCancel *cancel);

/* The leaves of one terminal branch of length len from frame f, attached to node. Returns
 * how many were added, -1 when the skeleton cannot grow. */
int strands_leaves(const StrandsParams *P, const StrandsFrame *f, double len, int32_t node, SylSkeleton *sk);
/* How many leaves each terminal branch gets. */
int strands_leaf_count(const StrandsParams *P);

#endif
