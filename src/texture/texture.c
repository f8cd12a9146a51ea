/* Procedural textures (bark, leaf, flower, grass) and their mip chains for the renderer. */

/* After Picek 2015 (§3.4, §4.7): bark whose cracks run along the branch
 * (stripes made by noise with the along-the-branch coordinate zeroed, which then distort a
 * second noise), a leaf with a bright main vein, sine side veins and darker edges, and grass
 * from two noises, the second shifted against the first.
 *
 * A texture is a pattern in linear light (0..1) that multiplies the material's colour. Image
 * x is texture u (around a branch, across a leaf with its main vein at u = 0.5), image y is
 * v (along a branch, from a leaf's base at v = 0 to its tip at v = 1). Every pattern tiles. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sylva/skeleton.h"
#include "texture/srgbbytes.h"
#include "texture/texture.h"

float srgb_to_linear(float c) {
    if (c <= 0) return 0;
    if (c >= 1) return 1;
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

float linear_to_srgb(float c) {
    if (c <= 0) return 0;
    if (c >= 1) return 1;
    return c <= 0.0031308f ? c * 12.92f : 1.055f * powf(c, 1 / 2.4f) - 0.055f;
}

static inline float clamp01(float x) { return x < 0 ? 0 : x > 1 ? 1 : x; }

static inline float smoothstep(float a, float b, float x) {
    float t = clamp01((x - a) / (b - a));
    return t * t * (3 - 2 * t);
}

/* Each pattern's noises, made once for all its pixels (texture_pattern). */
static void noises(int kind, Fbm f[4]) {
    switch (kind) {
    case SYL_MATERIAL_BARK:
        fbm_init(&f[0], 6, 0, 0.5f, 3, 11); /* stripes: across the branch only (the thesis zeroes y) */
        fbm_init(&f[1], 12, 2, 0.5f, 4, 23);
        fbm_init(&f[2], 32, 4, 0.5f, 3, 37);
        fbm_init(&f[3], 3, 1, 0.5f, 2, 51);
        break;
    case SYL_MATERIAL_LEAF: fbm_init(&f[0], 8, 8, 0.5f, 3, 71); break;
    case SYL_MATERIAL_FLOWER: fbm_init(&f[0], 6, 6, 0.5f, 3, 81); break;
    case -1:
        fbm_init(&f[0], 8, 8, 0.5f, 4, 91);
        fbm_init(&f[1], 64, 64, 0.6f, 2, 93);
        break;
    default: break;
    }
}

/* The noises a pixel of each pattern reads: nz[k] is noise k of the pattern at the pixel
 * (texture_pattern says which fbm at which place). */

/* stripes: f[0] at (s, 0), the same for a whole column; nz: f[1] at (s + 0.06 stripes, t),
 * f[2] and f[3] at (s, t). */
static void bark(const float *nz, float stripes, float out[3]) {
    /* The stripes distort a noise stretched along the branch; its zero lines are the cracks. */
    float n = nz[0];
    float crack = 1 - smoothstep(0.0f, 0.12f, fabsf(n));
    float grain = nz[1];
    float blotch = nz[2];
    float l = (0.80f + 0.14f * grain + 0.10f * blotch + 0.06f * stripes) * (1 - 0.72f * crack);
    out[0] = clamp01(l);
    out[1] = clamp01(l * (1 - 0.04f * crack));
    out[2] = clamp01(l * (1 - 0.08f * crack));
}

static void leaf(const float *nz, float s, float t, float out[3]) {
    float d = fabsf(s - 0.5f) * 2;                 /* 0 on the main vein, 1 at the edge */
    float w = 0.025f + 0.03f * (1 - t);            /* the main vein thins toward the tip */
    float q = (d / w) * (d / w); /* e^-q is far below half the least float past 110: expf's 0, without the call */
    float main_vein = q > 110 ? 0 : expf(-q);
    float f = sinf(6.2831853f * 7 * (t - 0.35f * d)); /* side veins slant toward the tip */
    float ridge = smoothstep(0.80f, 1.0f, f); /* +0 off the veins, and then so is the product */
    float side = ridge == 0 ? 0 : ridge * (1 - 0.7f * d) * smoothstep(w, 2 * w, d);
    float edge = smoothstep(0.5f, 1.0f, d);
    float n = nz[0];
    float l = (0.70f + 0.06f * n) * (1 - 0.45f * edge * edge);
    out[0] = clamp01(l + 0.28f * main_vein + 0.16f * side);
    out[1] = clamp01(l + 0.28f * main_vein + 0.16f * side);
    out[2] = clamp01(l + 0.10f * main_vein + 0.06f * side);
}

