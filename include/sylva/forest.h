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

typedef struct SylTextureCache SylTextureCache; /* sylva/stream.h */

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
    const SylSink *sink;  /* or as records to this sink instead (sylva.h); NULL: diag. The looks'
                             models are compiled with it: their builds report there too */
    /* NULL: none. The caller's (one a run, sylva/stream.h): the .glb files written of the
     * forest make their procedural textures once and copy them from here. Borrowed: it must
     * outlive the forest. The files' bytes do not change. */
    SylTextureCache *textures;
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
/* Render the plants over the terrain (syl_render_draw_instances: windows as there). */
int syl_forest_render(const SylForest *f, const SylEcoPlant *plants, size_t n, const SylRenderCamera *cam,
                      const SylRenderOptions *ro, const int (*windows)[4], int nwindows, uint8_t *rgb,
                      SylRenderCounts *counts);
/* The looks the plants wear (one per species, age class and variant: the meshes the .glb
 * instances, named by these three in its nodes' extras). Look k's mesh (NULL: k out of range;
 * a mesh of no triangles draws nothing), with its species, class and variant when asked. */
int syl_forest_looks(const SylForest *f);
const SylMesh *syl_forest_look(const SylForest *f, int k, int *species, int *age_class, int *variant);
/* The .glb: the terrain mesh and, per species and class, one mesh instanced with
 * EXT_mesh_gpu_instancing in one node per spatial cell (cells of about cell metres; 0: 250),
 * each node's extras giving its cell's bounds. */
int syl_forest_write_glb(const SylForest *f, const SylEcoPlant *plants, size_t n, double cell, const char *path,
                         const SylSink *sink);

/* A saved snapshot (its plant table, plants-YEAR.csv) of p's ecosystem block rendered as
 * `sylva ecosystem` renders view-YEAR.png, and written to png (and glb, when given, as one
 * transaction: both or neither) by rank 0 (src/forest/snapshot.c). Under MPI (mpi, from
 * syl_ecosystem_mpi_start) the picture's rows are cut into bands dealt round the ranks, each rank
 * renders its own and rank 0 gathers them: the bytes do not depend on the number of ranks.
 * Every rank calls it, with the status it has so far (p NULL when its compile failed: it
 * still takes part, so the job stops together). Rank 0 reports on diag; another rank keeps
 * its diagnostics and reports them there only when it alone failed. Every rank returns the
 * worst status of all: SYL_OK, SYL_EMODEL, SYL_EUSAGE (not an ecosystem block), SYL_EIO,
 * SYL_ELIMIT. */
typedef struct SylSnapshotOptions {
    const char *plants;              /* the plant table */
    SylForestView view;
    const SylRenderOptions *render;  /* width x height (0: 1280 x 720), samples, shadows, threads */
    const char *png, *glb;           /* rank 0's outputs; glb NULL: none */
    int threads;                     /* for the forest's meshes; <= 0: all cores */
    SylEcoMpi *mpi;                  /* NULL: one process */
    void (*before_gather)(void *user, int rank); /* under MPI, each rank before the gather */
    void *user;
    FILE *diag;
    const SylSink *sink;             /* or as records to this sink instead (sylva.h); NULL: diag */
} SylSnapshotOptions;
typedef struct SylSnapshotStats {    /* this rank's */
    SylRenderCamera camera;
    int width, height;
    size_t plants, rows, bytes;      /* rows rendered here, and their bytes sent to rank 0 */
    int bands;
    SylRenderCounts counts;
    double wall, cpu;                /* the render's seconds */
} SylSnapshotStats;
int syl_ecosystem_render_snapshot(const SylProgram *p, int status, const SylSnapshotOptions *o, SylSnapshotStats *stats);

#ifdef __cplusplus
}
#endif
#endif
