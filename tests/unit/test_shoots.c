/* Rule-made shoots (docs/growth.md "Shoot rules"): the plan a shoot rule yields (metamers, buds, organs,
 * twigs, rolls carried between metamers), and trees grown with one — the rule's length
 * limit, its buds replacing the phyllotaxis, organs on their metamers, `%` ending an axis,
 * `keep`, and the same tree for any thread count. */
#include <math.h>

#include "unit.h"

#include "sot/forest.h"
#include "sot/shoot_rule.h"
#include "sylva/grow.h"

#define GROW(extra, rule) GROWN("6", extra, rule)
#define GROWN(years, extra, rule)                                                          \
    "grow T {\n  years " years "\n  internode 0.3\n  buds alternate angle 45\n"            \
    "  light shadow a 0.2 b 3 depth 5\n  shoot relative max 3 rule R " extra "\n"          \
    "  direction bud 1 light 0.3 tropism 0.1 trunk 0.4 jitter 0\n}\n"                     \
    "lsystem R {\n  angle 90\n  module shoot(n, v, o, y)\n  axiom shoot(1, 1, 0, 0)\n" rule "}\n"

static SylProgram *compile(const char *text) {
    char *diag = NULL;
    SylProgram *p = unit_compile(text, &diag, NULL);
    if (!p) fail_msg("%s", diag);
    free(diag);
    return p;
}

static void near3(const float *v, float x, float y, float z) {
    assert_float_equal(v[0], x, 1e-5);
    assert_float_equal(v[1], y, 1e-5);
    assert_float_equal(v[2], z, 1e-5);
}

/* Metamers are the top-level I and F; what follows one hangs on it, in its frame; top-level
 * rolls carry over to the next metamer. */
static void plan_reads_the_string(void **state) {
    (void)state;
    SylProgram *g = compile(GROW("", "  shoot(n, v, o, y) -> ~leaf(0.5) I [&(90) B] /(90) I [&(90) B F(2) ~flower(0.3)] f(1) ~needle I\n"));
    ShootRule *r = shoot_rule_new(g, "R");
    assert_non_null(r);
    assert_true(shoot_rule_places_buds(r));
    ShootPlan plan = {0};
    const double args[4] = {3, 1, 0, 0};
    assert_int_equal(shoot_rule_plan(r, args, 1, &plan, stderr), SYL_OK);
    assert_int_equal(plan.metamers, 3);
    assert_int_equal(plan.n, 6); /* leaf, bud, bud, twig, flower, needle; nothing on the third */
    const Attach *a = plan.a;
    assert_int_equal(a[0].kind, ATT_ORGAN);
    assert_int_equal(a[0].metamer, 0); /* before the first metamer: on the shoot's base */
    assert_float_equal(a[0].size, 0.5, 1e-6);
    assert_int_equal(a[1].kind, ATT_BUD);
    assert_int_equal(a[1].metamer, 1);
    near3(a[1].h, 0, 0, -1); /* & pitches H toward -U */
    assert_int_equal(a[2].kind, ATT_BUD);
    assert_int_equal(a[2].metamer, 2);
    near3(a[2].h, 0, 1, 0); /* after a roll of 90, -U is +L */
    assert_int_equal(a[3].kind, ATT_TWIG);
    near3(a[3].from, 0, 0, 0);
    near3(a[3].pos, 0, 2, 0);
    assert_int_equal(a[3].parent, -1);
    assert_int_equal(a[4].kind, ATT_ORGAN);
    assert_int_equal(a[4].organ, SYL_KIND_FLOWER);
    near3(a[4].pos, 0, 2, 0); /* at the twig's end */
    assert_int_equal(a[5].kind, ATT_ORGAN);
    assert_int_equal(a[5].organ, SYL_KIND_NEEDLE);
    near3(a[5].pos, 1, 0, 0); /* the branch closed: back on the axis, then f(1) */
    assert_int_equal(a[5].metamer, 2);
    shoot_plan_free(&plan);
    shoot_rule_free(r);
    syl_program_free(g);
}

