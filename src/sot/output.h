/* A grown tree as a skeleton: one node per metamer end (its radius by the pipe model, its
 * frame, branch order and axis), the base as the root, and organs — leaves, flowers,
 * needles — on young metamers or at the tips, as the `organ` directives say. */
#ifndef SYL_SOT_OUTPUT_H
#define SYL_SOT_OUTPUT_H
#include "sot/tree.h"
#include "sylva/skeleton.h"

/* Append tree t (as it is at the end of year `year`) to sk, its axes numbered from
 * axis_base on. SYL_OK or SYL_ELIMIT. *organs counts the organs added. */
int tree_to_skeleton(Tree *t, int year, SylSkeleton *sk, int32_t axis_base, uint64_t *organs);
/* One more than the largest axis id of sk (0 when empty). */
int32_t skeleton_next_axis(const SylSkeleton *sk);

#endif
