/* Inside textures: noise, patterns, mip chains and sRGB, for the renderer and exporters. */
#ifndef SYL_TEXTURE_TEXTURE_H
#define SYL_TEXTURE_TEXTURE_H
#include <stdbool.h>
#include <stdint.h>

#include "sylva/texture.h"

/* ---- noise (noise.c) ---- */

/* 2D gradient (Perlin) noise, about -1..1, periodic: lattice coordinates wrap at px, py
 * (0: no wrap). seed picks an independent field. */
float noise2(float x, float y, int px, int py, uint32_t seed);
/* Sum of octaves after Picek (2.16)-(2.18): octave i samples at frequency f * 2^i with
 * amplitude p^i; x, y in 0..1 tile when f is a whole number. Divided by the sum of the
 * amplitudes, so also about -1..1. fbm_init hashes each periodic octave's gradients once (a
 * texture asks at every pixel); without memory for a table an octave is hashed at each call,
 * to the same values. At most FBM_OCTAVES octaves. */
enum { FBM_OCTAVES = 8 };
typedef struct Fbm {
    int fx, fy, octaves;
    float p;
    uint32_t seed;
    uint8_t *g[FBM_OCTAVES];
} Fbm;
void fbm_init(Fbm *f, int fx, int fy, float p, int octaves, uint32_t seed);
float fbm_at(const Fbm *f, float x, float y);
void fbm_free(Fbm *f);
/* One axis of a grid of fbm samples: for each octave and coordinate, its lattice cell, its
 * place in the cell and the fade (cells[o * n + k] for coordinate k of octave o). A pixel of
 * the grid then asks only its four corners per octave (fbm_grid_at): a texture's columns and
 * rows share these. False when an octave has no gradient table (then use fbm_at). */
typedef struct FbmCell {
    int i0, i1;    /* the cell's two lattice lines, wrapped */
    float d, w;    /* the place in the cell (0..1) and its fade */
} FbmCell;
bool fbm_axis(const Fbm *f, int axis, const float *at, int n, FbmCell *cells);
/* fbm_at(f, xs[kx], ys[ky]) to the bit, cx and cy from fbm_axis of xs (axis 0, nx of them)
 * and ys (axis 1, ny). */
float fbm_grid_at(const Fbm *f, const FbmCell *cx, int nx, int kx, const FbmCell *cy, int ny, int ky);
/* fbm_grid_at for every column of row ky at once, into out[0..nx): the same bits, with each
 * lattice cell's gradients looked up once for the run of columns inside it. */
void fbm_grid_row(const Fbm *f, const FbmCell *cx, int nx, const FbmCell *cy, int ny, int ky, float *out);

/* ---- leaf cards and clusters (leafshape.c) ---- */

/* syl_leaf_draw_card and syl_leaf_draw_cluster from the leaf pattern already made (rgb: syl_texture_draw of
 * a leaf at size, RGB): a writer that needs the pattern for several pictures makes it once. */
void leaf_card_of(const uint8_t *rgb, int shape, int size, uint8_t *rgba);
bool leaf_cluster_of(const uint8_t *rgb, int shape, int size, uint8_t *rgba);

/* ---- patterns (texture.c) ---- */

/* The linear-light pattern a texture kind multiplies the material colour by, size x size
 * RGB floats in 0..1; x runs along u (around a branch, across a leaf), y along v. */
void texture_pattern(int kind, int size, float *out);

/* A pattern with its mip chain, for the renderer. */
typedef struct Texture {
    int levels;
    int size[16];
    float *level[16]; /* size * size RGB, linear */
} Texture;
bool texture_build(Texture *t, int kind, int size); /* size: a power of two */
/* An image of w x h RGBA (sRGB, rows top to bottom; alpha not kept) resampled to size x size
 * (a power of two) in linear light, with its mip chain. False when out of memory. */
bool texture_from_rgba(Texture *t, const uint8_t *rgba, int w, int h, int size);
void texture_free(Texture *t);
/* Trilinear lookup with wrapping; lod is log2 of texels per sample footprint. */
void texture_sample(const Texture *t, float u, float v, float lod, float out[3]);

/* The ground's colour (sRGB). */
const float *texture_grass_rgb(void);

float srgb_to_linear(float c);
float linear_to_srgb(float c);

#endif