/* The plan follows the simulation's n, and a rule may grow a shoot shorter; % ends it. */
static void plan_length_and_end(void **state) {
    (void)state;
    SylProgram *g = compile(GROW("", "  module N(k)\n  shoot(n, v, o, y) : n > 2 -> I I %\n"
                                     "  shoot(n, v, o, y) -> N(n)\n  decompose {\n    N(k) : k > 0 -> I N(k - 1)\n  }\n"));
    ShootRule *r = shoot_rule_new(g, "R");
    assert_non_null(r);
    assert_false(shoot_rule_places_buds(r));
    ShootPlan plan = {0};
    double args[4] = {2, 1, 0, 0};
    assert_int_equal(shoot_rule_plan(r, args, 1, &plan, stderr), SYL_OK);
    assert_int_equal(plan.metamers, 2);
    assert_int_equal(plan.n, 0);
    args[0] = 3;
    assert_int_equal(shoot_rule_plan(r, args, 1, &plan, stderr), SYL_OK);
    assert_int_equal(plan.metamers, 2);
    assert_int_equal(plan.n, 1);
    assert_int_equal(plan.a[0].kind, ATT_END);
    shoot_plan_free(&plan);
    shoot_rule_free(r);
    syl_program_free(g);
}

static SylSkeleton *grow(const char *text, int threads, SylGrowStats *stats) {
    SylProgram *p = compile(text);
    SylGrowOptions o = {.years = -1, .threads = threads, .diag = stderr};
    SylSkeleton *sk = NULL;
    assert_int_equal(syl_grow_build(p, &o, &sk), SYL_OK);
    if (stats) *stats = o.stats;
    syl_program_free(p);
    return sk;
}

static size_t count_kind(const SylSkeleton *sk, int kind) {
    size_t n = 0;
    for (size_t i = 0; i < sk->nnodes; i++) n += sk->nodes[i].kind == kind;
    for (size_t i = 0; i < sk->norgans; i++) n += sk->organs[i].kind == kind;
    return n;
}

/* One metamer a year, a leaf on each, the phyllotaxis's buds: the trunk is `years` long,
 * and every metamer (the first year's too) carries exactly one leaf, at its end. */
static void one_leaf_per_metamer(void **state) {
    (void)state;
    SylSkeleton *sk = grow(GROW("", "  shoot(n, v, o, y) -> I ~leaf(0.1)\n"), 1, NULL);
    size_t trunk = 0, internodes = count_kind(sk, SYL_KIND_INTERNODE);
    for (size_t i = 0; i < sk->nnodes; i++) trunk += sk->nodes[i].kind == SYL_KIND_INTERNODE && sk->nodes[i].order == 0;
    assert_int_equal(trunk, 6);
    assert_true(internodes > 6); /* it branched: the buds directive placed the buds */
    assert_int_equal(count_kind(sk, SYL_KIND_LEAF), internodes);
    for (size_t i = 0; i < sk->norgans; i++) {
        const SylOrgan *o = &sk->organs[i];
        const SylNode *n = &sk->nodes[o->node];
        assert_int_equal(n->kind, SYL_KIND_INTERNODE);
        assert_float_equal(o->pos[0], n->pos[0], 1e-5);
        assert_float_equal(o->pos[1], n->pos[1], 1e-5);
        assert_float_equal(o->pos[2], n->pos[2], 1e-5);
    }
    syl_skeleton_free(sk);
}

/* The rule's buds replace the phyllotaxis: with none, the tree is one unbranched axis;
 * `keep 2` keeps only the last two years' organs. */
