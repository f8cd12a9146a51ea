/* The whole way from a compiled model to a mesh in one call: derive, apply the `interpret`
 * rules, draw with the turtle, mesh — or, for a `grow` block or a scene, grow and mesh. It
 * is what `sylva mesh`, `sylva render` and `sylva FILE` run (docs/embedding.md).
 *
 *     SylPlant pl;
 *     int st = syl_plant_build(p, &(SylPlantOptions){.diag = stderr}, &pl);
 *     if (!st) printf("%zu triangles\n", pl.mesh->nidx / 3);
 *     syl_plant_free(&pl);
 */
#ifndef SYLVA_PLANT_H
#define SYLVA_PLANT_H
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "grow.h"
#include "mesh.h"
#include "skeleton.h"
#include "sylva.h"

#ifdef __cplusplus
extern "C" {
#endif

/* How far syl_plant_build goes: the default (0) is all the way. */
typedef enum { SYL_PLANT_MESH, SYL_PLANT_SKELETON, SYL_PLANT_STRING } SylPlantStage;

/* Zeroed means defaults, as in every Sylva option struct. */
typedef struct SylPlantOptions {
    int use_steps;         /* nonzero: steps replaces the model's `derive` (for a grow block
                              or a scene: its `years`) */
    int steps;
    int use_seed;          /* nonzero: seed replaces the model's `seed` */
    uint64_t seed;
    int threads;           /* <= 0: all cores; the result never depends on it */
    /* Resource limits (docs/cli.md, "Resource limits"): each stops with SYL_ELIMIT and a
     * message on diag; 0 means the default. */
    uint64_t max_modules;  /* modules of a string: the L-system's, a scene plant's or a shoot
                              rule's (0: 200 million; shoot rules: 1 million) */
    uint64_t max_work;     /* modules rewritten by all steps of a derivation (0: 100 billion) */
    uint64_t max_metamers; /* grow blocks and scenes: living metamers (0: 20 million) */
    uint64_t max_buds;     /* grow blocks and scenes: living buds (0: 100 million) */
    uint64_t max_memory;   /* bytes of every engine's memory, when budget is NULL; 0: the
                              default (syl_budget_new) */
    SylBudget *budget;     /* a memory budget shared by every engine of the build (and the
                              caller's other work); it must outlive what the build returns.
                              NULL: each engine keeps its own limit of max_memory */
    SylPlantStage until;   /* stop after the string or the skeleton; SYL_PLANT_STRING refuses
                              grow blocks and scenes (they have no string) */
    int drop_string;       /* nonzero: free the string once drawn (less memory); out->string NULL */
    double age;            /* strands blocks: age t in (0, 1]; 0: full grown */
    int levels;            /* weber blocks: stem levels to build (0: the block's Levels) */
    int scene;             /* nonzero: when p's file has a `scene` block, build the scene — every
                              plant where it stands — rather than p alone */
    const SylMeshOptions *mesh; /* NULL: defaults, with threads as above */
    FILE *diag;            /* where problems are reported; NULL: nowhere */
    void (*progress)(void *user, double fraction); /* after each step or year; 1 at the end */
    void *user;
    /* Given to the derivation, the turtle and the mesher (sylva.h): a build it stops returns
     * SYL_ECANCELED with nothing in out. NULL: mesh->cancel for the mesh, else never. */
    const SylCancel *cancel;
} SylPlantOptions;

/* What was built. Every pointer is owned by the SylPlant: free them all with syl_plant_free
 * (or take one and set its field to NULL first). */
typedef struct SylPlant {
    SylModelKind kind;     /* SYL_MODEL_SCENE when the scene was built */
    SylString *string;     /* L-systems: the string the turtle read (after `interpret` rules);
                              NULL for grown plants and with drop_string */
    SylSkeleton *skeleton; /* NULL with SYL_PLANT_STRING */
    SylMesh *mesh;         /* with SYL_PLANT_MESH; a scene's obstacles are part of it */
    SylMesh **parts;       /* a scene's: each plant's and obstacle's mesh (mesh is them all) */
    int nparts;
    size_t modules;        /* L-systems: the string's length; grown plants: skeleton nodes */
    uint64_t rewritten;    /* L-systems: modules read by all passes of all steps */
    SylGrowStats grow;     /* grow blocks and scenes: counts and times */
    double derive_s, turtle_s, mesh_s; /* seconds per stage (derive_s: the growth, if grown) */
    double derive_cpu_s;   /* the processor time of derive_s (every thread's), which a loaded
                              machine does not inflate as it does the clock's */
    double mesh_cpu_s;     /* the same for mesh_s */
} SylPlant;

/* Build p (kept by the caller; it may be freed as soon as this returns). SYL_OK, or a
 * SYL_* status with *out zeroed; problems are reported on opt->diag. opt may be NULL. */
int syl_plant_build(const SylProgram *p, const SylPlantOptions *opt, SylPlant *out);
/* Free what syl_plant_build made and zero *pl (a zeroed SylPlant is fine too). */
void syl_plant_free(SylPlant *pl);

/* Growth as a sequence of frames (sylva animate): an L-system's derivation steps 0..n (n:
 * opt->steps or the model's `derive`), a grow block's or a scene's years 1..N (N: opt->steps
 * or the model's `years`), a strands block's ages k/N for k = 1..N (N: opt->steps, else 10,
 * through SylPlantOptions.age). An L-system is derived once, each step's string kept; a grown
 * plant is grown again to each year, its last year built here. weber blocks have no growth
 * (SYL_EUSAGE). p must outlive g. */
typedef struct SylGrowth SylGrowth;
int syl_growth_new(const SylProgram *p, const SylPlantOptions *opt, SylGrowth **out);
int syl_growth_count(const SylGrowth *g);        /* frames */
int syl_growth_label(const SylGrowth *g, int k); /* frame k's step, year or age number */
/* Frame k (0 .. count-1) with its skeleton and mesh, as syl_plant_build makes them; free
 * it with syl_plant_free. */
int syl_growth_build(SylGrowth *g, int k, SylPlant *out);
void syl_growth_free(SylGrowth *g);

#ifdef __cplusplus
}
#endif

#endif
