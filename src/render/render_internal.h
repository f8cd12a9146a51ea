/* Inside the renderer: the camera (camera.c), for the renderer and its tests. */
#ifndef SYL_RENDER_INTERNAL_H
#define SYL_RENDER_INTERNAL_H
#include <stdbool.h>
#include <stdint.h>

#include "sylva/render.h"

typedef struct RenderCamera {
    float eye[3], fwd[3], right[3], up[3]; /* right and up are unit vectors */
    float tanx, tany;                      /* half the field of view, as tangents */
    int width, height;
    float lo[3], hi[3];                    /* bounds of the mesh */
    float near, depth;                     /* toward: the sphere's nearest distance, its diameter */
} RenderCamera;

/* Frame the mesh for a view so it fills about 80% of a width x height picture. */
void render_camera(const SylMesh *m, SylView view, int width, int height, RenderCamera *cam);
/* Look along -toward at the mesh's bounding sphere from 100 radii away, framing it exactly. */
void render_camera_toward(const SylMesh *m, const float toward[3], int width, int height, RenderCamera *cam);
/* The same for a box already measured (lo, hi from render_mesh_bounds): many views of one
 * mesh measure it once. */
void render_camera_toward_box(const float lo[3], const float hi[3], const float toward[3], int width, int height,
                              RenderCamera *cam);
/* The bounds of the mesh's finite vertices (a unit box standing on the origin if none). */
void render_mesh_bounds(const SylMesh *m, float lo[3], float hi[3]);
/* Where a world point lands in the picture (pixels, y down); false if behind the eye. */
bool render_project(const RenderCamera *cam, const float p[3], float *x, float *y);

#endif
