/* Self-organizing growth (docs/growth.md): grow the tree a `grow` block describes, or every
 * plant of a file's `scene` in one shared environment, into a skeleton — the same skeleton
 * the turtle draws, so the mesher, renderer and exporters take it as it is. */
#ifndef SYLVA_GROW_H
#define SYLVA_GROW_H
#include <stdint.h>
#include <stdio.h>

#include "mesh.h"
#include "skeleton.h"
#include "sylva.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Counts at the end and seconds per phase (comparable with Tázlar 2018, Table 5.2). */
typedef struct SylGrowStats {
    int plants, years;
    uint64_t metamers;        /* living at the end, every plant */
    uint64_t grown;           /* metamers ever grown (shed ones too) */
    uint64_t buds;            /* living buds at the end */
    uint64_t shed_branches, shed_metamers;
    uint64_t organs;
    uint64_t rule_shoots;     /* shoots a shoot rule built (docs/growth.md, "Shoot rules") */
    double light_s;           /* light per bud, and the shadow grid's updates */
    double space_s;           /* space colonization rounds and occupancy */
    double alloc_s;           /* demand, Borchert–Honda or priority, shoot lengths */
    double growth_s;          /* directions, obstacle tests, new metamers and buds */
    double rule_s;            /* deriving the shoot rules' plans (part of growth_s) */
    double shed_s;            /* shedding */
    double other_s;           /* L-system plants of a scene, obstacles, the skeleton */
    double total_s;
} SylGrowStats;

typedef struct SylGrowOptions {
    int years;                /* < 0: the model's `years` (in a scene: each plant's) */
    int use_seed;             /* nonzero: seed replaces the model's (in a scene: seed + plant number) */
    uint64_t seed;
    int threads;              /* <= 0: all cores; the result never depends on it */
    uint64_t max_metamers;    /* living metamers of all trees: stop with SYL_ELIMIT beyond; 0: 20 million */
    FILE *diag;
    void (*progress)(void *user, double fraction); /* after every year; may be NULL */
    void *user;
    SylGrowStats stats;       /* out */
    /* Limits (exit code 3 beyond them, with a message naming the option). */
    uint64_t max_buds;        /* living buds of all trees; 0: 100 million */
    uint64_t max_modules;     /* of each L-system string in a scene, and of each shoot a shoot
                                 rule derives; 0: 200 million (a shoot: 1 million) */
    uint64_t max_work;        /* of each L-system derivation (SylDeriveOptions.max_work) */
    uint64_t max_memory;      /* bytes, when budget is NULL; 0: the default */
    SylBudget *budget;        /* shared memory budget: trees, buds, scenes' strings, shoots */
    const SylCancel *cancel;  /* asked before every year (sylva.h); NULL: never */
} SylGrowOptions;

/* The most years a tree may grow (`years`, --years, -n). */
enum { SYL_GROW_MAX_YEARS = 10000 };

/* A grow model as a preset (docs/growth.md#presets): each of its directives with its values
 * worked out (params, expressions, a --set of a param), as an XML preset file that `sylva
 * FILE.xml` reads back (<grow-presets><species name=…><param name=… value=…/>), or as a grow
 * block. Read back, either one writes the same bytes again. SYL_OK; SYL_EUSAGE for another
 * kind of block or a directive a preset cannot hold (a shoot rule, a string), reported on
 * diag; SYL_ELIMIT out of memory; SYL_EIO. */
int syl_grow_write_preset(const SylProgram *p, FILE *out, FILE *diag);
int syl_grow_write_syl(const SylProgram *p, const char *note, FILE *out, FILE *diag);

/* Grow a `grow` model alone, its base at the origin. */
int syl_grow_build(const SylProgram *p, SylGrowOptions *opt, SylSkeleton **out);
/* Grow the file's scene (p: any model of the file, or the scene itself): every plant, year
 * by year in lockstep, in one environment; L-system plants are derived, drawn and take part
 * as shadow casters and occupants. One skeleton holds every plant, each where the scene puts
 * it. *obstacles (if not NULL) receives the obstacles' triangles as a mesh, to draw with the
 * plants (NULL when there are none). */
int syl_grow_build_scene(const SylProgram *p, SylGrowOptions *opt, SylSkeleton **out, SylMesh **obstacles);

#ifdef __cplusplus
}
#endif

#endif
