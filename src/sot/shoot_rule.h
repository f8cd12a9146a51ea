/* Rule-made shoots (docs/growth.md "Shoot rules", docs/language.md §17): the simulation decides
 * where a shoot grows and how many metamers it gets; an lsystem of the file rewrites
 * shoot(n, vigor, order, year) into what the shoot is made of.
 *
 * The derived string is read as a plan. Its top-level I (or F) modules are the shoot's
 * metamers, in order; whatever follows the k-th of them, up to the next, hangs on that
 * metamer's end: lateral buds (B), organs (~leaf, ~flower, ~needle) and drawn twigs (F in a
 * branch). Turns and rolls work as in the turtle, in the frame of the metamer the simulation
 * grew; top-level rolls carry on from metamer to metamer (phyllotaxis). A top-level % ends
 * the axis: its apical bud dies once the shoot is grown. */
#ifndef SYL_SOT_SHOOT_RULE_H
#define SYL_SOT_SHOOT_RULE_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "sylva/sylva.h"

typedef enum { ATT_BUD, ATT_ORGAN, ATT_TWIG, ATT_END } AttachKind;

/* One thing the plan hangs on a metamer, in that metamer's frame: coordinates along its
 * H, L and U. */
typedef struct Attach {
    uint8_t kind;     /* AttachKind */
    uint8_t organ;    /* ATT_ORGAN: SYL_KIND_LEAF, _FLOWER or _NEEDLE */
    uint8_t material;
    uint16_t metamer; /* 0: the shoot's base; k: the end of its k-th metamer */
    int32_t parent;   /* ATT_TWIG: the twig of this plan it continues, or -1 */
    float from[3];    /* ATT_TWIG: where it starts */
    float pos[3];     /* the organ's place, the twig's end */
    float h[3], l[3]; /* its frame; a bud's direction is h */
    float size;       /* organ size, twig radius */
    int32_t placed;   /* ATT_TWIG, once grown: its index among the tree's twigs */
} Attach;

typedef struct ShootPlan {
    Attach *a;
    size_t n, cap;
    int metamers; /* top-level I and F modules */
} ShootPlan;

typedef struct ShootRule ShootRule;

/* Why q cannot be a shoot rule (not an lsystem, no production for shoot), or NULL. */
const char *shoot_rule_check(const SylProgram *q);
/* The rule `model` of grow's file; NULL when it does not compile or is out of memory. */
ShootRule *shoot_rule_new(const SylProgram *grow, const char *model);
void shoot_rule_free(ShootRule *r);
/* The limits of every shoot's derivation: max_modules (0: a million), max_work (0: the
 * default) and the memory budget (NULL: 256 MB a shoot). */
void shoot_rule_limits(ShootRule *r, uint64_t max_modules, uint64_t max_work, SylBudget *mem);
/* How every shoot derives, and so who fills its query modules (?P ... ?E): the public
 * syl_derive_begin when the scene layer sets it (the stand-alone environment); NULL, the
 * default: the engine's own deriver, which leaves query modules as they are. */
typedef int (*ShootDeriveFn)(const SylProgram *p, SylDeriveOptions *opt, const SylString *start, SylDeriver **out);
void shoot_rule_derive_with(ShootRule *r, ShootDeriveFn begin);
/* The rule places lateral buds (its model uses B): the `buds` directive places none. */
bool shoot_rule_places_buds(const ShootRule *r);
/* Colours the rule's model sets (colour I, R, G, B): rgb[i] when set[i]. */
void shoot_rule_colours(const ShootRule *r, bool set[256], float rgb[256][3]);
/* Derive shoot(n, vigor, order, year) with the given seed and read the string into plan
 * (emptied first). Returns SYL_OK or the derivation's error (reported through diag). */
int shoot_rule_plan(const ShootRule *r, const double args[4], uint64_t seed, ShootPlan *plan, FILE *diag);
void shoot_plan_free(ShootPlan *plan);

/* A local point or direction in the frame (pos; h, l, u) to world coordinates. */
static inline void shoot_to_world(const float o[3], const float h[3], const float l[3], const float u[3],
                                  const float v[3], bool point, float out[3]) {
    for (int k = 0; k < 3; k++) out[k] = (point ? o[k] : 0) + v[0] * h[k] + v[1] * l[k] + v[2] * u[k];
}

#endif
