/* Branch-aware context matching (ABOP §1.8), seen through derivations. */
#include "unit.h"

/* One rule (or several, separated by \n) applied once to an axiom. */
static void one_step(const char *axiom, const char *rules, const char *expected) {
    char text[1024];
    snprintf(text, sizeof text, "lsystem T {\n  axiom %s\n%s\n}\n", axiom, rules);
    char *got = unit_derive(text, 1, 1);
    if (!got) fail_msg("did not derive:\n%s", text);
    if (strcmp(got, expected)) fail_msg("%s  on %s\n  gave     %s\n  expected %s", rules, axiom, got, expected);
    free(got);
}

static void abop_1_8_example(void **state) {
    const char *ax = "ABC[DE][SG[HI[JK]L]MNO]";
    one_step(ax, "  BC < S > G[H]M -> X", "ABC[DE][XG[HI[JK]L]MNO]");
    /* each part matters */
    one_step(ax, "  BC < S > G[I]M -> X", ax);
    one_step(ax, "  BD < S > G[H]M -> X", ax);
    one_step(ax, "  BC < S > G[H]N -> X", ax);
    one_step(ax, "  E < S -> X", ax); /* a sibling branch is not on the path to the root */
    one_step(ax, "  AB < C -> X", "ABX[DE][SG[HI[JK]L]MNO]");
    one_step(ax, "  C < S -> X", "ABC[DE][XG[HI[JK]L]MNO]");
    one_step(ax, "  S > GM -> X", "ABC[DE][XG[HI[JK]L]MNO]");
    one_step(ax, "  G < M -> X", "ABC[DE][SG[HI[JK]L]XNO]");
    one_step(ax, "  I < L -> X", "ABC[DE][SG[HI[JK]X]MNO]");
}

static void left_context_skips_side_branches(void **state) {
    one_step("A[B]C", "  A < C -> X", "A[B]X");
    one_step("A[B][D[E]F]C", "  A < C -> X", "A[B][D[E]F]X");
    one_step("A[B]C", "  B < C -> X", "A[B]C");
    /* inside a branch the left context is the module the branch grows from */
    one_step("A[B]C", "  A < B -> X", "A[X]C");
    one_step("A[B[C]]", "  AB < C -> X", "A[B[X]]");
    one_step("A[B[C]]", "  A < C -> X", "A[B[C]]");
    /* nothing is left of the first module */
    one_step("AB", "  B < A -> X", "AB");
    one_step("[A]B", "  B < A -> X", "[A]B");
}

static void right_context_skips_branches(void **state) {
    one_step("A[B]C", "  A > C -> X", "X[B]C");
    one_step("A[B][D]CE", "  A > CE -> X", "X[B][D]CE");
    /* a branch not written in the context is not entered */
    one_step("A[B]C", "  A > B -> X", "A[B]C");
    /* a branch written in the context is */
    one_step("A[B]C", "  A > [B]C -> X", "X[B]C");
    one_step("A[B]C", "  A > [B] -> X", "X[B]C");
    one_step("A[D][B]C", "  A > [B]C -> X", "X[D][B]C");
    one_step("A[BE]C", "  A > [B]C -> X", "X[BE]C"); /* the rest of the branch is skipped */
    one_step("A[B]C", "  A > [C] -> X", "A[B]C");
    one_step("AD[B]C", "  A > [B] -> X", "AD[B]C"); /* the branch must start right here */
}

/* A rule whose right context names a branch does not change how the others' right contexts
 * match (issue 11): each pair gives the same string with and without the bracketed rule,
 * whose predecessor never occurs. */
