/* The checker: errors and warnings of syl_compile (lint on), with their locations. */
#include <stdbool.h>

#include "unit.h"
#include "util/closest.h"

/* Compile text; it must fail with SYL_EMODEL and report `where` (a "test.syl:L:C: error:"
 * prefix) followed on the same line by what. */
static void expect_error(const char *text, const char *where, const char *what) {
    int st = -1;
    char *diag = NULL;
    SylProgram *p = unit_compile(text, &diag, &st);
    if (p) fail_msg("compiled, but expected %s %s; diagnostics:\n%s", where, what, diag ? diag : "");
    assert_int_equal(st, SYL_EMODEL);
    const char *at = strstr(diag, where);
    if (!at) fail_msg("expected \"%s\" in:\n%s", where, diag);
    const char *eol = strchr(at, '\n');
    const char *found = strstr(at, what);
    if (!found || (eol && found > eol)) fail_msg("expected \"%s%s\" in:\n%s", where, what, diag);
    free(diag);
}

/* Compile text; it must succeed and warn `what` at `where` ("test.syl:L:C: warning:"). */
static void expect_warning(const char *text, const char *where, const char *what) {
    int st = -1;
    char *diag = NULL;
    SylProgram *p = unit_compile(text, &diag, &st);
    if (!p) fail_msg("failed to compile:\n%s", diag);
    assert_int_equal(st, SYL_OK);
    assert_not_contains(diag, "error:");
    const char *at = strstr(diag, where);
    if (!at) fail_msg("expected \"%s\" in:\n%s", where, diag);
    const char *eol = strchr(at, '\n');
    const char *found = strstr(at, what);
    if (!found || (eol && found > eol)) fail_msg("expected \"%s%s\" in:\n%s", where, what, diag);
    free(diag);
    syl_program_free(p);
}

/* Compile text; it must succeed with no diagnostics at all. */
static void expect_clean(const char *text) {
    int st = -1;
    char *diag = NULL;
    SylProgram *p = unit_compile(text, &diag, &st);
    if (!p) fail_msg("failed to compile:\n%s", diag);
    assert_int_equal(st, SYL_OK);
    if (diag && *diag) fail_msg("expected no diagnostics, got:\n%s", diag);
    free(diag);
    syl_program_free(p);
}

/* ---- errors ---- */

static void unknown_name(void **state) {
    expect_error("lsystem T {\n  axiom A(x)\n}\n", "test.syl:2:11: error: ", "unknown name 'x'");
    /* a rule can only use the parameters it binds */
    expect_error("lsystem T {\n  axiom A(1)\n  A(x) -> B(y)\n}\n", "test.syl:3:13: error: ", "unknown name 'y'");
    expect_error("lsystem T {\n  axiom A(sin)\n}\n", "test.syl:2:11: error: ", "'sin' is a function");
}

static void unknown_function(void **state) {
    expect_error("lsystem T {\n  axiom A(foo(1))\n}\n", "test.syl:2:11: error: ", "unknown function 'foo'");
}

static void wrong_argument_count(void **state) {
    expect_error("lsystem T {\n  axiom A(sin(1, 2))\n}\n", "test.syl:2:11: error: ", "'sin' takes 1 argument, not 2");
    expect_error("lsystem T {\n  fn f(a, b) = a + b\n  axiom A(f(1))\n}\n", "test.syl:3:11: error: ",
                 "function 'f' takes 2 arguments, not 1");
    expect_error("lsystem T {\n  curve c = (0, 0), (1, 1)\n  axiom A(c(1, 2))\n}\n", "test.syl:3:11: error: ",
                 "curve 'c' takes 1 argument, not 2");
    expect_error("lsystem T {\n  axiom A(clamp(1, 2))\n}\n", "test.syl:2:11: error: ", "'clamp' takes 3 arguments, not 2");
}

