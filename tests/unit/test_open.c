/* Open L-systems (?E modules, scene/open.h): light is lower under a canopy than in the open,
 * obstacle distance along the heading, the pruned hedge of examples/hybrid never crosses its
 * box, and reruns agree. Run from the repository's root (tests/run-all does). */
#include <math.h>

#include "unit.h"

#include "sylva/grow.h"

/* Derive text; the parameters of the k-th ?E module's answer (parameter 1) into out. */
static int answers(const char *text, double *out, int max) {
    int st;
    SylProgram *p = unit_compile(text, NULL, &st);
    assert_non_null(p);
    SylDeriveOptions d = {.steps = -1, .threads = 1};
    SylString *s = NULL;
    assert_int_equal(syl_derive(p, &d, &s), SYL_OK);
    int n = 0;
    for (size_t i = 0; i < syl_string_length(s); i++) {
        int na;
        const double *a;
        int sym = syl_string_module(s, i, &na, &a);
        if (!strcmp(syl_program_symbol_name(p, sym), "?E") && n < max) out[n++] = a[1];
    }
    syl_string_free(s);
    syl_program_free(p);
    return n;
}

static void light_under_a_canopy(void **state) {
    (void)state;
    /* a canopy of three segment ends 7 up; light asked below it, and off to the side */
    const char *text = "lsystem C {\n  derive 1\n"
                       "  axiom [ f(6) [ +(90) f(3) -(90) F(1) ] [ -(90) f(3) +(90) F(1) ] F(1) ] "
                       "f(3) ?E(0, 0) f(2) ?E(0, 0) [ +(90) f(10) ?E(0, 0) ] ?E(2, 0) &(90) ?E(2, 0) &(90) ?E(2, 0)\n}\n";
    double v[6];
    assert_int_equal(answers(text, v, 6), 6);
    assert_true(v[0] < 1 && v[0] > 0);         /* under the canopy, 4 voxels down */
    assert_true(v[1] < v[0]);                  /* closer under it: darker */
    assert_float_equal(v[2], 1, 1e-9);         /* in the open */
    assert_true(v[3] > 1e8);                   /* heading up: nothing ahead */
    assert_true(v[4] > 1e8);                   /* horizontal: nothing either */
    assert_float_equal(v[5], 5, 1e-4);         /* heading down from 5 up: the ground */
}

static char *hedge_csv(SylSkeleton **keep) {
    int st;
    SylCompileOptions co = {.validate = syl_validate};
    SylProgram *p = syl_compile("examples/hybrid/hedge.syl", NULL, 0, &co, &st);
    assert_non_null(p);
    SylGrowOptions go = {.years = -1, .threads = 1};
    SylSkeleton *sk = NULL;
    assert_int_equal(syl_grow_build_scene(p, &go, &sk, NULL), SYL_OK);
    syl_program_free(p);
    char *out = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&out, &len);
    syl_skeleton_write_csv(sk, mem);
    fclose(mem);
    *keep = sk;
    return out;
}

static void hedge_stays_in_its_box(void **state) {
    (void)state;
    SylSkeleton *a, *b;
    char *x = hedge_csv(&a), *y = hedge_csv(&b);
    assert_string_equal(x, y); /* deterministic */
    assert_true(a->nnodes > 1000);
    const float lo[3] = {-1.2f, -0.05f, -0.5f}, hi[3] = {1.2f, 1.4f, 0.5f};
    for (size_t i = 0; i < a->nnodes; i++)
        for (int k = 0; k < 3; k++) {
            assert_true(a->nodes[i].pos[k] >= lo[k] - 1e-4f);
            assert_true(a->nodes[i].pos[k] <= hi[k] + 1e-4f);
        }
    free(x);
    free(y);
    syl_skeleton_free(a);
    syl_skeleton_free(b);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(light_under_a_canopy),
        cmocka_unit_test(hedge_stays_in_its_box),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
