/* Inside the renderer: Perlin noise, texture patterns with mipmaps, the camera, and a
 * synthetic tree for the unit tests. Not part of the public API. */
#ifndef SYL_RENDER_INTERNAL_H
#define SYL_RENDER_INTERNAL_H
#include <stdbool.h>
#include <stdint.h>

#include "sylva/render.h"

/* ---- noise (noise.c) ---- */

/* 2D gradient (Perlin) noise, about -1..1, periodic: lattice coordinates wrap at px, py
 * (0: no wrap). seed picks an independent field. */
float noise2(float x, float y, int px, int py, uint32_t seed);
/* Sum of octaves after Picek (2.16)-(2.18): octave i samples at frequency f * 2^i with
 * amplitude p^i; x, y in 0..1 tile when f is a whole number. Divided by the sum of the
 * amplitudes, so also about -1..1. */
float fbm2(float x, float y, int fx, int fy, float p, int octaves, uint32_t seed);

/* ---- textures (texture.c) ---- */

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
void texture_free(Texture *t);
/* Trilinear lookup with wrapping; lod is log2 of texels per sample footprint. */
void texture_sample(const Texture *t, float u, float v, float lod, float out[3]);

/* The ground's colour (sRGB). */
const float *texture_grass_rgb(void);

float srgb_to_linear(float c);
float linear_to_srgb(float c);

/* ---- camera (render.c) ---- */

typedef struct RenderCamera {
    float eye[3], fwd[3], right[3], up[3]; /* right and up are unit vectors */
    float tanx, tany;                      /* half the field of view, as tangents */
    int width, height;
    float lo[3], hi[3];                    /* bounds of the mesh */
} RenderCamera;

/* Frame the mesh for a view so it fills about 80% of a width x height picture. */
void render_camera(const SylMesh *m, SylView view, int width, int height, RenderCamera *cam);
/* Where a world point lands in the picture (pixels, y down); false if behind the eye. */
bool render_project(const RenderCamera *cam, const float p[3], float *x, float *y);

/* ---- meshes built by hand (synth.c), for the unit tests; free them with syl_mesh_free ---- */

/* An empty mesh with materials 0 bark, 1 leaf, 2 flower, 3 plain red (repeating). */
SylMesh *synth_new(void);
/* Append an axis-aligned box with material mat; materials must be appended in increasing
 * order (groups stay sorted). */
bool synth_box(SylMesh *m, const float lo[3], const float hi[3], uint8_t mat);
/* A branching tree of tubes (bark) with folded leaves, about `triangles` triangles (at
 * least 500), the same every time; its base at the origin, about 2.5 units tall. */
SylMesh *synth_tree(long triangles);

#endif