static void bracketed_rule_leaves_others_alone(void **state) {
    static const char *const bracketed = "\n  Y(c) > [Y(a)]Y(b) -> Y(a + b + c)";
    static const struct {
        const char *axiom, *rules, *expected;
    } cases[] = {
        {"U[-W[+W]W]", "  ignore + -\n  W > W -> Q", "U[-Q[+W]W]"},
        {"A[B]C", "  A > C -> X", "X[B]C"},
        {"A[B][D[E]F]CE", "  A > CE -> X", "X[B][D[E]F]CE"},
        {"A[B]C", "  A > B -> X", "A[B]C"},
        {"A[BC]D", "  B > C -> X\n  C > D -> Z", "A[XC]D"},
        {"A(1)[B(2)]C(3)", "  A(x) > C(y) -> A(x + y)", "A(4)[B(2)]C(3)"},
        {"AFB[F[FC]]B", "  consider A B C\n  A > B -> X\n  B > C -> Y", "XFB[F[FC]]B"},
    };
    char rules[256];
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        one_step(cases[k].axiom, cases[k].rules, cases[k].expected);
        snprintf(rules, sizeof rules, "%s%s", cases[k].rules, bracketed);
        one_step(cases[k].axiom, rules, cases[k].expected);
    }
    /* and the bracketed rule still applies beside them */
    one_step("Y(1)[Y(2)]Y(3)W", "  W > W -> Q\n  Y(c) > [Y(a)]Y(b) -> Y(a + b + c)\n  Y(x) > W -> Q",
             "Y(6)[Y(2)]QW");
}

static void branch_ends_block_contexts(void **state) {
    one_step("A[B]C", "  B > C -> X", "A[B]C");
    one_step("[A]B", "  A > B -> X", "[A]B");
    one_step("A[B]", "  B > C -> X", "A[B]");
    one_step("A[BC]D", "  B > CD -> X", "A[BC]D");
    one_step("A[BC]D", "  B > C -> X", "A[XC]D");
    one_step("AB", "  B > A -> X", "AB");
}

static void contexts_of_several_modules(void **state) {
    one_step("ABCDE", "  AB < C > DE -> X", "ABXDE");
    one_step("ABCDE", "  AB < C > ED -> X", "ABCDE");
    one_step("ABCDE", "  BA < C -> X", "ABCDE");
    one_step("A[Q]B[R]C[S]DE", "  AB < C > DE -> X", "A[Q]B[R]X[S]DE");
}

static void ignore_and_consider(void **state) {
    one_step("A+-B-C", "  A < B > C -> X", "A+-B-C");
    one_step("A+-B-C", "  ignore + -\n  A < B > C -> X", "A+-X-C");
    one_step("A+F[-G]B", "  ignore + - F G\n  A < B -> X", "A+F[-G]X");
    one_step("A+F-B", "  consider A B\n  A < B -> X", "A+F-X");
    one_step("A+F-B", "  consider A F\n  A < B -> X", "A+F-B");
    one_step("AFB[F[FC]]", "  consider A B C\n  B > C -> X", "AFB[F[FC]]");
    one_step("AFB[F[FC]]", "  consider A B C\n  B > [[C]] -> X", "AFX[F[FC]]");
    /* an ignored module is still rewritten, and has contexts of its own */
    one_step("A+B", "  ignore +\n  A < + > B -> X", "AXB");
}

static void parametric_contexts_bind(void **state) {
    one_step("A(1)B(2)C(3)", "  A(x) < B(y) > C(z) -> B(x + y + z)", "A(1)B(6)C(3)");
    one_step("A(1)[Q]B(2)[R]C(3)", "  A(x) < B(y) > C(z) -> B(x * 100 + y * 10 + z)", "A(1)[Q]B(123)[R]C(3)");
    one_step("A(1)B(2)[C(5)]D(7)", "  A(x) < B(y) > [C(z)]D(w) -> B(x, y, z, w)", "A(1)B(1,2,5,7)[C(5)]D(7)");
    /* a context module with another number of parameters is another module */
    one_step("A(1,2)B(2)C(3)", "  A(x) < B(y) > C(z) -> X", "A(1,2)B(2)C(3)");
    /* conditions see the context's values */
    one_step("A(1)B(2)A(5)B(2)", "  A(x) < B(y) : x > y -> X(x - y)", "A(1)B(2)A(5)X(3)");
}

