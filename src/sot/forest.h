/* A forest: the trees of one scene growing year by year in lockstep in one shared
 * environment (Tázlar 2018 §3.8, Palubicki 2009 §4):
 *
 *   1. light   every bud's light (shadow grid, sky rays, or space when there is no light model)
 *   2. allocate demand, Borchert–Honda or priority, shoot lengths — per tree
 *   3. grow    metamer by metamer, all shoots of all trees together: a space-colonization
 *              round, then each bud's direction, an obstacle test, a new metamer and its buds
 *   4. register the new metamers cast shadow and occupy space
 *   5. shed    per tree; shed metamers leave the light and space models
 *
 * Before the light phase of every year the forest calls its year_start hook, if any: a
 * scene's L-system plants take their derivation step there and replace their casters and
 * occupants (scene/lsys.c), so trees and L-systems grow in lockstep.
 *
 * Everything random comes from the buds' own streams and every sum runs in a fixed order,
 * so the forest is the same for any thread count. */
#ifndef SYL_SOT_FOREST_H
#define SYL_SOT_FOREST_H
#include "env/env.h"
#include "env/space.h"
#include "sot/shoot_rule.h"
#include "sot/tree.h"
#include "sylva/grow.h"

typedef struct Candidate {
    int32_t tree, bud;
    float dir[3], space[3];
    float to[3];
    uint8_t blocked, spaced;
} Candidate;

typedef struct ForestRule {
    const SylProgram *from;
    const char *name;
    ShootRule *rule;
} ForestRule;

typedef struct Forest {
    Env env;
    Tree *trees;
    int ntrees;
    int years;             /* the forest's age at the end */
    int threads;
    uint64_t max_metamers, max_buds;
    uint64_t max_modules, max_work; /* of shoot rules' derivations (0: their defaults) */
    Budget own, *mem;      /* the memory budget: own, or the caller's */
    uint64_t charged;      /* the forest's own arrays */
    bool reported;         /* a limit's message was printed */
    const SylCancel *cancel; /* asked before every year (SylGrowOptions.cancel); NULL: never */
    ForestRule *rules; /* shoot rules, one per model and rule name, shared by trees */
    int nrules, rules_cap;
    int trees_cap;
    FILE *diag;
    const SylSink *sink;   /* the grown program's sink (set after forest_init); NULL: diag's text */
    SylGrowStats *stats;
    int space_variant;     /* SPACE_PER_BUD or SPACE_GLOBAL, from the first tree that uses space */
    bool space_any;
    /* How shoot rules derive (set before the trees are added): see shoot_rule_derive_with. */
    ShootDeriveFn shoot_derive;
    /* Called at the start of every year, before light; NULL: none. */
    int (*year_start)(void *user, int year);
    void *year_user;
    /* A shadow grid for ?E light when no tree uses `light shadow` (set before forest_setup):
     * probe_shadow_params at this voxel. */
    bool lsys_shadow;
    float lsys_shadow_voxel;
    /* scratch */
    Candidate *cand;
    size_t ncand, ccap;
    SpaceBud *sb;
    SpaceResult *sr;
    uint32_t *sb_cand;
    size_t sbcap;
    float *occ;
    size_t occ_cap;
} Forest;

int forest_init(Forest *f, int threads, FILE *diag, SylGrowStats *stats);
/* The limits of opt (max_metamers, max_buds, max_modules, max_work, the memory budget) and
 * its cancel. */
void forest_limits(Forest *f, const SylGrowOptions *opt);
/* st, having said why when st is SYL_ELIMIT and nothing was said yet: the memory budget or
 * an allocation ran out in `year` (0: before growth). */
int forest_said(Forest *f, int st, int year);
void forest_free(Forest *f);
/* A tree that grows for `years` years, ending with the forest. */
int forest_add_tree(Forest *f, const GrowParams *P, const float base[3], int years);
/* After the trees and the obstacles: set the light and space models up. */
int forest_setup(Forest *f, float ground, const float sun[3], bool sun_set);
/* Register static occupants (L-system plants drawn before the trees grow) before forest_run. */
int forest_add_static(Forest *f, const float pos[3]);
int forest_run(Forest *f, void (*progress)(void *, double), void *user);
/* Each node's light this year (shadow model: the grid; otherwise the best bud on it). */
void forest_node_light(Forest *f, Tree *t);

#endif
