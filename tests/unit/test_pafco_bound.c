/* Pafčo's up-front size bound (pafco/bound.c, issue 29): never below what a build makes — the
 * seven examples over many seeds and growth ages, and trees of random parameters within their
 * ranges — and stopping early at its cap. The builder counts nodes and leaves as it makes them,
 * so each tree is checked against the skeleton that was actually built. */
#include <math.h>

#include "unit.h"

#include "pafco/pafco.h"
#include "util/rng.h"

static const char *const examples[] = {"birch", "cherry", "linden", "oak", "pine", "poplar", "spruce"};

/* Build P with seed and check the bound holds; the worst ratio actual / bound is kept. */
static void check(const PafcoParams *P, uint64_t seed, double *fill) {
    double nodes, leaves;
    pafco_bounds(P, INFINITY, &nodes, &leaves);
    Budget mem;
    budget_init(&mem, 0);
    SylSkeleton *sk = syl_skeleton_new("t");
    assert_non_null(sk);
    assert_int_equal(pafco_build(P, seed, &mem, sk, NULL, NULL), SYL_OK);
    if (!((double)sk->nnodes <= nodes) || !((double)sk->norgans <= leaves))
        fail_msg("seed %llu: %zu nodes, %zu leaves, bound %.0f, %.0f", (unsigned long long)seed, sk->nnodes,
                 sk->norgans, nodes, leaves);
    if (fill && nodes > 0) *fill = fmax(*fill, (double)sk->nnodes / nodes);
    syl_skeleton_free(sk);
}

static void examples_never_pass_the_bound(void **state) {
    (void)state;
    for (size_t e = 0; e < sizeof examples / sizeof *examples; e++) {
        char path[64];
        snprintf(path, sizeof path, "examples/pafco/%s.cfg", examples[e]);
        size_t len;
        char *text = syl_read_file(path, &len);
        assert_non_null(text);
        SylProgram *p = unit_compile(text, NULL, NULL);
        assert_non_null(p);
        PafcoParams P;
        assert_int_equal(pafco_params_read(p, &P, NULL), 0);
        double fill = 0;
        for (uint64_t seed = 1; seed <= 12; seed++) check(&P, seed, &fill);
        PafcoParams young = P; /* sylva animate's ages: the height scaled */
        for (int a = 1; a < 10; a += 3) young.height = P.height * a / 10, check(&young, 1, NULL);
        /* not a loose bound: the examples fill a good part of it */
        if (!(fill > 0.6)) fail_msg("%s: at most %.2f of the bound's nodes", examples[e], fill);
        syl_program_free(p);
        free(text);
    }
}

static double draw(Rng *r, double lo, double hi) { return lo + (hi - lo) * rng_unit(r); }

static void random_trees_never_pass_the_bound(void **state) {
    (void)state;
    Rng r = rng_stream(29, 0, 0, 0);
    for (int i = 0; i < 300; i++) {
        PafcoParams P;
        pafco_defaults(&P);
        P.height = draw(&r, 0.1, 12);
        P.width_ratio = draw(&r, 0, 1);
        P.crown_ratio = draw(&r, 0.01, 3);
        P.seg_branch = 1 + (int)draw(&r, 0, 8);
        P.seg_trunk = 1 + (int)draw(&r, 0, 5);
        P.whorl = 1 + (int)draw(&r, 0, 4);
        P.round_crown = rng_unit(&r) < 0.5;
        P.nextg = draw(&r, 0, 1);
        P.maxlen[1] = draw(&r, 0, 3), P.maxlen[2] = draw(&r, 0, 1.5);
        P.gen[1] = rng_unit(&r) < 0.8, P.gen[2] = rng_unit(&r) < 0.6;
        P.sph_leaves = rng_unit(&r) < 0.6, P.bil_leaves = rng_unit(&r) < 0.5;
        P.sph_count = draw(&r, 0, 6), P.leaf_size = draw(&r, 0, 0.3), P.bil_length = draw(&r, 0, 0.2);
        P.scatter = draw(&r, 0, 90), P.angle[0] = draw(&r, 0, 180), P.uhp = draw(&r, -180, 180);
        check(&P, (uint64_t)i + 1, NULL);
    }
}

static void the_count_stops_at_its_cap(void **state) {
    (void)state;
    PafcoParams P;
    pafco_defaults(&P);
    P.height = 200, P.width_ratio = 2, P.seg_branch = 100, P.whorl = 16;
    P.gen[1] = P.gen[2] = true, P.maxlen[1] = P.maxlen[2] = 100;
    double nodes, leaves;
    pafco_bounds(&P, 1e6, &nodes, &leaves);
    assert_true(nodes > 1e6);
    assert_true(nodes < 1e6 + 1e5); /* one branch past the cap at most */
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(examples_never_pass_the_bound),
        cmocka_unit_test(random_trees_never_pass_the_bound),
        cmocka_unit_test(the_count_stops_at_its_cap),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