static void redefinition(void **state) {
    expect_error("lsystem T {\n  const a = 1\n  const a = 2\n  axiom A(a)\n}\n", "test.syl:3:9: error: ",
                 "'a' is already defined");
    expect_error("lsystem T {\n  fn k(a) = a\n  const k = 2\n  axiom A(k(1))\n}\n", "test.syl:3:9: error: ",
                 "'k' is already defined");
    expect_error("lsystem T {\n  param p = 1\n  fn p(a) = a\n  axiom A(p)\n}\n", "test.syl:3:6: error: ",
                 "'p' is already defined");
    expect_error("lsystem T {\n  fn g(a, a) = a\n  axiom A(g(1, 2))\n}\n", "test.syl:2:11: error: ",
                 "parameter 'a' is named twice");
    expect_error("lsystem T {\n  axiom A(1)B(2)\n  A(x) < B(x) -> C\n}\n", "test.syl:3:5: error: ",
                 "parameter 'x' is bound twice");
}

/* A curve named like an earlier const or fn is a redefinition, not a crash. */
static void curve_redefinition(void **state) {
    expect_error("lsystem T {\n  const k = 1\n  curve k = (0, 0), (1, 1)\n  axiom A(k)\n}\n", "test.syl:3:9: error: ",
                 "'k' is already defined");
    expect_error("lsystem T {\n  fn k(a) = a\n  curve k = (0, 0), (1, 1)\n  axiom A(k(1))\n}\n",
                 "test.syl:3:9: error: ", "'k' is already defined");
}

static void module_arity(void **state) {
    expect_error("lsystem T {\n  module A(x)\n  axiom A(1, 2)\n}\n", "test.syl:3:9: error: ",
                 "module 'A' takes 1 parameter (declared at line 2), not 2");
    expect_error("lsystem T {\n  module A(x)\n  axiom A(1)\n  A -> B\n}\n", "test.syl:4:3: error: ",
                 "module 'A' takes 1 parameter (declared at line 2), not 0");
    expect_error("lsystem T {\n  module A(x)\n  module A(x, y)\n  axiom A(1)\n}\n", "test.syl:3:10: error: ",
                 "module 'A' was declared with 1 parameter");
    /* the declaration is honoured where the module is used correctly */
    expect_clean("lsystem T {\n  module Apex(a, b)\n  axiom F Apex(1, 2)\n  Apex(a, b) -> Apex(b, a)\n}\n");
}

static void const_used_before_defined(void **state) {
    expect_error("lsystem T {\n  const a = b\n  const b = 1\n  axiom A(a)\n}\n", "test.syl:2:13: error: ",
                 "'b' is used before its value is known");
    /* in the right order it is fine, and the value is computed */
    assert_derives("lsystem T {\n  const b = 2\n  const a = b * 3\n  axiom A(a)\n}\n", 0, "A(6)");
}

static void random_in_const(void **state) {
    expect_error("lsystem T {\n  const a = uniform(0, 1)\n  axiom A(a)\n}\n", "test.syl:2:13: error: ",
                 "cannot be random");
    expect_error("lsystem T {\n  derive normal(3, 1)\n  axiom A\n}\n", "test.syl:2:10: error: ", "cannot be random");
}

/* One mistake, one message: a const whose definition failed is not "used before its value
 * is known" where it is used later. */
static void no_cascading_errors(void **state) {
    const char *texts[] = {
        "lsystem T {\n  const a = uniform(0, 1)\n  axiom A(a)\n}\n",
        "lsystem T {\n  const a = b\n  const b = 1\n  axiom A(a)\n}\n",
        "lsystem T {\n  const a = nosuch\n  axiom A(a)\n}\n",
    };
    for (size_t i = 0; i < sizeof texts / sizeof *texts; i++) {
        int st = -1;
        char *diag = NULL;
        assert_null(unit_compile(texts[i], &diag, &st));
        int n = unit_occurrences(diag, ": error:");
        if (n != 1) print_error("expected one error in:\n%s", diag);
        free(diag);
        assert_int_equal(n, 1);
    }
}

static void negative_weight(void **state) {
    expect_error("lsystem T {\n  axiom A\n  A -> B : -1\n  A -> C : 2\n}\n", "test.syl:3:12: error: ",
                 "a weight must not be negative");
    expect_error("lsystem T {\n  const w = 0.5\n  axiom A\n  A -> B : 1 - 2 * w - 1\n}\n", "test.syl:4:", "must not be negative");
}

