/* Stochastic rules and random functions: frequencies, normalisation over the applicable
 * rules, reproducibility across seeds and thread counts. */
#include <math.h>

#include "unit.h"

/* A model whose axiom is n copies of module text m, followed by rules. */
static char *many(const char *m, int n, const char *rules) {
    size_t ml = strlen(m), rl = strlen(rules);
    char *text = malloc(64 + ml * (size_t)n + rl);
    char *p = text + sprintf(text, "lsystem T {\n  seed 7\n  axiom ");
    for (int i = 0; i < n; i++, p += ml) memcpy(p, m, ml);
    sprintf(p, "\n%s}\n", rules);
    return text;
}

/* count within 5 standard deviations of a binomial(n, prob) */
static void assert_binomial(uint64_t count, int n, double prob) {
    double mean = n * prob, sd = sqrt(n * prob * (1 - prob));
    if (fabs((double)count - mean) > 5 * sd + 1e-9)
        fail_msg("count %llu, expected %.1f +- %.1f (5 sd)", (unsigned long long)count, mean, 5 * sd);
}

static UnitRun run1(const char *text, int steps, int threads, uint64_t seed) {
    UnitRun r = unit_run(text, (SylDeriveOptions){.steps = steps, .threads = threads, .use_seed = seed != 0, .seed = seed});
    if (r.status != SYL_OK) fail_msg("status %d:\n%s", r.status, r.diag);
    return r;
}

static void weights_1_2_7(void **state) {
    const int n = 20000;
    char *text = many("A", n, "  A -> B : 1\n  A -> C : 2\n  A -> D : 7\n");
    UnitRun r = run1(text, 1, 1, 0);
    assert_int_equal(syl_string_length(r.s), n);
    assert_binomial(unit_count(&r, "B"), n, 0.1);
    assert_binomial(unit_count(&r, "C"), n, 0.2);
    assert_binomial(unit_count(&r, "D"), n, 0.7);
    assert_int_equal(unit_count(&r, "A"), 0);
    unit_run_free(&r);
    free(text);
}

/* Weights that are expressions of the module's parameters. */
static void weights_from_parameters(void **state) {
    const int n = 20000;
    char *text = many("A(1)A(3)", n / 2, "  A(x) -> B : x\n  A(x) -> C : 4 - x\n");
    UnitRun r = run1(text, 1, 1, 0);
    /* A(1): B with 1/4; A(3): B with 3/4; count each half apart */
    uint64_t b1 = 0, b3 = 0;
    int sb = syl_program_symbol_find(r.p, "B");
    for (size_t i = 0; i < syl_string_length(r.s); i++)
        if (syl_string_module(r.s, i, NULL, NULL) == sb) *(i % 2 ? &b3 : &b1) += 1;
    assert_binomial(b1, n / 2, 0.25);
    assert_binomial(b3, n / 2, 0.75);
    unit_run_free(&r);
    free(text);
}

/* A weighted rule whose condition is false takes no part: the others share the whole. */
static void normalised_over_applicable_rules(void **state) {
    const int n = 20000;
    char *text = many("A(0)", n, "  A(x) : x > 5 -> B : 8\n  A(x) -> C : 1\n  A(x) -> D : 1\n");
    UnitRun r = run1(text, 1, 1, 0);
    assert_int_equal(unit_count(&r, "B"), 0);
    assert_int_equal(unit_count(&r, "A"), 0); /* identity is never chosen */
    assert_binomial(unit_count(&r, "C"), n, 0.5);
    assert_binomial(unit_count(&r, "D"), n, 0.5);
    unit_run_free(&r);
    free(text);
    /* the same with a context that does not match */
    text = many("A", n, "  Q < A -> B : 8\n  A -> C : 1\n  A -> D : 3\n");
    r = run1(text, 1, 1, 0);
    assert_int_equal(unit_count(&r, "B"), 0);
    assert_binomial(unit_count(&r, "C"), n, 0.25);
    assert_binomial(unit_count(&r, "D"), n, 0.75);
    unit_run_free(&r);
    free(text);
}

/* Rules are tried in order: an unweighted rule before the weighted ones wins where it
 * applies; where it does not, the weighted ones decide. */
