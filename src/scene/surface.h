/* Each plant's surface in a scene: its materials (colour, leaf outline, trunk jitter) take
 * slots of their own in the scene's one palette, so that a tree draws in a scene as it does
 * alone, whatever the plants beside it. */
#ifndef SCENE_SURFACE_H
#define SCENE_SURFACE_H
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "lang/program.h"
#include "sylva/skeleton.h"

typedef struct SceneSurface {
    bool taken[256]; /* slots of the scene's palette that a plant's material holds */
    bool full_warned;
} SceneSurface;

/* The slots of sk's palette for the materials of plant b (their images added to sk's) (the scene's line `line`:`col` of p,
 * named name): map[m] for each m below b->nmaterials. A material keeps its own number when that
 * slot is free or holds the same material, else takes the slot of an equal one, else the first
 * free one. When all 256 are taken by other materials, it shares its number's slot (warned once
 * on diag). */
void scene_surface_map(SceneSurface *S, SylSkeleton *sk, const SylSkeleton *b, uint8_t map[256], const char *name,
                       const SylProgram *p, int line, int col, FILE *diag);

#endif
