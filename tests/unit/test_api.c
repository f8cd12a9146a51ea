/* Edges of the public API an embedding program meets: NULL options, indices out of range,
 * one string read by several threads, and limits of the skeleton's 32-bit fields. */
#include <pthread.h>

#include "unit.h"

#include "sylva/skeleton.h"

static const char *const model = "lsystem A {\n axiom F(1)\n F(x) -> F(x+1)[+F(x*2)]F(x)\n}\n";

static void derive_begin_accepts_null_options(void **state) {
    (void)state;
    SylProgram *p = unit_compile(model, NULL, NULL);
    assert_non_null(p);
    SylDeriver *d = NULL;
    /* it crashed: the engine read the options it was not given */
    assert_int_equal(syl_derive_begin(p, NULL, NULL, &d), SYL_OK);
    assert_int_equal(syl_derive_step(d), SYL_OK);
    assert_int_equal(syl_deriver_steps(d), 1);
    SylString *s = NULL;
    assert_int_equal(syl_derive_end(d, &s), SYL_OK);
    /* F(1) -> F(2) [ + F(2) ] F(1): six modules */
    assert_int_equal(syl_string_length(s), 6);
    syl_string_free(s);
    syl_program_free(p);
}

static void string_module_out_of_range(void **state) {
    (void)state;
    SylString *s = syl_string_new();
    double one = 1.5;
    assert_int_equal(syl_string_push(s, 3, 1, &one), SYL_OK);
    int np = 7;
    const double *par = &one;
    assert_int_equal(syl_string_module(s, 1, &np, &par), -1);
    assert_int_equal(np, 0);
    assert_null(par);
    assert_int_equal(syl_string_module(s, SIZE_MAX, NULL, NULL), -1);
    assert_int_equal(syl_string_module(s, 0, &np, &par), 3);
    assert_int_equal(np, 1);
    assert_true(par[0] == 1.5);
    /* a change after a read is seen: the offsets are rebuilt */
    double two[2] = {2, 3};
    assert_int_equal(syl_string_push(s, 4, 2, two), SYL_OK);
    assert_int_equal(syl_string_module(s, 1, &np, &par), 4);
    assert_int_equal(np, 2);
    assert_true(par[0] == 2 && par[1] == 3);
    syl_string_free(s);
}

typedef struct Reader {
    const SylString *s;
    double sum;
} Reader;

static void *read_all(void *arg) {
    Reader *r = arg;
    size_t n = syl_string_length(r->s);
    for (size_t i = 0; i < n; i++) {
        int np;
        const double *par;
        syl_string_module(r->s, i, &np, &par);
        for (int k = 0; k < np; k++) r->sum += par[k];
    }
    return NULL;
}

static void string_read_by_threads(void **state) {
    (void)state;
    /* modules with 0, 1 or 2 parameters, so every offset matters; the parameter sum is
     * known: sum over i of (i % 3 == 1 ? i : i % 3 == 2 ? i + 0.5 : 0) */
    SylString *s = syl_string_new();
    double expect = 0;
    enum { N = 200000, THREADS = 4 };
    for (int i = 0; i < N; i++) {
        double v[2] = {i, 0.5};
        int np = i % 3;
        assert_int_equal(syl_string_push(s, 1, np, v), SYL_OK);
        expect += np == 1 ? i : np == 2 ? i + 0.5 : 0;
    }
    for (int round = 0; round < 5; round++) {
        double x = 0;
        assert_int_equal(syl_string_push(s, 1, 1, &x), SYL_OK); /* stale cache each round */
        pthread_t t[THREADS];
        Reader r[THREADS];
        for (int k = 0; k < THREADS; k++) {
            r[k] = (Reader){.s = s};
            assert_int_equal(pthread_create(&t[k], NULL, read_all, &r[k]), 0);
        }
        for (int k = 0; k < THREADS; k++) {
            pthread_join(t[k], NULL);
            assert_true(r[k].sum == expect);
        }
    }
    syl_string_free(s);
}

static void polygon_first_stays_32_bit(void **state) {
    (void)state;
    SylSkeleton *sk = syl_skeleton_new("t");
    float v[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    assert_int_equal(syl_skeleton_add_polygon(sk, v, 3, -1, 0, 0), 0);
    assert_int_equal(sk->polys[0].first, 0);
    /* pretend 2^32 - 2 vertices are there: 3 more would not fit SylPolygon.first + count
     * (refused before any allocation) */
    size_t real = sk->nverts;
    sk->nverts = (size_t)UINT32_MAX - 1;
    assert_int_equal(syl_skeleton_add_polygon(sk, v, 3, -1, 0, 0), -1);
    assert_int_equal(sk->npolys, 1);
    assert_int_equal(sk->nverts, (size_t)UINT32_MAX - 1); /* no orphan vertices */
    sk->nverts = real;
    assert_int_equal(syl_skeleton_add_polygon(sk, v, 3, -1, 0, 0), 1);
    assert_int_equal(sk->polys[1].first, 3);
    syl_skeleton_free(sk);
}

/* An organ's struct has two bytes of padding (after material) that a caller's local leaves
 * unset: the skeleton stores them zeroed, so one seed gives one skeleton to the byte (the
 * pafco, curvetree and shoots tests compare organs with memcmp; under ASan they differed). */
static void organ_padding_is_zero(void **state) {
    (void)state;
    SylSkeleton *sk = syl_skeleton_new("t");
    SylOrgan o;
    memset(&o, 0xa5, sizeof o);
    o.node = -1, o.kind = SYL_KIND_LEAF, o.material = SYL_MATERIAL_LEAF, o.module = 7, o.size = 1;
    assert_int_equal(syl_skeleton_add_organ(sk, &o), 0);
    const unsigned char *b = (const unsigned char *)&sk->organs[0];
    for (size_t i = offsetof(SylOrgan, material) + 1; i < offsetof(SylOrgan, module); i++) assert_int_equal(b[i], 0);
    assert_int_equal(sk->organs[0].module, 7);
    assert_int_equal(sk->organs[0].material, SYL_MATERIAL_LEAF);
    syl_skeleton_free(sk);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(derive_begin_accepts_null_options),
        cmocka_unit_test(string_module_out_of_range),
        cmocka_unit_test(string_read_by_threads),
        cmocka_unit_test(polygon_first_stays_32_bit),
        cmocka_unit_test(organ_padding_is_zero),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