static void first_applicable_rule_decides(void **state) {
    const int n = 10000;
    char *text = many("A(1)A(0)", n / 2, "  A(x) : x > 0 -> U\n  A(x) -> B : 1\n  A(x) -> C : 1\n");
    UnitRun r = run1(text, 1, 1, 0);
    assert_int_equal(unit_count(&r, "U"), n / 2);
    int su = syl_program_symbol_find(r.p, "U");
    for (size_t i = 0; i < syl_string_length(r.s); i += 2) assert_int_equal(syl_string_module(r.s, i, NULL, NULL), su);
    assert_binomial(unit_count(&r, "B"), n / 2, 0.5);
    assert_binomial(unit_count(&r, "C"), n / 2, 0.5);
    unit_run_free(&r);
    free(text);
    /* an unweighted rule after weighted ones that apply is not part of the choice */
    text = many("A", n, "  A -> B : 1\n  A -> C : 1\n  A -> U\n");
    r = run1(text, 1, 1, 0);
    assert_int_equal(unit_count(&r, "U"), 0);
    assert_binomial(unit_count(&r, "B"), n, 0.5);
    unit_run_free(&r);
    free(text);
    /* all weights zero: no rule is chosen, the module stays */
    assert_derives("lsystem T {\n  axiom AA\n  A -> B : 0\n  A -> C : 0\n}\n", 1, "AA");
}

/* A stochastic bush that grows to a few thousand modules. */
static const char *bush = "lsystem Bush {\n"
                          "  derive 6\n"
                          "  seed 11\n"
                          "  axiom F\n"
                          "  F -> F[+F]F[-F]F : 1\n"
                          "  F -> F[+F]F : 1\n"
                          "  F -> F[-F]F : 1\n"
                          "}\n";

static void same_seed_same_string(void **state) {
    UnitRun a = run1(bush, -1, 1, 0), b = run1(bush, -1, 1, 0), c = run1(bush, -1, 1, 11);
    char *sa = unit_string(&a), *sb = unit_string(&b), *sc = unit_string(&c);
    assert_true(strlen(sa) > 500);
    assert_string_equal(sa, sb);
    assert_string_equal(sa, sc); /* use_seed with the model's own seed */
    UnitRun d = run1(bush, -1, 1, 12), e = run1(bush, -1, 1, 13);
    char *sd = unit_string(&d), *se = unit_string(&e);
    assert_string_not_equal(sa, sd);
    assert_string_not_equal(sa, se);
    assert_string_not_equal(sd, se);
    free(sa), free(sb), free(sc), free(sd), free(se);
    unit_run_free(&a), unit_run_free(&b), unit_run_free(&c), unit_run_free(&d), unit_run_free(&e);
}

/* A string of more than 100000 modules is rewritten by several threads (above 65536
 * modules): every choice, every random parameter and every context must be the same. */
static void threads_do_not_change_the_result(void **state) {
    const char *text = "lsystem T {\n"
                       "  derive 18\n"
                       "  seed 5\n"
                       "  axiom A(0)\n"
                       "  A(x) > [B(y)] : y > 7 -> A(x - y) [C(y)]\n"
                       "  A(x) -> A(x + 1) A(uniform(0, 8)) : 2\n"
                       "  A(x) -> A(normal(x, 1)) [B(x)] A(x) : 1\n"
                       "  A(x) < B(y) -> B(x + y)\n"
                       "  B(y) > [C(z)] -> B(y + z)\n"
                       "}\n";
    UnitRun one = run1(text, -1, 1, 0), four = run1(text, -1, 4, 0);
    size_t n = syl_string_length(one.s);
    assert_true(n > 100000);
    assert_int_equal(syl_string_length(four.s), n);
    char *s1 = unit_string(&one), *s4 = unit_string(&four);
    assert_string_equal(s1, s4);
    free(s1), free(s4);
    /* and the random parameters were really drawn: not all the same */
    assert_true(unit_count(&one, "C") > 1000);
    unit_run_free(&one), unit_run_free(&four);

    /* the same on a wide axiom with weighted choices in the first step */
    char *wide = many("A(0)", 120000, "  A(x) -> B : 1\n  A(x) -> C(uniform(0, 1)) : 1\n  B -> D(normal(0, 1))\n");
    UnitRun w1 = run1(wide, 2, 1, 0), w4 = run1(wide, 2, 4, 0), w3 = run1(wide, 2, 3, 0);
    s1 = unit_string(&w1), s4 = unit_string(&w4);
    char *s3 = unit_string(&w3);
    assert_string_equal(s1, s4);
    assert_string_equal(s1, s3);
    assert_binomial(unit_count(&w1, "D"), 120000, 0.5);
    free(s1), free(s3), free(s4);
    unit_run_free(&w1), unit_run_free(&w3), unit_run_free(&w4);
    free(wide);
}

