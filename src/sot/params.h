/* The parameters of a self-organizing tree: what the directives of a `grow` block say, with
 * the defaults of docs/growth.md (after Palubicki et al. 2009 and Tázlar 2018). Reading them
 * checks every directive and reports a wrong one at its line and column. */
#ifndef SYL_SOT_PARAMS_H
#define SYL_SOT_PARAMS_H
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "sylva/sylva.h"

typedef enum { PHYL_ALTERNATE, PHYL_OPPOSITE, PHYL_WHORLED } Phyllotaxis;
typedef enum { LIGHT_SHADOW, LIGHT_SKY, LIGHT_OFF } LightModel;
typedef enum { SPACEM_OFF, SPACEM_BUD, SPACEM_GLOBAL } SpaceModel;
typedef enum { ALLOC_BH, ALLOC_PRIORITY } AllocModel;
typedef enum { SHOOT_RELATIVE, SHOOT_VIGOR } ShootModel;
typedef enum { ORGAN_YOUNG, ORGAN_TIPS } OrganPlace;

enum { MAX_ORGANS = 8 };

typedef struct OrganSpec {
    uint8_t kind;    /* SYL_KIND_LEAF, _FLOWER or _NEEDLE */
    uint8_t place;   /* OrganPlace */
    float size;      /* model units */
    int count;       /* per node */
    float angle;     /* from the shoot, degrees */
    int age;         /* on metamers at most this many years old */
    float chance;    /* of each site */
} OrganSpec;

typedef struct GrowParams {
    int years;
    uint64_t seed;
    float internode;
    /* buds */
    int phyllotaxis, laterals;        /* laterals: buds per node */
    float divergence, branch_angle;   /* degrees */
    int bud_life;                     /* years a lateral bud can break */
    /* gravimorphism */
    float grav_h, grav_v, grav_up;
    /* light */
    int light;
    float voxel, full, shadow_a, shadow_b;
    int depth;
    float sun[3];
    bool sun_set;
    int sky_rays;
    float foliage;
    /* space */
    int space;
    int markers;
    float density, occupancy, perception, cone;  /* occupancy and perception in internodes */
    /* allocation */
    int alloc;
    float lambda, alpha, kappa, wmax, wmin;
    float sensitivity;
    /* shoots */
    int shoot, shoot_max;
    char rule[64];                    /* an lsystem of the file whose `shoot` rule builds each shoot */
    int rule_keep;                    /* years the rule's organs and twigs stay (0: for good) */
    const SylProgram *from;           /* the grow model read (to compile the rule); valid while read */
    /* direction */
    float w_bud, w_space, w_light, w_tropism, tropism_angle, w_trunk, jitter;
    bool trunk_tropism;
    float tropism_sin, tropism_cos, jitter_cos;       /* derived from the angles */
    float branch_sin, branch_cos;
    /* shedding */
    float shed_threshold, bare_trunk;
    /* pipe model */
    float pipe_exponent, tip_radius;
    int lod; /* levels of detail of `sylva mesh` (not read by the growth: syl_program_setting) */
    OrganSpec organs[MAX_ORGANS];
    int norgans;
} GrowParams;

void grow_params_default(GrowParams *g);
/* Read the directives of p's grow block into g (defaults first). Returns the number of
 * errors, each reported through diag at its place. */
int grow_params_read(const SylProgram *p, GrowParams *g, FILE *diag);

/* Check a grow block's directives (what syl_validate, scene/spec.c, runs for a grow
 * model). Returns the number of errors reported, negated when all are of --set. */
int sot_check_grow(const SylProgram *p, FILE *diag);

#endif