static void unbalanced_brackets(void **state) {
    expect_error("lsystem T {\n  axiom A\n  A -> B]\n}\n", "test.syl:3:9: error: ", "']' closes no branch");
    expect_error("lsystem T {\n  axiom A\n  A -> [B\n}\n", "test.syl:3:", "is never closed");
    expect_error("lsystem T {\n  axiom A\n  A -> ][\n}\n", "test.syl:3:8: error: ", "']' closes no branch");
    expect_error("lsystem T {\n  axiom A\n  A > [B -> C\n}\n", "test.syl:3:7: error: ", "'[' without ']'");
    expect_error("lsystem T {\n  axiom A\n  A > B] -> C\n}\n", "test.syl:3:8: error: ", "']' without '['");
}

/* The message for an axiom talks about the axiom. */
static void unbalanced_axiom(void **state) {
    int st = -1;
    char *diag = NULL;
    assert_null(unit_compile("lsystem T {\n  axiom A[B\n}\n", &diag, &st));
    assert_int_equal(st, SYL_EMODEL);
    assert_contains(diag, "test.syl:2:");
    assert_contains(diag, "never closed");
    bool successor = strstr(diag, "successor") != NULL;
    if (successor) print_error("%s", diag);
    free(diag);
    assert_false(successor);
}

static void predecessor_is_one_module(void **state) {
    expect_error("lsystem T {\n  axiom AB\n  AB -> C\n}\n", "test.syl:3:3: error: ", "'AB' is not a declared module: declare it");
    expect_error("lsystem T {\n  axiom A\n  [ -> C\n}\n", "test.syl:3:3: error: ", "a predecessor is one module");
    /* a declared name is one module */
    expect_clean("lsystem T {\n  module AB\n  axiom F AB\n  AB -> C\n}\n");
}

static void left_context_without_branches(void **state) {
    expect_error("lsystem T {\n  axiom A[B]C\n  A[B] < C -> X\n}\n", "test.syl:3:4: error: ",
                 "a left context cannot hold branches");
}

static void pattern_parameters_are_names(void **state) {
    expect_error("lsystem T {\n  axiom A(1)\n  A(x + 1) -> B\n}\n", "test.syl:3:7: error: ", "must be names");
}

static void settings_and_axiom(void **state) {
    expect_error("lsystem T {\n  derive 2.5\n  axiom A\n}\n", "test.syl:2:10: error: ", "'derive' must be a whole number");
    expect_error("lsystem T {\n  derive 1\n  derive 2\n  axiom A\n}\n", "test.syl:3:3: error: ",
                 "'derive' is set twice (first at line 2)");
    expect_error("lsystem T {\n  axiom A\n  axiom B\n}\n", "test.syl:3:3: error: ", "a model has one axiom");
    expect_error("lsystem T {\n  A -> B\n}\n", "test.syl:1:9: error: ", "model 'T' has no axiom");
}

/* ---- --set ---- */

static SylProgram *compile_with(const char *text, const SylOverride *ov, int n, char **diag, int *st) {
    size_t len = 0;
    FILE *mem = open_memstream(diag, &len);
    SylCompileOptions opt = {.diag = mem, .lint = 1, .overrides = ov, .noverrides = n,
                             .validate = syl_validate};
    SylProgram *p = syl_compile("test.syl", text, strlen(text), &opt, st);
    fclose(mem);
    return p;
}

