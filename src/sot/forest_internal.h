/* The forest's phases, shared by forest.c, forest_light.c and forest_grow.c. */
#ifndef SYL_SOT_FOREST_INTERNAL_H
#define SYL_SOT_FOREST_INTERNAL_H
#include "sot/forest.h"

double forest_now(void);
/* More metamers than the limit? (Reported.) */
bool forest_too_many(Forest *f, int year);
/* Static occupants cast shadow and occupy space once, before the first year. */
int forest_register_statics(Forest *f);
/* The shadow grid could not grow (past its voxel cap, or refused by --max-memory): reported,
 * SYL_ELIMIT. */
int forest_shadow_too_big(Forest *f);
/* Every candidate bud's light (shadow grid or sky rays); the sky's scene is rebuilt. */
int forest_light(Forest *f, int year);
/* Trees without a light model: a bud's light is 1 if it perceives markers, else 0. */
int forest_space_light(Forest *f, int year);
/* Grow every shoot, metamer by metamer. */
int forest_grow(Forest *f, int year);
/* The metamers grown this year (nodes from before[i] on) cast shadow and kill markers. */
int forest_register(Forest *f, const size_t *before);
/* The n dead nodes of t (NODE_DEAD; the root never is) leave the tree (tree_compact) and the
 * shadow grid. */
int forest_drop_dead(Forest *f, Tree *t, size_t n);
/* Rebuild the occupied points (every metamer end). */
int forest_occupancy(Forest *f);
/* Room for n buds in the space-colonization arrays; a bud as space colonization sees it. */
bool forest_space_scratch(Forest *f, size_t n);
void forest_space_bud(const Tree *t, const Bud *b, SpaceBud *out);

#endif