static void flower(const float *nz, float s, float t, float out[3]) {
    float d = fabsf(s - 0.5f) * 2;
    float streak = powf(0.5f + 0.5f * sinf(6.2831853f * 9 * s), 6);
    float n = nz[0];
    float l = (0.82f + 0.12f * t + 0.04f * n - 0.10f * streak * (1 - t)) * (1 - 0.15f * smoothstep(0.7f, 1, d));
    float base = 0.5f * (1 - smoothstep(0.0f, 0.25f, t)); /* a yellowish heart */
    out[0] = clamp01(l);
    out[1] = clamp01(l * (1 - 0.15f * base));
    out[2] = clamp01(l * (1 - 0.55f * base));
}

/* nz: f[0] at (s, t) and at (s + 0.37, t + 0.61), f[1] at (s, t). */
static void grass(const float *nz, float out[3]) {
    /* The same noise twice, the second shifted, so no lattice pattern shows. */
    float n1 = nz[0];
    float n2 = nz[1];
    float blades = nz[2];
    float l = 0.72f + 0.16f * n1 + 0.16f * n2 + 0.16f * blades;
    float dry = smoothstep(0.05f, 0.45f, n2 - n1);
    out[0] = clamp01(l * (1 + 0.30f * dry) * 0.92f);
    out[1] = clamp01(l * 0.95f);
    out[2] = clamp01(l * (1 - 0.35f * dry) * 0.90f);
}

/* Where each noise of a pattern is read: fbm fi at (column coordinate + dx, row + dy); for
 * the bark's first, the column coordinate moved by the stripes. */
typedef struct Probe {
    int fi;
    float dx, dy;
    bool striped;
} Probe;

static int probes(int kind, Probe p[4]) {
    switch (kind) {
    case SYL_MATERIAL_BARK:
        p[0] = (Probe){1, 0, 0, true}, p[1] = (Probe){2, 0, 0, false}, p[2] = (Probe){3, 0, 0, false};
        return 3;
    case SYL_MATERIAL_LEAF:
    case SYL_MATERIAL_FLOWER: p[0] = (Probe){0, 0, 0, false}; return 1;
    case -1:
        p[0] = (Probe){0, 0, 0, false}, p[1] = (Probe){0, 0.37f, 0.61f, false}, p[2] = (Probe){1, 0, 0, false};
        return 3;
    default: return 0;
    }
}

/* Each probe's column and row cells (fbm_axis): the lattice work of a pixel done once per
 * column and once per row. False when out of memory or an fbm has no tables. */
typedef struct Grid {
    FbmCell *cx[4], *cy[4];
} Grid;

static void grid_free(Grid *g) {
    for (int k = 0; k < 4; k++) free(g->cx[k]), free(g->cy[k]);
}

static bool grid_make(const Fbm *f, const Probe *p, int np, const float *stripes, int size, Grid *g) {
    memset(g, 0, sizeof *g);
    float *at = malloc((size_t)size * sizeof *at);
    bool ok = at != NULL;
    for (int k = 0; ok && k < np; k++) {
        size_t cells = (size_t)f[p[k].fi].octaves * (size_t)size;
        g->cx[k] = malloc((cells ? cells : 1) * sizeof(FbmCell));
        g->cy[k] = malloc((cells ? cells : 1) * sizeof(FbmCell));
        if (!g->cx[k] || !g->cy[k]) {
            ok = false;
            break;
        }
        for (int x = 0; x < size; x++) { /* as the pixel loop computes s, and the probe moves it */
            float s = ((float)x + 0.5f) / (float)size;
            at[x] = p[k].striped ? s + 0.06f * stripes[x] : p[k].dx != 0 ? s + p[k].dx : s;
        }
        ok = fbm_axis(&f[p[k].fi], 0, at, size, g->cx[k]);
        for (int y = 0; ok && y < size; y++) {
            float t = ((float)y + 0.5f) / (float)size;
            at[y] = p[k].dy != 0 ? t + p[k].dy : t;
        }
        ok = ok && fbm_axis(&f[p[k].fi], 1, at, size, g->cy[k]);
    }
    free(at);
    if (!ok) grid_free(g);
    return ok;
}