static void set_parameters(void **state) {
    const char *text = "lsystem T {\n  param lat = 45\n  const k = 2\n  axiom A(lat, k)\n}\n";
    char *diag = NULL;
    int st = -1;
    SylOverride ok = {"lat", 30};
    SylProgram *p = compile_with(text, &ok, 1, &diag, &st);
    assert_non_null(p);
    assert_int_equal(st, SYL_OK);
    SylString *s = NULL;
    assert_int_equal(syl_derive(p, &(SylDeriveOptions){.steps = 0, .threads = 1}, &s), SYL_OK);
    int np;
    const double *par;
    syl_string_module(s, 0, &np, &par);
    assert_int_equal(np, 2);
    assert_true(par[0] == 30 && par[1] == 2);
    syl_string_free(s);
    syl_program_free(p);
    free(diag);

    /* an unknown name is a bad command line: the model itself is fine */
    SylOverride bad = {"nosuch", 1};
    assert_null(compile_with(text, &bad, 1, &diag, &st));
    assert_contains(diag, "test.syl: error: --set nosuch: model 'T' has no parameter or setting 'nosuch'");
    free(diag);
    assert_int_equal(st, SYL_EUSAGE);

    SylOverride konst = {"k", 1};
    assert_null(compile_with(text, &konst, 1, &diag, &st));
    assert_contains(diag, "has no parameter or setting 'k' (it is a const");
    free(diag);
    assert_int_equal(st, SYL_EUSAGE);

    /* a setting: over the file's line, and over the default when the file has none */
    const char *set = "lsystem T {\n  angle 90\n  axiom F\n}\n";
    SylOverride angles[] = {{"angle", 30}, {"step", 2.5}, {"T.width", 0.3}};
    p = compile_with(set, angles, 3, &diag, &st);
    assert_non_null(p);
    assert_true(syl_program_setting(p, "angle") == 30 && syl_program_setting(p, "step") == 2.5);
    assert_true(syl_program_setting(p, "width") == 0.3);
    syl_program_free(p);
    free(diag);
    SylOverride far = {"angle", 1e10}; /* the file's range holds */
    assert_null(compile_with(set, &far, 1, &diag, &st));
    assert_contains(diag, "--set angle=10000000000: 'angle' 10000000000 is out of range (at most 1000000000)");
    free(diag);
    assert_int_equal(st, SYL_EUSAGE);
}

/* Close names: the edit distance counts a swap of neighbours as one edit. */
static void close_names(void **state) {
    assert_int_equal(closest_distance("Leef", "Leaf", 2), 1);
    assert_int_equal(closest_distance("lamda", "lambda", 2), 1);
    assert_int_equal(closest_distance("agnle", "angle", 2), 1);
    assert_int_equal(closest_distance("kitten", "sitting", 5), 3);
    assert_int_equal(closest_distance("kitten", "sitting", 2), 3); /* stops at limit + 1 */
    assert_true(closest_near("angel", "angle"));
    assert_false(closest_near("q", "k"));    /* two short names are always close: none */
    assert_false(closest_near("Leaf", "Leaf")); /* the same name is no suggestion */
    assert_false(closest_near("Bud", "Leaf"));
    char buf[64];
    const char *names[] = {"step", "steps", "angle"};
    assert_int_equal(closest_list("stpes", names, 3, buf, sizeof buf), 2);
    assert_string_equal(buf, "'step' or 'steps'");
}

/* ---- warnings ---- */

static void warning_nothing_makes_the_module(void **state) {
    expect_warning("lsystem T {\n  axiom A\n  A -> A\n  B -> C\n}\n", "test.syl:4:3: warning: ",
                   "this rule never applies: neither the axiom nor any rule makes 'B'");
    expect_warning("lsystem T {\n  axiom A(1)\n  A -> B\n  A(x) -> A(x)\n}\n", "test.syl:3:3: warning: ",
                   "'A' is only made with 1 parameter, not 0");
}

static void warning_condition_always_false(void **state) {
    expect_warning("lsystem T {\n  axiom A\n  A : 1 > 2 -> C\n}\n", "test.syl:3:3: warning: ",
                   "its condition is always false");
    expect_warning("lsystem T {\n  const big = 3\n  axiom A(1)\n  A(x) : big < 2 && x > 0 -> C\n}\n",
                   "test.syl:4:3: warning: ", "its condition is always false");
}