/* A large string without parameters, rewritten into one with parameters, then rewritten
 * again: the second step must not be refused for lack of memory. */
static void parameters_appear_in_a_large_string(void **state) {
    const int n = 40000;
    char *text = many("A", n, "  A -> B(1)\n  B(x) -> B(x + 1)\n");
    for (int threads = 1; threads <= 4; threads += 3) {
        UnitRun r = unit_run(text, (SylDeriveOptions){.steps = 2, .threads = threads});
        if (r.status != SYL_OK) {
            print_error("threads %d, status %d:\n%s", threads, r.status, r.diag);
            unit_run_free(&r);
            free(text);
            fail();
        }
        assert_int_equal(unit_count(&r, "B"), n);
        assert_true(unit_param(&r, n - 1, 0) == 2);
        unit_run_free(&r);
    }
    free(text);
}

static void random_functions(void **state) {
    const int n = 20000;
    char *text = many("A", n, "  A -> B(uniform(2, 5), normal(10, 2), uniform(-1, -1))\n");
    UnitRun r = run1(text, 1, 1, 0), again = run1(text, 1, 1, 0), other = run1(text, 1, 1, 99);
    double su = 0, sn = 0, sn2 = 0, lo = 1e9, hi = -1e9;
    size_t same_as_other = 0;
    for (size_t i = 0; i < (size_t)n; i++) {
        double u = unit_param(&r, i, 0), g = unit_param(&r, i, 1);
        assert_true(u >= 2 && u < 5);
        assert_true(unit_param(&r, i, 2) == -1);
        assert_true(u == unit_param(&again, i, 0) && g == unit_param(&again, i, 1));
        same_as_other += u == unit_param(&other, i, 0);
        su += u;
        sn += g;
        sn2 += g * g;
        if (u < lo) lo = u;
        if (u > hi) hi = u;
    }
    /* uniform(2, 5): mean 3.5, sd sqrt(0.75); normal(10, 2): mean 10, sd 2 */
    assert_near(su / n, 3.5, 5 * sqrt(0.75 / n));
    assert_true(lo < 2.01 && hi > 4.99);
    double mean = sn / n, var = sn2 / n - mean * mean;
    assert_near(mean, 10, 5 * 2 / sqrt(n));
    assert_near(var, 4, 0.25);
    assert_true(same_as_other < 10); /* another seed, other draws */
    /* two draws in one module are different numbers */
    assert_true(unit_param(&r, 0, 0) != unit_param(&r, 1, 0));
    unit_run_free(&r), unit_run_free(&again), unit_run_free(&other);
    free(text);
}

/* Draws are keyed by (seed, step, module): the same module position in another step
 * draws other numbers, and a module's draws do not depend on the string before it. */
static void draws_are_keyed(void **state) {
    const char *text = "lsystem T {\n  seed 3\n  axiom A(0)\n  A(x) -> A(uniform(0, 1))\n}\n";
    UnitRun a = run1(text, 1, 1, 0), b = run1(text, 2, 1, 0);
    assert_true(unit_param(&a, 0, 0) != unit_param(&b, 0, 0));
    unit_run_free(&a), unit_run_free(&b);
    /* B's rewriting does not move A's stream: position 1 draws the same as before */
    const char *t1 = "lsystem T {\n  seed 3\n  axiom X A\n  A -> C(uniform(0, 1))\n}\n";
    const char *t2 = "lsystem T {\n  seed 3\n  axiom Y A\n  A -> C(uniform(0, 1))\n  Y -> Y(uniform(0, 1))\n}\n";
    a = run1(t1, 1, 1, 0), b = run1(t2, 1, 1, 0);
    assert_true(unit_param(&a, 1, 0) == unit_param(&b, 1, 0));
    unit_run_free(&a), unit_run_free(&b);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(weights_1_2_7),
        cmocka_unit_test(weights_from_parameters),
        cmocka_unit_test(normalised_over_applicable_rules),
        cmocka_unit_test(first_applicable_rule_decides),
        cmocka_unit_test(same_seed_same_string),
        cmocka_unit_test(threads_do_not_change_the_result),
        cmocka_unit_test(parameters_appear_in_a_large_string),
        cmocka_unit_test(random_functions),
        cmocka_unit_test(draws_are_keyed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
