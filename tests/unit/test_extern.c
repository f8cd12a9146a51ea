/* `extern` functions bound through the public API (sylva.h): the bound function answers every
 * call with the call's arguments, its failure stops the derivation, and an unbound extern runs
 * its default or fails. A(x) -> A(f(x)) with f(x) = 2x + 1 from A(0) gives 2^n - 1. */
#include <stdatomic.h>

#include "unit.h"

static const char *const model =
    "lsystem E {\n extern f(x)\n extern g(a, b) = a - b\n derive 6\n axiom A(0) B(5, 2)\n"
    " A(x) -> A(f(x))\n B(a, b) -> B(g(a, b), b)\n}\n";

typedef struct Calls {
    atomic_int n;
    int fail_at; /* the call that fails, 0: none */
} Calls;

static int twice_plus_one(void *user, const double *args, int nargs, double *out) {
    Calls *c = user;
    int k = atomic_fetch_add(&c->n, 1) + 1;
    if (nargs != 1 || k == c->fail_at) return 1;
    *out = 2 * args[0] + 1;
    return 0;
}

static int product(void *user, const double *args, int nargs, double *out) {
    (void)user;
    *out = nargs == 2 ? args[0] * args[1] : -1;
    return 0;
}

static double param(const SylString *s, size_t i, int k) {
    int np;
    const double *par;
    syl_string_module(s, i, &np, &par);
    return par[k];
}

static void lists_its_externs(void **state) {
    (void)state;
    SylProgram *p = unit_compile(model, NULL, NULL);
    assert_non_null(p);
    assert_int_equal(syl_program_extern_count(p), 2);
    int np = -1, def = -1;
    assert_string_equal(syl_program_extern(p, 0, &np, &def), "f");
    assert_int_equal(np, 1);
    assert_int_equal(def, 0);
    assert_string_equal(syl_program_extern(p, 1, &np, &def), "g");
    assert_int_equal(np, 2);
    assert_int_equal(def, 1);
    assert_null(syl_program_extern(p, 2, NULL, NULL));
    assert_null(syl_program_extern(p, -1, NULL, NULL));
    assert_int_equal(syl_program_bind_extern(p, "h", product, NULL), SYL_EUSAGE);
    syl_program_free(p);
}

static void bound_function_answers(void **state) {
    (void)state;
    SylProgram *p = unit_compile(model, NULL, NULL);
    Calls c = {0};
    assert_int_equal(syl_program_bind_extern(p, "f", twice_plus_one, &c), SYL_OK);
    SylDeriveOptions o = {.steps = 6, .threads = 4};
    SylString *s = NULL;
    assert_int_equal(syl_derive(p, &o, &s), SYL_OK);
    assert_true(param(s, 0, 0) == 63); /* 2^6 - 1 */
    assert_true(param(s, 1, 0) == 5 - 6 * 2); /* g's default: a - b, six times */
    assert_int_equal(atomic_load(&c.n), 6);
    syl_string_free(s);
    /* g bound too: 5 * 2^6 */
    assert_int_equal(syl_program_bind_extern(p, "g", product, NULL), SYL_OK);
    assert_int_equal(syl_derive(p, &o, &s), SYL_OK);
    assert_true(param(s, 1, 0) == 5 * 64);
    syl_string_free(s);
    syl_program_free(p);
}

static void failure_and_unbound_stop_it(void **state) {
    (void)state;
    SylProgram *p = unit_compile(model, NULL, NULL);
    Calls c = {.fail_at = 3};
    syl_program_bind_extern(p, "f", twice_plus_one, &c);
    char *text = NULL;
    size_t len = 0;
    SylDeriveOptions o = {.steps = 6, .threads = 1, .diag = open_memstream(&text, &len)};
    SylString *s = NULL;
    assert_int_equal(syl_derive(p, &o, &s), SYL_EMODEL);
    assert_null(s);
    assert_int_equal(atomic_load(&c.n), 3);
    fflush(o.diag);
    assert_non_null(strstr(text, "test.syl:6:12: error: the function bound to this extern failed (step 3"));
    /* unbound again: f has no default */
    assert_int_equal(syl_program_bind_extern(p, "f", NULL, NULL), SYL_OK);
    assert_int_equal(syl_derive(p, &o, &s), SYL_EMODEL);
    assert_null(s);
    fflush(o.diag);
    assert_non_null(strstr(text, "has no default and nothing is bound to it"));
    fclose(o.diag);
    free(text);
    syl_program_free(p);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(lists_its_externs),
        cmocka_unit_test(bound_function_answers),
        cmocka_unit_test(failure_and_unbound_stop_it),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
