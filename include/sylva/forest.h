/* Forest: an ecosystem's plants drawn by instancing (docs/ecosystem.md#pictures). Each
 * species' model is meshed once per age class (with a coarser level of detail for far
 * plants), each plant is an instance of its class on the terrain mesh: a picture of 100,000
 * plants costs a handful of meshes. */
#ifndef SYLVA_FOREST_H
#define SYLVA_FOREST_H
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "ecosystem.h"
#include "mesh.h"
#include "render.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { SYL_FOREST_CLASSES = 3 }; /* age classes: by the share h / height_max */
typedef enum { SYL_FOREST_BIRD, SYL_FOREST_WALKER } SylForestView;

typedef struct SylForestOptions {
    int threads;          /* <= 0: all cores; nothing depends on it */
    int coarse;           /* 0: a coarser level for far plants (src/lod); -1: none */
    SylBudget *budget;    /* NULL: each mesh its own default limit */
    FILE *diag;
} SylForestOptions;

typedef struct SylForest SylForest;

/* Mesh the looks of m's species (their `model`, compiled from p's file) and the terrain t
 * (which must outlive the forest). A species without a model is drawn as nothing. SYL_OK,
 * or the status of the first model that fails, reported. */
int syl_forest_new(const SylProgram *p, const SylEcoModel *m, const SylTerrain *t, const SylForestOptions *o,
                   SylForest **out);
void syl_forest_free(SylForest *f);
/* The camera of a view for a width x height picture: the bird's-eye view frames the whole
 * terrain from the south-south-east, 40° up; the walker's eye is 1.7 m above the valley
 * floor at the terrain's middle, looking along the valley (the axis the ground rises
 * least along) downhill. */
void syl_forest_camera(const SylForest *f, SylForestView v, int width, int height, SylRenderCamera *cam);
/* The plants as instances: at (x, terrain height, z), scaled to their height, turned about
 * y by a hash of their id. inst gets n entries; those without a look get scale 0. */
void syl_forest_instances(const SylForest *f, const SylEcoPlant *plants, size_t n, SylRenderInstance *inst);
/* Render the plants over the terrain (syl_render_instances: windows as there). */
int syl_forest_render(const SylForest *f, const SylEcoPlant *plants, size_t n, const SylRenderCamera *cam,
                      const SylRenderOptions *ro, const int (*windows)[4], int nwindows, uint8_t *rgb,
                      SylRenderCounts *counts);
/* The .glb: the terrain mesh and, per species and class, one mesh instanced with
 * EXT_mesh_gpu_instancing in one node per spatial cell (cells of about cell metres; 0: 250),
 * each node's extras giving its cell's bounds. */
int syl_forest_write_glb(const SylForest *f, const SylEcoPlant *plants, size_t n, double cell, const char *path,
                         FILE *diag);

#ifdef __cplusplus
}
#endif
#endif
