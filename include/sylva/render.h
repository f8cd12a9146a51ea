/* Render: an Embree ray caster that writes PNG pictures of meshes — a sun with shadows, sky
 * ambient occlusion, a ground plane, procedural bark, leaf and grass textures, automatic
 * framing. Tiled across threads; the picture does not depend on the thread count. */
#ifndef SYLVA_RENDER_H
#define SYLVA_RENDER_H
#include <stdint.h>
#include <stdio.h>

#include "mesh.h"

typedef enum { SYL_VIEW_ISO, SYL_VIEW_FRONT, SYL_VIEW_SIDE, SYL_VIEW_TOP } SylView;

typedef struct SylRenderOptions {
    int width, height;   /* 0: 1024 x 1024 */
    SylView view;
    int samples;         /* anti-aliasing samples per pixel; 0: 4 */
    int ao_samples;      /* ambient occlusion rays per hit; 0: 8; -1: none */
    int shadows;         /* 0: on; -1: off */
    int threads;         /* 0: all cores */
    FILE *diag;
    void (*progress)(void *user, double fraction); /* may be NULL */
    void *user;
} SylRenderOptions;

/* Render into rgb (width * height * 3 bytes, rows top to bottom). */
int syl_render(const SylMesh *m, const SylRenderOptions *opt, uint8_t *rgb);
/* Render and write a PNG (via a temporary file). */
int syl_render_png(const SylMesh *m, const SylRenderOptions *opt, const char *path);
int syl_write_png(const char *path, const uint8_t *rgb, int width, int height, FILE *diag);

/* Procedural textures after Picek 2015 (bark with cracks along the branch, leaf with veins,
 * grass): size x size RGB. Kind is SYL_MATERIAL_*, or -1 for grass. */
void syl_texture(int kind, const float rgb[3], int size, uint8_t *out);

#endif
