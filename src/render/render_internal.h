/* Inside the renderer: the camera, and a synthetic tree for the unit tests. Not part of the
 * public API. The textures it samples are in texture/texture.h. */
#ifndef SYL_RENDER_INTERNAL_H
#define SYL_RENDER_INTERNAL_H
#include <stdbool.h>
#include <stdint.h>

#include "sylva/render.h"
#include "texture/texture.h"

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
