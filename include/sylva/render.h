/* Render: an Embree ray caster that writes PNG pictures of meshes — a sun with shadows, sky
 * ambient occlusion, a ground plane, procedural bark, leaf and grass textures, automatic
 * framing. Tiled across threads; the picture does not depend on the thread count. */
#ifndef SYLVA_RENDER_H
#define SYLVA_RENDER_H
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "mesh.h"
#include "texture.h"

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
    FILE *diag;          /* where problems are said as text; NULL: nowhere */
    const SylSink *sink; /* or as records to this sink instead (sylva.h); NULL: diag */
    /* May be NULL. Called once per finished tile with the fraction done, increasing and
     * ending with exactly 1.0; the calls are serial but may come from any render thread. */
    void (*progress)(void *user, double fraction);
    void *user;
    /* The picture's buffers and Embree's scene (about 150 bytes a triangle) are estimated
     * before they are built: beyond the memory budget it stops with SYL_ELIMIT. */
    uint64_t max_memory;  /* bytes, when budget is NULL; 0: the default */
    SylBudget *budget;    /* shared memory budget */
    /* NULL: the camera, the ground and the light's scale are fitted to the mesh drawn.
     * Otherwise to this mesh: an animation fits them to its last frame once, so every frame
     * is seen by one camera over one ground (sylva animate). */
    const SylMesh *frame;
    /* NULL, or width * height bytes: each pixel's coverage, 255 times the share of its
     * samples whose camera ray hit the mesh (not the ground or the sky) — a silhouette. */
    uint8_t *alpha;
    /* Impostor baking. toward: NULL, or a unit vector from the plant toward the camera: the
     * view is then nearly orthographic (from 100 radii away) and frames the mesh's bounding
     * sphere (the box's centre, half its diagonal) exactly, whatever the direction. */
    const float *toward;
    int ground;           /* 0: on; -1: no ground (nor its shadows): sky behind the plant */
    /* NULL, or width * height * 4 bytes: the surface's normal (world space, n * 0.5 + 0.5 in
     * RGB) and in A its depth across the bounding sphere (0 nearest, 255 farthest; with
     * toward), of the first sample that hit the mesh; zero where none did. */
    uint8_t *normal;
    bool unlit;           /* the surfaces' own colour (albedo, textures included), no light */
    /* Samples beyond the first only for blocks of 4 x 4 pixels whose first samples disagree
     * (some hit the mesh, some not): edges are smoothed, the inside and the sky cost one ray
     * a pixel. For impostor atlases, where most of each view is one or the other. */
    bool adaptive;
} SylRenderOptions;

/* Render into rgb (width * height * 3 bytes, rows top to bottom). Embree shares m->idx, and
 * m->pos too when the library made it with room past the last vertex (Embree reads a little
 * past it; a mesh made by hand has its positions copied). The ground is at the mesh's lowest point; the camera is framed
 * from the mesh's vertices. */
int syl_render_draw_mesh(const SylMesh *m, const SylRenderOptions *opt, uint8_t *rgb);
/* n pictures of one mesh, one after another in rgb (and alpha, normal), each seen from
 * toward[i] (see toward): Embree's scene is built once. */
int syl_render_draw_views(const SylMesh *m, const SylRenderOptions *opt, int n, const float (*toward)[3], uint8_t *rgb);
/* Render and write a PNG (via a temporary file). */
int syl_render_write_png(const SylMesh *m, const SylRenderOptions *opt, const char *path);
/* Many copies of a few meshes (a forest: sylva ecosystem, docs/ecosystem.md#pictures) as
 * Embree instances over a ground mesh (the terrain: drawn itself, no ground plane). A copy
 * of proto p is at t + Ry(yaw) (scale x), x a vertex of the proto's mesh, or of its coarse
 * mesh when the copy spans fewer than SYL_RENDER_COARSE_PX rows of the picture (level of
 * detail by distance). A copy whose bounding sphere, grown by its height for the shadow it
 * casts, is outside the view is left out (frustum culling). A proto mesh (or coarse mesh)
 * with leaf cards or cluster cards (SylMesh.leaves) lets rays through their transparent
 * parts, as syl_render_draw_mesh does. */
enum { SYL_RENDER_COARSE_PX = 48 };
typedef struct SylRenderProto {
    const SylMesh *mesh, *coarse; /* coarse: NULL for none */
} SylRenderProto;
typedef struct SylRenderInstance {
    float t[3], yaw, scale; /* yaw: radians about +y, counter-clockwise seen from above */
    uint32_t proto;
} SylRenderInstance;
/* A pinhole camera: vertical field of view fov degrees, x to the right of the picture is
 * fwd x (0, 1, 0). */
typedef struct SylRenderCamera {
    float eye[3], target[3], fov;
} SylRenderCamera;
typedef struct SylRenderCounts {
    size_t drawn, coarse, culled;
} SylRenderCounts;
/* Rays go to Embree in packets of SYL_RENDER_BLOCK x SYL_RENDER_BLOCK pixels from the
 * window's corner, and a ray's result may differ in its last bit with its packet. */
enum { SYL_RENDER_BLOCK = 4 };
/* Render windows of the opt->width x opt->height picture, the scene built once: window k has
 * columns windows[k][0] .. windows[k][2]-1 and rows windows[k][1] .. windows[k][3]-1, and its
 * pixels follow window k-1's in rgb (each its size times 3 bytes); nwindows 0: the whole
 * picture. A window whose [0] and [1] are multiples of SYL_RENDER_BLOCK has byte for byte the
 * whole picture's pixels, so such pieces rendered apart (on MPI ranks) tile it. counts (the
 * scene's, once) may be NULL. SYL_OK, SYL_EUSAGE, SYL_ELIMIT. */
int syl_render_draw_instances(const SylMesh *ground, const SylRenderProto *protos, int nprotos,
                              const SylRenderInstance *inst, size_t n, const SylRenderCamera *cam,
                              const SylRenderOptions *opt, const int (*windows)[4], int nwindows, uint8_t *rgb,
                              SylRenderCounts *counts);
/* Where the camera puts world point p in the whole picture (pixels, y down, the centre of
 * the top-left pixel at (0.5, 0.5)); false behind the eye. */
bool syl_render_project(const SylRenderCamera *cam, int width, int height, const float p[3], float *x, float *y);

/* The PNG writer (syl_png_write) and the textures the renderer uses are in texture.h. */

#ifdef __cplusplus
}
#endif

#endif
