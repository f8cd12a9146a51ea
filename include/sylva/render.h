/* Render: an Embree ray caster that writes PNG pictures of meshes — a sun with shadows, sky
 * ambient occlusion, a ground plane, procedural bark, leaf and grass textures, automatic
 * framing. Tiled across threads; the picture does not depend on the thread count. */
#ifndef SYLVA_RENDER_H
#define SYLVA_RENDER_H
#include <stdint.h>
#include <stdio.h>

#include "mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* AUTO: front for a plant drawn in a plane (2D models), iso otherwise. */
typedef enum { SYL_VIEW_ISO, SYL_VIEW_FRONT, SYL_VIEW_SIDE, SYL_VIEW_TOP, SYL_VIEW_AUTO } SylView;

typedef struct SylRenderOptions {
    int width, height;   /* 0: 1024 x 1024 */
    SylView view;
    int samples;         /* anti-aliasing samples per pixel; 0: 4 */
    int ao_samples;      /* ambient occlusion rays per pixel, shared by its samples; 0: 8; -1: none */
    int shadows;         /* 0: on; -1: off */
    int threads;         /* 0: all cores */
    FILE *diag;
    /* May be NULL. Called once per finished tile with the fraction done, increasing and
     * ending with exactly 1.0; the calls are serial but may come from any render thread. */
    void (*progress)(void *user, double fraction);
    void *user;
    /* The picture's buffers and Embree's scene (about 150 bytes a triangle) are estimated
     * before they are built: beyond the memory budget it stops with SYL_ELIMIT. */
    uint64_t max_memory;  /* bytes, when budget is NULL; 0: the default */
    SylBudget *budget;    /* shared memory budget */
} SylRenderOptions;

/* Render into rgb (width * height * 3 bytes, rows top to bottom). Embree shares m->idx, and
 * m->pos too when vert_cap > nverts (it reads a little past the last vertex; otherwise the
 * positions are copied). The ground is at the mesh's lowest point; the camera is framed
 * from the mesh's vertices. */
int syl_render(const SylMesh *m, const SylRenderOptions *opt, uint8_t *rgb);
/* Render and write a PNG (via a temporary file). */
int syl_render_png(const SylMesh *m, const SylRenderOptions *opt, const char *path);
/* path "-": standard output; otherwise as the mesh writers (mesh.h). */
int syl_write_png(const char *path, const uint8_t *rgb, int width, int height, FILE *diag);

/* Procedural textures after Picek 2015 (bark with cracks along the branch, leaf with veins,
 * grass): size x size RGB, rows top to bottom. Kind is SYL_MATERIAL_*, or -1 for grass.
 * The texture is a pattern times rgb (in linear light); rgb NULL: white (grass: its green).
 * Image x is u: around a branch, across a leaf or petal (main vein at u = 0.5); image y is
 * v (row 0 first, as in glTF): along a branch, from a leaf's base (v = 0) to its tip (1).
 * Every texture tiles. SYL_MATERIAL_PLAIN is flat. False when out of memory: out is then
 * flat, which a writer must not commit as the texture. */
bool syl_texture(int kind, const float rgb[3], int size, uint8_t *out);
/* "bark", "leaf", "flower", "grass" (kind -1); NULL for kinds without a texture. */
const char *syl_texture_name(int kind);

enum { SYL_TEXTURE_SIZE = 512 };
/* For exporters: write PREFIX_bark.png, PREFIX_leaf.png and PREFIX_flower.png, each only if
 * a material group of m has that kind (m NULL: all of them and PREFIX_grass.png), as
 * SYL_TEXTURE_SIZE squares. They are white-based patterns: the material's colour goes in
 * the material (glTF baseColorFactor, MTL Kd), which multiplies them — as the renderer does.
 * Each file is written through a temporary file. Returns SYL_OK, SYL_EIO or SYL_ELIMIT. */
int syl_write_textures(const SylMesh *m, const char *prefix, FILE *diag);

#ifdef __cplusplus
}
#endif

#endif
