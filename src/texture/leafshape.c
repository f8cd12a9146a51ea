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

bool syl_leaf_draw_card(int shape, int size, uint8_t *rgba) {
    uint8_t *rgb = malloc((size_t)size * (size_t)size * 3);
    if (!rgb) return false;
    bool ok = syl_texture_draw(SYL_MATERIAL_LEAF, NULL, size, rgb);
    leaf_card_of(rgb, shape, size, rgba);
    free(rgb);
    return ok;
}

void leaf_card_of(const uint8_t *rgb, int shape, int size, uint8_t *rgba) {
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
}

/* ------------------------------------------------------------------ leaf clusters */

/* A cluster card (Pafčo's spherical clusters, seen from one side): leaves radiating from the
 * card's centre, an outer ring and a shorter inner one between them; or a tuft of needles.
 * Each leaf has its base near the centre and its tip inside the card's inscribed circle. */
typedef struct ClusterLeaf {
    float base[2], dir[2], len, half; /* card units (0..1); half: the half width */
} ClusterLeaf;

enum { CLUSTER_MAX = 32, MASK = 256 };

static int cluster_layout(int shape, ClusterLeaf *lf) {
    int n = 0;
    bool needles = shape == SYL_CLUSTER_NEEDLES;
    int rings = needles ? 2 : 2, per[2] = {needles ? 16 : 8, needles ? 12 : 5};
    for (int r = 0; r < rings; r++)
        for (int i = 0; i < per[r]; i++) {
            /* evenly round, the inner ring half a step over, a fixed wobble so it is not a star */
            float a = 2 * PI * ((float)i + 0.5f * (float)r) / (float)per[r] + 0.23f * sinf(7.1f * (float)(i + 3 * r));
            float len = needles ? (r ? 0.3f : 0.45f) : (r ? 0.3f : 0.44f);
            float off = needles ? (r ? 0.1f : 0.02f) : 0.035f;
            ClusterLeaf *l = &lf[n++];
            l->dir[0] = cosf(a), l->dir[1] = sinf(a);
            l->base[0] = 0.5f + off * l->dir[0], l->base[1] = 0.5f + off * l->dir[1];
            l->len = len - (needles ? 0 : 0.02f * (float)(i % 2));
            l->half = needles ? 0.09f * len : 0.22f * len; /* needles: the strap at a needle's width */
        }
    return n;
}

/* The shape in a MASK x MASK grid over (s, t) in 0..1 x -1..1: drawn once, looked up per sample. */
static void shape_mask(int shape, uint8_t *mask) {
    int drawn = shape == SYL_CLUSTER_NEEDLES ? SYL_LEAF_LINEAR : shape;
    for (int j = 0; j < MASK; j++)
        for (int i = 0; i < MASK; i++)
            mask[j * MASK + i] = syl_leaf_inside(drawn, ((float)j + 0.5f) / MASK, 2 * ((float)i + 0.5f) / MASK - 1);
}

/* The last leaf of the layout over card point (x, y), -1: none; (s, t) its coordinates. */
static int cluster_hit(const ClusterLeaf *lf, int n, const uint8_t *mask, float x, float y, float *s, float *t) {
    for (int k = n - 1; k >= 0; k--) {
        const ClusterLeaf *l = &lf[k];
        float dx = x - l->base[0], dy = y - l->base[1];
        float a = (dx * l->dir[0] + dy * l->dir[1]) / l->len, b = (dy * l->dir[0] - dx * l->dir[1]) / l->half;
        if (!(a > 0 && a < 1 && b > -1 && b < 1)) continue;
        int j = (int)(a * MASK), i = (int)((b + 1) * 0.5f * MASK);
        if (mask[(j < MASK ? j : MASK - 1) * MASK + (i < MASK ? i : MASK - 1)]) {
            *s = a, *t = b;
            return k;
        }
    }
    return -1;
}

/* Alpha (and, with rgb, colour) of a size x size cluster card. A texel whose four corners
 * see the same leaf (or none) takes its centre's; the others, at edges, 4 x 4 samples. */
static bool draw_cluster(int shape, int size, const uint8_t *rgb, uint8_t *rgba, size_t *opaque) {
    ClusterLeaf lf[CLUSTER_MAX];
    int n = cluster_layout(shape, lf);
    uint8_t *mask = malloc(MASK * MASK);
    int8_t *corner = malloc((size_t)(size + 1) * (size_t)(size + 1));
    if (!mask || !corner) {
        free(mask), free(corner);
        return false;
    }
    shape_mask(shape, mask);
    enum { SS = 4 };
    *opaque = 0;
    float s, t;
    for (int y = 0; y <= size; y++)
        for (int x = 0; x <= size; x++)
            corner[y * (size + 1) + x] = (int8_t)cluster_hit(lf, n, mask, (float)x / (float)size, (float)y / (float)size, &s, &t);
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
            const int8_t *c = corner + y * (size + 1) + x;
            bool same = c[0] == c[1] && c[0] == c[size + 1] && c[0] == c[size + 2];
            int in = 0, top = -1, ss = same ? 1 : SS;
            float ts = 0, tt = 0;
            for (int j = 0; j < ss; j++)
                for (int i = 0; i < ss; i++) {
                    int k = cluster_hit(lf, n, mask, ((float)x + ((float)i + 0.5f) / (float)ss) / (float)size,
                                        ((float)y + ((float)j + 0.5f) / (float)ss) / (float)size, &s, &t);
                    if (k < 0) continue;
                    in++;
                    if (k >= top) top = k, ts = s, tt = t;
                }
            size_t p = (size_t)y * (size_t)size + (size_t)x;
            uint8_t alpha = (uint8_t)((in * 255 + ss * ss / 2) / (ss * ss));
            *opaque += alpha >= 128;
            if (!rgba) continue;
            /* the leaf texture in the top leaf's own coordinates, so its veins follow it */
            size_t q = p;
            if (top >= 0) {
                int u = (int)((0.5f + 0.5f * tt) * (float)size), v = (int)(ts * (float)size);
                q = (size_t)(v < size ? v : size - 1) * (size_t)size + (size_t)(u < size ? u : size - 1);
            }
            memcpy(rgba + 4 * p, rgb + 3 * q, 3);
            rgba[4 * p + 3] = alpha;
        }
    free(mask), free(corner);
    return true;
}

bool syl_leaf_draw_cluster(int shape, int size, uint8_t *rgba) {
    uint8_t *rgb = malloc((size_t)size * (size_t)size * 3);
    size_t opaque;
    bool ok = rgb && syl_texture_draw(SYL_MATERIAL_LEAF, NULL, size, rgb) && draw_cluster(shape, size, rgb, rgba, &opaque);
    free(rgb);
    return ok;
}

bool leaf_cluster_of(const uint8_t *rgb, int shape, int size, uint8_t *rgba) {
    size_t opaque;
    return draw_cluster(shape, size, rgb, rgba, &opaque);
}

float syl_leaf_cluster_fill(int shape) {
    enum { FILL_SIZE = 128 };
    size_t opaque = 0;
    if (!draw_cluster(shape, FILL_SIZE, NULL, NULL, &opaque)) return 0;
    return (float)opaque / (float)(FILL_SIZE * FILL_SIZE);
}