void texture_pattern(int kind, int size, float *out) {
    Fbm f[4] = {0};
    noises(kind, f);
    float *stripes = kind == SYL_MATERIAL_BARK ? malloc((size_t)size * sizeof *stripes) : NULL;
    for (int x = 0; stripes && x < size; x++) stripes[x] = fbm_at(&f[0], ((float)x + 0.5f) / (float)size, 0);
    Probe p[4];
    int np = probes(kind, p);
    Grid g;
    bool gridded = (kind != SYL_MATERIAL_BARK || stripes) && grid_make(f, p, np, stripes, size, &g);
    float *rows = gridded && np ? malloc((size_t)np * (size_t)size * sizeof *rows) : NULL; /* a row's noises */
    for (int y = 0; y < size; y++) {
        for (int k = 0; rows && k < np; k++) fbm_grid_row(&f[p[k].fi], g.cx[k], size, g.cy[k], size, y, rows + (size_t)k * size);
        for (int x = 0; x < size; x++) {
            float s = ((float)x + 0.5f) / (float)size, t = ((float)y + 0.5f) / (float)size;
            float *o = out + 3 * ((size_t)y * (size_t)size + (size_t)x);
            float stripe = kind != SYL_MATERIAL_BARK ? 0 : stripes ? stripes[x] : fbm_at(&f[0], s, 0), nz[4];
            for (int k = 0; k < np; k++) /* the same values every way, to the bit */
                nz[k] = rows      ? rows[(size_t)k * size + x]
                        : gridded ? fbm_grid_at(&f[p[k].fi], g.cx[k], size, x, g.cy[k], size, y)
                                  : fbm_at(&f[p[k].fi], p[k].striped ? s + 0.06f * stripe : p[k].dx != 0 ? s + p[k].dx : s,
                                         p[k].dy != 0 ? t + p[k].dy : t);
            switch (kind) {
            case SYL_MATERIAL_BARK: bark(nz, stripe, o); break;
            case SYL_MATERIAL_LEAF: leaf(nz, s, t, o); break;
            case SYL_MATERIAL_FLOWER: flower(nz, s, t, o); break;
            case -1: grass(nz, o); break;
            default: o[0] = o[1] = o[2] = 1; break;
            }
        }
    }
    free(rows);
    if (gridded) grid_free(&g);
    free(stripes);
    for (int k = 0; k < 4; k++) fbm_free(&f[k]);
}

static const float grass_rgb[3] = {0.42f, 0.56f, 0.22f};

const float *texture_grass_rgb(void) { return grass_rgb; }

bool syl_texture_draw(int kind, const float rgb[3], int size, uint8_t *out) {
    if (size <= 0) return true;
    static const float white[3] = {1, 1, 1};
    if (!rgb) rgb = kind == -1 ? grass_rgb : white;
    float *p = malloc((size_t)size * (size_t)size * 3 * sizeof *p);
    float lin[3];
    for (int c = 0; c < 3; c++) lin[c] = srgb_to_linear(rgb[c]);
    if (!p) { /* out of memory: a flat texture, for a picture that can live with it */
        for (size_t i = 0; i < (size_t)size * (size_t)size * 3; i++)
            out[i] = srgb_byte_exact(lin[i % 3]);
        return false;
    }
    texture_pattern(kind, size, p);
    /* the same bytes as the formula (srgbbytes.h); its table costs some 24,000 of them */
    SrgbBytes *t = (size_t)size * (size_t)size * 3 >= 1u << 16 ? malloc(sizeof *t) : NULL;
    if (t) srgb_bytes_init(t);
    for (size_t i = 0; i < (size_t)size * (size_t)size * 3; i += 3)
        for (int c = 0; c < 3; c++) out[i + c] = t ? srgb_byte(t, p[i + c] * lin[c]) : srgb_byte_exact(p[i + c] * lin[c]);
    free(t);
    free(p);
    return true;
}

const char *syl_texture_name(int kind) {
    switch (kind) {
    case SYL_MATERIAL_BARK: return "bark";
    case SYL_MATERIAL_LEAF: return "leaf";
    case SYL_MATERIAL_FLOWER: return "flower";
    case -1: return "grass";
    default: return NULL;
    }
}

/* ---- mip-mapped patterns for the renderer ---- */

static void mip_chain(Texture *t);

bool texture_build(Texture *t, int kind, int size) {
    memset(t, 0, sizeof *t);
    if (size < 1 || (size & (size - 1))) return false; /* a power of two */
    t->level[0] = malloc((size_t)size * size * 3 * sizeof(float));
    if (!t->level[0]) return false;
    texture_pattern(kind, size, t->level[0]);
    t->size[0] = size;
    t->levels = 1;
    mip_chain(t);
    return true;
}

