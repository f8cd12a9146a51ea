/* Leaf silhouettes for alpha-tested cards: a named shape drawn into the card's square, the
 * leaf texture in RGB and the shape's coverage in alpha (4 x 4 samples per texel, so the
 * edge is smooth when a viewer filters it and 0 wherever no part of the leaf is). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sylva/skeleton.h"
#include "texture/texture.h"
#include "util/leafoutline.h"

#define PI 3.14159265358979f

const char *const syl_leaf_shape_names[SYL_LEAF_SHAPES] = {"ovate", "linear", "cordate", "maple", "palmate"};

int syl_leaf_shape_named(const char *name) {
    for (int k = 0; k < SYL_LEAF_SHAPES; k++)
        if (!strcmp(name, syl_leaf_shape_names[k])) return k;
    return -1;
}

/* Lobed outlines are polar about a centre on the main vein: radius against the angle from
 * the tip, with n lobes whose sharpness is p; the base (around the petiole) is cut away. */
static bool lobed(float s, float t, float centre, int lobes, float depth, float p) {
    float x = t, y = (s - centre) / (1 - centre); /* y: towards the tip, 1 at the tip */
    float r = sqrtf(x * x + y * y), a = atan2f(x, y); /* 0 towards the tip, ±PI to the base */
    if (fabsf(a) > PI * 0.85f) return r < 0.08f;      /* the sinus at the petiole */
    float lobe = powf(fabsf(cosf(0.5f * (float)lobes * a / 0.85f)), p);
    return r <= (1 - depth) + depth * lobe;
}

bool syl_leaf_inside(int shape, float s, float t) {
    if (!(s > 0 && s < 1 && t > -1 && t < 1)) return false;
    if (shape >= LEAF_OUTLINE_CARD(0, 0)) /* a skeleton's own outline (Weber–Penn's shapes) */
        return leaf_outline_inside((shape - LEAF_OUTLINE_CARD(0, 0)) / 32, (shape - LEAF_OUTLINE_CARD(0, 0)) % 32, s, t);
    float w;
    switch (shape) {
    case SYL_LEAF_LINEAR: w = 0.35f * sqrtf(sinf(PI * s)); break;                     /* a strap */
    case SYL_LEAF_CORDATE: /* heart: two rounded lobes either side of a notch at the petiole */
        if (s < 0.18f && fabsf(t) < 0.3f * (1 - s / 0.18f)) return false;
        w = (s < 0.3f ? sqrtf(1 - (0.3f - s) * (0.3f - s) / 0.09f) : 1) * powf(1 - s, 1.2f) * 1.25f;
        break;
    case SYL_LEAF_MAPLE: return lobed(s, t, 0.45f, 5, 0.45f, 0.5f);
    case SYL_LEAF_PALMATE: return lobed(s, t, 0.4f, 7, 0.7f, 0.7f);
    default: w = powf(sinf(PI * powf(s, 0.75f)), 0.9f); break; /* ovate: widest below the middle */
    }
    return fabsf(t) < w;
}

bool syl_leaf_card(int shape, int size, uint8_t *rgba) {
    uint8_t *rgb = malloc((size_t)size * (size_t)size * 3);
    if (!rgb) return false;
    bool ok = syl_texture(SYL_MATERIAL_LEAF, NULL, size, rgb);
    enum { SS = 4 };
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
            int in = 0;
            for (int j = 0; j < SS; j++)
                for (int i = 0; i < SS; i++) {
                    float u = ((float)x + ((float)i + 0.5f) / SS) / (float)size; /* across */
                    float v = ((float)y + ((float)j + 0.5f) / SS) / (float)size; /* base to tip */
                    in += syl_leaf_inside(shape, v, 2 * u - 1);
                }
            size_t k = (size_t)y * (size_t)size + (size_t)x;
            memcpy(rgba + 4 * k, rgb + 3 * k, 3);
            rgba[4 * k + 3] = (uint8_t)((in * 255 + SS * SS / 2) / (SS * SS));
        }
    free(rgb);
    return ok;
}
