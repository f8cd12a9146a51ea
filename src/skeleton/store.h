/* What a skeleton keeps for the library alone (SylSkeleton.store): the room of its arrays
 * and the memory budget its nodes count against. Generators that fill a skeleton's arrays
 * themselves (the turtle, weber, strands) come through these. */
#ifndef SYL_SKELETON_STORE_H
#define SYL_SKELETON_STORE_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "sylva/skeleton.h"

struct SylSkeletonStore {
    size_t node_cap, organ_cap, poly_cap, vert_cap, part_cap;
    SylBudget *budget; /* counted against until the skeleton is freed (NULL: none) */
    uint64_t charged;
    /* A generator's mapping that holds the nodes and organs (one page fault for both where
     * each had its own), freed whole (pages_free); an array grown past it moves out. */
    void *block;
    size_t block_bytes;
};

/* bytes of budget b stay charged to s until it is freed. */
void skeleton_charge(SylSkeleton *s, SylBudget *b, uint64_t bytes);
/* Room for n nodes (organs) in all; false when out of memory. */
bool skeleton_reserve_nodes(SylSkeleton *s, size_t n);
bool skeleton_reserve_organs(SylSkeleton *s, size_t n);
/* s takes over organs (n of them, room for cap), malloc'ed, in place of its own. */
void skeleton_adopt_organs(SylSkeleton *s, SylOrgan *organs, size_t n, size_t cap);
/* s takes over block (pages_alloc'ed or arena_detach'ed, bytes long), in which its nodes and
 * organs may live. */
void skeleton_adopt_block(SylSkeleton *s, void *block, size_t bytes);

#endif