static void rule_buds_and_keep(void **state) {
    (void)state;
    SylSkeleton *sk = grow(GROW("keep 2", "  module B\n  shoot(n, v, o, y) -> I ~leaf(0.1) I ~leaf(0.1)\n  B -> B\n"), 1, NULL);
    size_t internodes = count_kind(sk, SYL_KIND_INTERNODE);
    assert_int_equal(internodes, 12); /* two metamers a year, no lateral ever */
    assert_int_equal(count_kind(sk, SYL_KIND_LEAF), 4);
    syl_skeleton_free(sk);
    /* two buds per metamer, pitched to either side: every lateral comes from a B */
    sk = grow(GROW("", "  shoot(n, v, o, y) -> I [+(50) B] [-(50) B] ~leaf(0.1)\n"), 1, NULL);
    internodes = count_kind(sk, SYL_KIND_INTERNODE);
    assert_true(internodes > 12);
    size_t axes = 0;
    for (size_t i = 1; i < sk->nnodes; i++) axes += sk->nodes[i].axis != sk->nodes[sk->nodes[i].parent].axis;
    assert_true(axes > 2);
    syl_skeleton_free(sk);
}

/* `%` ends the axis: the shoots of year 3 on are flowers (y is 1 in the first year), so
 * the tree stops as it was after year 2, and its buds flower once and die. */
static void flowering_ends_axes(void **state) {
    (void)state;
    SylGrowStats st;
    SylSkeleton *sk = grow(GROW("", "  shoot(n, v, o, y) : y >= 3 -> ~flower(0.2) %\n  shoot(n, v, o, y) -> I\n"), 1, &st);
    SylSkeleton *two = grow(GROWN("2", "", "  shoot(n, v, o, y) -> I\n"), 1, NULL);
    assert_int_equal(count_kind(sk, SYL_KIND_INTERNODE), count_kind(two, SYL_KIND_INTERNODE));
    assert_int_equal(count_kind(two, SYL_KIND_FLOWER), 0);
    size_t flowers = count_kind(sk, SYL_KIND_FLOWER);
    assert_true(flowers > 0);
    assert_true(flowers <= st.grown + 1); /* at most a bud per metamer, and the first */
    syl_skeleton_free(sk);
    syl_skeleton_free(two);
}

/* F in a branch draws twigs: a node each, hanging from the metamer's end, of the given
 * length, radius half the width; the same tree whatever the thread count. */
static void twigs_and_threads(void **state) {
    (void)state;
    const char *text = GROW("", "  shoot(n, v, o, y) -> I [&(60) !(0.02) F(0.2) F(0.1) ~flower(0.05)]\n");
    SylSkeleton *a = grow(text, 1, NULL), *b = grow(text, 3, NULL);
    assert_int_equal(a->nnodes, b->nnodes);
    assert_memory_equal(a->nodes, b->nodes, a->nnodes * sizeof *a->nodes);
    assert_int_equal(a->norgans, b->norgans);
    assert_memory_equal(a->organs, b->organs, a->norgans * sizeof *a->organs);
    size_t twigs = 0;
    for (size_t i = 0; i < a->nnodes; i++) {
        const SylNode *n = &a->nodes[i];
        if (n->radius != 0.01f) continue;
        twigs++;
        const SylNode *p = &a->nodes[n->parent];
        float d = 0;
        for (int k = 0; k < 3; k++) d += (n->pos[k] - p->pos[k]) * (n->pos[k] - p->pos[k]);
        d = sqrtf(d);
        assert_true(fabsf(d - 0.2f) < 1e-4f || fabsf(d - 0.1f) < 1e-4f);
    }
    assert_int_equal(twigs, 2 * count_kind(a, SYL_KIND_FLOWER));
    syl_skeleton_free(a);
    syl_skeleton_free(b);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(plan_reads_the_string), cmocka_unit_test(plan_length_and_end),
        cmocka_unit_test(one_leaf_per_metamer),  cmocka_unit_test(rule_buds_and_keep),
        cmocka_unit_test(flowering_ends_axes),   cmocka_unit_test(twigs_and_threads),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