/* When weighted rules with different contexts all apply, the chosen one's parameters are
 * bound, not the last one tried. */
static void chosen_rule_binds_its_own_context(void **state) {
    char text[8192] = "lsystem T {\n  axiom ";
    for (int i = 0; i < 200; i++) strcat(text, "L(1)AR(2)");
    strcat(text, "\n  L(a) < A -> X(a) : 1\n  A > R(b) -> Y(b) : 1\n}\n");
    UnitRun r = unit_run(text, (SylDeriveOptions){.steps = 1, .threads = 1});
    assert_int_equal(r.status, SYL_OK);
    uint64_t nx = 0, ny = 0;
    int sx = syl_program_symbol_find(r.p, "X"), sy = syl_program_symbol_find(r.p, "Y");
    for (size_t i = 0; i < syl_string_length(r.s); i++) {
        int np;
        const double *par;
        int sym = syl_string_module(r.s, i, &np, &par);
        if (sym == sx) {
            nx++;
            assert_true(par[0] == 1);
        } else if (sym == sy) {
            ny++;
            assert_true(par[0] == 2);
        }
    }
    assert_int_equal(nx + ny, 200);
    assert_true(nx > 50 && ny > 50);
    unit_run_free(&r);
}

static void step_by_step(const char *text, const char *const *want, int n) {
    for (int i = 0; i < n; i++) {
        char *got = unit_derive(text, i, 1);
        assert_non_null(got);
        if (strcmp(got, want[i])) fail_msg("step %d: %s, expected %s", i, got, want[i]);
        free(got);
    }
}

/* A signal moves up the main axis and into branches, one module per step (ABOP §1.8). */
static void acropetal_signal(void **state) {
    static const char *const want[] = {
        "SFA[FA]FA[FA]FA", "AFS[FA]FA[FA]FA", "AFA[FS]FS[FA]FA", "AFA[FA]FA[FS]FS", "AFA[FA]FA[FA]FA",
    };
    step_by_step("lsystem T {\n  ignore F\n  axiom S F A[F A]F A[F A]F A\n  S < A -> S\n  S -> A\n}\n", want, 5);
}

/* And down the main axis, one module per step: right contexts skip the side branches. */
static void basipetal_signal(void **state) {
    static const char *const want[] = {
        "AFA[FA]FA[FA]FS", "AFA[FA]FS[FA]FA", "AFS[FA]FA[FA]FA", "SFA[FA]FA[FA]FA", "AFA[FA]FA[FA]FA",
    };
    step_by_step("lsystem T {\n  ignore F\n  axiom A F A[F A]F A[F A]F S\n  A > S -> S\n  S -> A\n}\n", want, 5);
    /* out of a branch it takes a context that names the branch */
    static const char *const up[] = {"AFA[FA]FA[FS]FA", "AFA[FA]FS[FA]FA", "AFA[FA]FA[FA]FA"};
    step_by_step("lsystem T {\n  ignore F\n  axiom A F A[F A]F A[F S]F A\n  A > [S] -> S\n  S -> A\n}\n", up, 3);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(abop_1_8_example),
        cmocka_unit_test(left_context_skips_side_branches),
        cmocka_unit_test(right_context_skips_branches),
        cmocka_unit_test(bracketed_rule_leaves_others_alone),
        cmocka_unit_test(branch_ends_block_contexts),
        cmocka_unit_test(contexts_of_several_modules),
        cmocka_unit_test(ignore_and_consider),
        cmocka_unit_test(parametric_contexts_bind),
        cmocka_unit_test(chosen_rule_binds_its_own_context),
        cmocka_unit_test(acropetal_signal),
        cmocka_unit_test(basipetal_signal),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
