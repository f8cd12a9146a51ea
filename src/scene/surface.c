/* Each plant's materials in the scene's palette (surface.h). */
#include <string.h>

#include "scene/surface.h"

static bool same_material(const SylMaterial *a, const SylMaterial *b) {
    return a->rgb[0] == b->rgb[0] && a->rgb[1] == b->rgb[1] && a->rgb[2] == b->rgb[2] && a->kind == b->kind &&
           a->leaf_outline == b->leaf_outline && a->leaf_tris == b->leaf_tris && a->leaf_width == b->leaf_width &&
           a->trunk_jitter == b->trunk_jitter && a->translucency == b->translucency && a->image == b->image &&
           a->tile[0] == b->tile[0] && a->tile[1] == b->tile[1] &&
           !memcmp(a->ring_sides, b->ring_sides, sizeof a->ring_sides);
}

static void take(SceneSurface *S, SylSkeleton *sk, int slot, const SylMaterial *m) {
    S->taken[slot] = true;
    sk->materials[slot] = *m;
    if (slot >= sk->nmaterials) sk->nmaterials = slot + 1;
}

void scene_surface_map(SceneSurface *S, SylSkeleton *sk, const SylSkeleton *b, uint8_t map[256], const char *name,
                       const SylProgram *p, int line, int col, FILE *diag) {
    for (int m = 0; m < 256; m++) map[m] = (uint8_t)m;
    for (int m = 0; m < b->nmaterials; m++) {
        SylMaterial mine = b->materials[m], *own = &mine;
        /* its image among the scene's (the plants' images, each file once); none when they
         * do not fit: its procedural texture then */
        const SylImage *g = syl_material_image(b->images, own);
        if (g) own->image = (uint8_t)syl_images_add(&sk->images, g);
        if (!S->taken[m]) {
            take(S, sk, m, own);
            continue;
        }
        if (same_material(&sk->materials[m], own)) continue;
        int slot = -1;
        for (int k = 0; k < 256 && slot < 0; k++)
            if (S->taken[k] && same_material(&sk->materials[k], own)) slot = k;
        for (int k = 0; k < 256 && slot < 0; k++)
            if (!S->taken[k]) take(S, sk, slot = k, own);
        if (slot >= 0) map[m] = (uint8_t)slot;
        else if (!S->full_warned) {
            S->full_warned = true;
            program_warning(p, diag, line, col,
                            "the scene's plants have more than 256 materials: '%s' draws with other plants' colours",
                            name);
        }
    }
}