static void warning_shadowed_rule(void **state) {
    expect_warning("lsystem T {\n  axiom A\n  A -> B\n  A -> C\n}\n", "test.syl:4:3: warning: ",
                   "this rule never applies: the rule at line 3 always applies first");
    expect_warning("lsystem T {\n  axiom A(1)\n  A(x) -> B\n  A(y) : y > 0 -> C\n}\n", "test.syl:4:3: warning: ",
                   "the rule at line 3 always applies first");
    /* a conditional, a context-sensitive or a weighted rule shadows nothing */
    expect_clean("lsystem T {\n  axiom F A(1)\n  A(x) : x > 0 -> B\n  A(x) -> C\n}\n");
    expect_clean("lsystem T {\n  axiom F BA\n  B < A -> B\n  A -> C\n}\n");
    expect_clean("lsystem T {\n  axiom F A\n  A -> B : 1\n  A -> C : 2\n}\n");
    /* an always-true condition is no condition */
    expect_warning("lsystem T {\n  axiom A\n  A : 2 > 1 -> B\n  A -> C\n}\n", "test.syl:4:3: warning: ",
                   "the rule at line 3 always applies first");
}

static void warning_unused(void **state) {
    const char *text = "const shared = 1\n" /* outside the model: shared, never reported */
                       "lsystem T {\n"
                       "  module Q\n"
                       "  const k = 1\n"
                       "  param p = 2\n"
                       "  fn f(x) = x\n"
                       "  curve c = (0, 0), (1, 1)\n"
                       "  axiom F A\n"
                       "}\n";
    expect_warning(text, "test.syl:3:10: warning: ", "module 'Q' is declared but never used");
    expect_warning(text, "test.syl:4:9: warning: ", "const 'k' is never used");
    expect_warning(text, "test.syl:5:9: warning: ", "param 'p' is never used");
    expect_warning(text, "test.syl:6:6: warning: ", "function 'f' is never used");
    expect_warning(text, "test.syl:7:9: warning: ", "curve 'c' is never used");
    char *diag = NULL;
    SylProgram *p = unit_compile(text, &diag, NULL);
    assert_non_null(p);
    assert_int_equal(unit_occurrences(diag, "warning:"), 5);
    assert_not_contains(diag, "shared");
    free(diag);
    syl_program_free(p);
    /* used ones are not reported */
    expect_clean("lsystem T {\n  module Q\n  const k = 1\n  fn f(x) = x\n  curve c = (0, 0), (1, 1)\n"
                 "  axiom F Q(f(k) + c(0.5))\n}\n");
}

static void warning_zero_weight(void **state) {
    expect_warning("lsystem T {\n  axiom A\n  A -> B : 0\n  A -> C : 1\n}\n", "test.syl:3:3: warning: ",
                   "this rule's weight is zero: it is never chosen");
}

static void warnings_only_with_lint(void **state) {
    const char *text = "lsystem T {\n  const k = 1\n  axiom A\n  B -> C\n}\n";
    char *diag = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&diag, &len);
    int st = -1;
    SylProgram *p = syl_compile("test.syl", text, strlen(text), &(SylCompileOptions){.diag = mem}, &st);
    fclose(mem);
    assert_non_null(p);
    assert_int_equal(st, SYL_OK);
    assert_string_equal(diag, "");
    free(diag);
    syl_program_free(p);
    expect_warning(text, "test.syl:2:9: warning: ", "never used");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(unknown_name),
        cmocka_unit_test(unknown_function),
        cmocka_unit_test(wrong_argument_count),
        cmocka_unit_test(redefinition),
        cmocka_unit_test(module_arity),
        cmocka_unit_test(const_used_before_defined),
        cmocka_unit_test(random_in_const),
        cmocka_unit_test(no_cascading_errors),
        cmocka_unit_test(negative_weight),
        cmocka_unit_test(unbalanced_brackets),
        cmocka_unit_test(unbalanced_axiom),
        cmocka_unit_test(predecessor_is_one_module),
        cmocka_unit_test(close_names),
        cmocka_unit_test(left_context_without_branches),
        cmocka_unit_test(pattern_parameters_are_names),
        cmocka_unit_test(settings_and_axiom),
        cmocka_unit_test(set_parameters),
        cmocka_unit_test(warning_nothing_makes_the_module),
        cmocka_unit_test(warning_condition_always_false),
        cmocka_unit_test(warning_shadowed_rule),
        cmocka_unit_test(warning_unused),
        cmocka_unit_test(warning_zero_weight),
        cmocka_unit_test(warnings_only_with_lint),
        cmocka_unit_test(curve_redefinition), /* last: it crashed, which ends an ASan run */
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