bool texture_from_rgba(Texture *t, const uint8_t *rgba, int w, int h, int size) {
    memset(t, 0, sizeof *t);
    if (size < 1 || (size & (size - 1)) || w < 1 || h < 1) return false;
    float *px = t->level[0] = malloc((size_t)size * size * 3 * sizeof(float));
    if (!px) return false;
    float lin[256];
    for (int i = 0; i < 256; i++) lin[i] = srgb_to_linear((float)i / 255);
    /* bilinear, wrapping (bark tiles), from the image's pixel centres to the square's */
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
            float sx = ((float)x + 0.5f) * (float)w / (float)size - 0.5f, sy = ((float)y + 0.5f) * (float)h / (float)size - 0.5f;
            float fx = floorf(sx), fy = floorf(sy), ax = sx - fx, ay = sy - fy;
            int x0 = (((int)fx % w) + w) % w, y0 = (((int)fy % h) + h) % h, x1 = (x0 + 1) % w, y1 = (y0 + 1) % h;
            for (int c = 0; c < 3; c++) {
                float p00 = lin[rgba[4 * ((size_t)y0 * w + x0) + c]], p10 = lin[rgba[4 * ((size_t)y0 * w + x1) + c]];
                float p01 = lin[rgba[4 * ((size_t)y1 * w + x0) + c]], p11 = lin[rgba[4 * ((size_t)y1 * w + x1) + c]];
                float a = p00 + ax * (p10 - p00), b = p01 + ax * (p11 - p01);
                px[3 * ((size_t)y * size + x) + c] = a + ay * (b - a);
            }
        }
    t->size[0] = size;
    t->levels = 1;
    mip_chain(t);
    return true;
}

/* Each level the mean of the one before's 2 x 2 texels, down to one texel. */
static void mip_chain(Texture *t) {
    while (t->size[t->levels - 1] > 1 && t->levels < 16) {
        int ps = t->size[t->levels - 1], s = ps / 2;
        const float *src = t->level[t->levels - 1];
        float *dst = malloc((size_t)s * s * 3 * sizeof(float));
        if (!dst) break; /* coarser levels are a nicety */
        for (int y = 0; y < s; y++)
            for (int x = 0; x < s; x++)
                for (int c = 0; c < 3; c++) {
                    const float *a = src + 3 * ((size_t)(2 * y) * ps + 2 * x) + c;
                    dst[3 * ((size_t)y * s + x) + c] = 0.25f * (a[0] + a[3] + a[3 * ps] + a[3 * ps + 3]);
                }
        t->level[t->levels] = dst;
        t->size[t->levels++] = s;
    }
}

void texture_free(Texture *t) {
    for (int i = 0; i < t->levels; i++) free(t->level[i]);
    memset(t, 0, sizeof *t);
}

/* Sizes are powers of two, so wrapping is a mask. */
static void bilinear(const float *img, int size, float u, float v, float out[3]) {
    float x = u * (float)size - 0.5f, y = v * (float)size - 0.5f;
    float fx = floorf(x), fy = floorf(y);
    float ax = x - fx, ay = y - fy;
    int mask = size - 1;
    int x0 = (int)fx & mask, y0 = (int)fy & mask, x1 = (x0 + 1) & mask, y1 = (y0 + 1) & mask;
    const float *p00 = img + 3 * ((size_t)y0 * size + x0), *p10 = img + 3 * ((size_t)y0 * size + x1);
    const float *p01 = img + 3 * ((size_t)y1 * size + x0), *p11 = img + 3 * ((size_t)y1 * size + x1);
    for (int c = 0; c < 3; c++) {
        float a = p00[c] + ax * (p10[c] - p00[c]), b = p01[c] + ax * (p11[c] - p01[c]);
        out[c] = a + ay * (b - a);
    }
}

void texture_sample(const Texture *t, float u, float v, float lod, float out[3]) {
    if (!t->levels) {
        out[0] = out[1] = out[2] = 1;
        return;
    }
    if (!(fabsf(u) < 1e6f) || !(fabsf(v) < 1e6f)) u = v = 0; /* also NaN */
    if (!(lod > 0)) lod = 0;
    if (lod >= (float)(t->levels - 1)) {
        bilinear(t->level[t->levels - 1], t->size[t->levels - 1], u, v, out);
        return;
    }
    int l = (int)lod;
    float f = lod - (float)l, a[3], b[3];
    bilinear(t->level[l], t->size[l], u, v, a);
    if (f <= 0) {
        memcpy(out, a, sizeof a);
        return;
    }
    bilinear(t->level[l + 1], t->size[l + 1], u, v, b);
    for (int c = 0; c < 3; c++) out[c] = a[c] + f * (b[c] - a[c]);
}
