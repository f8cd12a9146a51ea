/* What a plant's own skeleton says about its surface (Weber–Penn's leaf outline and trunk
 * jitter: SylSkeleton.leaf_tris, leaf_width, leaf_outline, trunk_jitter), carried into the
 * scene's one skeleton so that a tree meshes in a scene as it does alone. */
#ifndef SCENE_SURFACE_H
#define SCENE_SURFACE_H
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "lang/program.h"
#include "sylva/skeleton.h"

typedef struct SceneSurface {
    const char *leaves_by, *jitter_by; /* the plants that gave them (NULL: none yet) */
    bool leaves_warned, jitter_warned;
} SceneSurface;

/* The plant `name` (the scene's line `line`:`col` of p) just appended to sk, its nodes from
 * first_node and its organs from first_organ; own: its own skeleton, NULL for a grown tree
 * (Sylva's blade leaves, no jitter). The first plant with leaves gives the scene its leaf
 * surface, the first with a trunk jitter its jitter; a trunk without one is marked
 * SYL_NODE_NO_JITTER. One skeleton holds one leaf surface and one jitter: a plant that
 * differs from the one that gave them is warned about (once each) on diag. */
void scene_surface_carry(SceneSurface *S, SylSkeleton *sk, const SylSkeleton *own, size_t first_node,
                         size_t first_organ, const char *name, const SylProgram *p, int line, int col, FILE *diag);

#endif
