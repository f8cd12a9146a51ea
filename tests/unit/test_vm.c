/* Expressions: compiled to bytecode, run by the VM (or folded by the compiler); values are
 * read back as parameters of the derived string. */
#include "unit.h"

enum { MAXV = 32 };

/* Derive text for `steps` steps; returns the parameters of module `mod` in v, and how many. */
static int params_of(const char *text, int steps, size_t mod, double *v) {
    UnitRun r = unit_run(text, (SylDeriveOptions){.steps = steps, .threads = 1});
    if (r.status != SYL_OK) fail_msg("status %d:\n%s", r.status, r.diag);
    if (mod >= syl_string_length(r.s)) fail_msg("no module %zu", mod);
    int np = 0;
    const double *par;
    syl_string_module(r.s, mod, &np, &par);
    assert_true(np <= MAXV);
    memcpy(v, par, sizeof *v * (size_t)np);
    unit_run_free(&r);
    return np;
}

/* Every expression given both ways: folded (`axiom A(expr)` with x replaced by a constant)
 * and run by the VM (`A(x) -> B(expr)` with x a rule parameter). */
static void check_both(const char *x, const char *exprs, const double *want, int n, double eps) {
    char text[2048];
    double v[MAXV];
    snprintf(text, sizeof text, "lsystem T {\n  axiom A(%s)\n  A(x) -> B(%s)\n}\n", x, exprs);
    assert_int_equal(params_of(text, 1, 0, v), n);
    for (int i = 0; i < n; i++) assert_near(v[i], want[i], eps);
    snprintf(text, sizeof text, "lsystem T {\n  const x = %s\n  axiom B(%s)\n}\n", x, exprs);
    assert_int_equal(params_of(text, 0, 0, v), n);
    for (int i = 0; i < n; i++) assert_near(v[i], want[i], eps);
}

/* Derive text (expected to fail at run time) and return its diagnostics. */
static char *runtime_error(const char *text) {
    UnitRun r = unit_run(text, (SylDeriveOptions){.steps = -1, .threads = 1});
    if (!r.p) fail_msg("did not compile:\n%s", r.diag);
    assert_int_equal(r.status, SYL_EMODEL);
    assert_null(r.s);
    char *d = r.diag;
    r.diag = NULL;
    unit_run_free(&r);
    return d;
}

static void arithmetic(void **state) {
    const double want[] = {3, -1, 8, 0.5, 1, 8, -2, 1.5, -1, 1, 1024, 0.25, 5, 2};
    check_both("2", "x+1, x-3, x*4, x/4, 7%x, x^3, -x, 7.5%x, -7%x, 7%-x, x^10, x^-2, 1+x*2, (1+x)*2/3", want, 14, 0);
}

static void comparisons(void **state) {
    const double want[] = {1, 1, 0, 1, 1, 0, 0, 1, 0, 1};
    check_both("2", "x<3, x<=2, x>2, x>=2, x==2, x!=2, x<2, x>1, x==2.5, x!=2.5", want, 10, 0);
}

static void logic(void **state) {
    const double want[] = {1, 0, 1, 1, 0, 1, 0, 1, 0, 1, 1, 0};
    check_both("2", "x && 3, x && 0, 0 || x, x || 0, 0 || 0, !0, !x, !!x, !(x > 1), x > 1 && x < 3, x < 1 || x > 1, "
                    "x > 1 && x > 3",
               want, 12, 0);
}

/* `&&`, `||` and `?:` evaluate only what they need: a division by a zero parameter on the
 * side not taken is never run. */
static void short_circuit(void **state) {
    double v[MAXV];
    const char *text = "lsystem T {\n  axiom A(0)\n"
                       "  A(x) -> B(x > 0 && 1/x > 0, x == 0 || 1/x, x ? 1/x : 5, x != 0 ? 1/x : -1, "
                       "x > 0 && x < 1/x || 7)\n}\n";
    assert_int_equal(params_of(text, 1, 0, v), 5);
    assert_true(v[0] == 0);
    assert_true(v[1] == 1);
    assert_true(v[2] == 5);
    assert_true(v[3] == -1);
    assert_true(v[4] == 1);
    /* the same in a condition */
    assert_derives("lsystem T {\n  axiom A(0) A(4)\n  A(x) : x != 0 && 1/x < 1 -> B\n}\n", 1, "A(0)B");
    /* and the other side is run when it is needed */
    char *d = runtime_error("lsystem T {\n  axiom A(0)\n  A(x) -> B(x == 0 && 1/x > 0)\n}\n");
    assert_contains(d, "test.syl:3:24: error: division by zero (step 1, module ");
    free(d);
}

static void ternary(void **state) {
    const double want[] = {10, 20, 3, 2};
    check_both("2", "x > 1 ? 10 : 20, x > 5 ? 10 : 20, x < 0 ? 1 : x < 1 ? 2 : 3, x ? x : 9", want, 4, 0);
}

static void trigonometry_in_degrees(void **state) {
    const double pi = 3.14159265358979323846;
    const double want[] = {1, 0.5, 1, 90, 90, 30, 45, 45, 135, -90, pi, 180, 0, 1};
    check_both("90", "sin(x), cos(x/1.5), tan(x/2), asin(1), acos(0), asin(0.5), atan(1), atan2(1, 1), atan2(1, -1), "
                     "atan2(-x, 0), rad(2*x), deg(3.14159265358979323846), cos(x), sin(x*5)",
               want, 14, 1e-12);
}

static void builtins(void **state) {
    const double want[] = {2, 3, 4, 0, -1, 1, 2, 2, 1024, 4, 1, 0, 2, 0.001, -1, 1, -1, 3, 3, 2};
    check_both("2", "min(x, 3), max(x, 3), clamp(x*5, 0, 4), clamp(-x, 0, 4), floor(-x/4), ceil(x/4 + 0.1), "
                    "abs(-x), abs(x), pow(x, 10), sqrt(x*8), exp(0), log(1), log(exp(x)), pow(10, -3), "
                    "sign(-x), sign(x), trunc(-1.5), round(2.5), round(x + 0.6), log10(100)",
               want, 20, 1e-12);
}

static void functions(void **state) {
    double v[MAXV];
    const char *text = "lsystem T {\n"
                       "  fn sq(a) = a * a\n"
                       "  fn f(a, b) = sq(a) + b\n"
                       "  fn fact(n) = n <= 1 ? 1 : n * fact(n - 1)\n"
                       "  fn fib(n) = n < 2 ? n : fib(n - 1) + fib(n - 2)\n"
                       "  axiom A(3) C(fact(5), f(2, 0.5))\n"
                       "  A(x) -> B(f(x, 1), fact(x + 2), fact(0), fib(x * 4), sq(sq(x)))\n"
                       "}\n";
    assert_int_equal(params_of(text, 1, 0, v), 5);
    assert_true(v[0] == 10);
    assert_true(v[1] == 120);
    assert_true(v[2] == 1);
    assert_true(v[3] == 144);
    assert_true(v[4] == 81);
    assert_int_equal(params_of(text, 0, 1, v), 2); /* folded at compile time */
    assert_true(v[0] == 120);
    assert_true(v[1] == 4.5);
}

static void curves(void **state) {
    double v[MAXV];
    const char *text = "lsystem T {\n"
                       "  curve c = (0, 0), (1, 10), (3, 30), (4, 0)\n"
                       "  axiom A(-1) A(0.5) A(2) A(3.5) A(9) A(1) A(4) C(c(0.25), c(-5), c(5), c(2.5))\n"
                       "  A(x) -> B(c(x))\n"
                       "}\n";
    static const double at[] = {0, 5, 20, 15, 0, 10, 0}; /* clamped below, inside, clamped above, knots */
    UnitRun r = unit_run(text, (SylDeriveOptions){.steps = 1, .threads = 1});
    assert_int_equal(r.status, SYL_OK);
    for (size_t i = 0; i < 7; i++) assert_near(unit_param(&r, i, 0), at[i], 1e-12);
    assert_near(unit_param(&r, 7, 0), 2.5, 1e-12);
    assert_near(unit_param(&r, 7, 1), 0, 0);
    assert_near(unit_param(&r, 7, 2), 0, 0);
    assert_near(unit_param(&r, 7, 3), 25, 1e-12);
    unit_run_free(&r);
    /* a curve of one point is constant */
    assert_int_equal(params_of("lsystem T {\n  curve k = (1, 7)\n  axiom A(0)\n  A(x) -> B(k(x), k(x + 5))\n}\n", 1, 0,
                               v), 2);
    assert_true(v[0] == 7 && v[1] == 7);
}

static void params_and_consts(void **state) {
    double v[MAXV];
    const char *text = "const top = 100\n"
                       "lsystem T {\n"
                       "  param lat = 45\n"
                       "  const r1 = 0.9, wr = r1 * 2\n"
                       "  const tl = top + lat\n"
                       "  axiom A(1, 10)\n"
                       "  A(l, w) -> B(l * r1, w * wr, lat, tl, l + w)\n"
                       "}\n";
    assert_int_equal(params_of(text, 1, 0, v), 5);
    assert_near(v[0], 0.9, 1e-15);
    assert_near(v[1], 18, 1e-12);
    assert_true(v[2] == 45);
    assert_true(v[3] == 145);
    assert_true(v[4] == 11);
}

/* Slots take shortcuts for x + k, x - k, x * k and x / k: the same values as the VM. */
static void slot_shortcuts(void **state) {
    const double want[] = {5.5, -1.5, 7, 0.8, 2, 2};
    check_both("2", "x + 3.5, x - 3.5, x * 3.5, x / 2.5, x, 2", want, 6, 1e-15);
}

/* ---- runtime errors ---- */

static void division_by_zero_names_the_step(void **state) {
    char *d = runtime_error("lsystem T {\n  derive 3\n  axiom A(2)\n  A(x) -> A(x - 1) B(1 / (x - 1))\n}\n");
    assert_contains(d, "test.syl:4:24: error: division by zero (step 2, module ");
    free(d);
    d = runtime_error("lsystem T {\n  derive 2\n  axiom B A(0)\n  A(x) -> B(7 % x)\n}\n");
    assert_contains(d, "test.syl:4:15: error: division by zero (step 1, module ");
    free(d);
    /* in a condition, and inside a function: the location is where it happened */
    d = runtime_error("lsystem T {\n  axiom A(0)\n  A(x) : 1/x > 0 -> B\n}\n");
    assert_contains(d, "test.syl:3:11: error: division by zero (step 1, module ");
    free(d);
    d = runtime_error("lsystem T {\n  fn inv(a) = 1 / a\n  axiom A(0)\n  A(x) -> B(inv(x))\n}\n");
    assert_contains(d, "test.syl:2:17: error: division by zero (step 1, module ");
    free(d);
}

static void domain_errors(void **state) {
    char *d = runtime_error("lsystem T {\n  derive 3\n  axiom A(2)\n  A(x) -> A(x - 1) B(sqrt(x - 3))\n}\n");
    assert_contains(d, "test.syl:4:22: error: argument out of the function's domain (step 1, module ");
    free(d);
    d = runtime_error("lsystem T {\n  axiom A(0)\n  A(x) -> B(log(x))\n}\n");
    assert_contains(d, "argument out of the function's domain (step 1");
    free(d);
    d = runtime_error("lsystem T {\n  axiom A(-4)\n  A(x) -> B(x ^ 0.5)\n}\n");
    assert_contains(d, "test.syl:3:15: error: argument out of the function's domain");
    free(d);
    d = runtime_error("lsystem T {\n  axiom A(2)\n  A(x) -> B(asin(x))\n}\n");
    assert_contains(d, "domain (step 1, module ");
    free(d);
}

static void non_finite_results(void **state) {
    char *d = runtime_error("lsystem T {\n  derive 3\n  axiom A(2)\n  A(x) -> A(x * 500) B(exp(x))\n}\n");
    assert_contains(d, "test.syl:4:24: error: the result is not a finite number (step 2, module ");
    free(d);
    /* the x * k shortcut checks too */
    d = runtime_error("lsystem T {\n  axiom A(1e200)\n  A(x) -> A(x * 1e200)\n}\n");
    assert_contains(d, "test.syl:3:");
    assert_contains(d, "error: the result is not a finite number (step 1, module ");
    free(d);
    d = runtime_error("lsystem T {\n  axiom A(1e300)\n  A(x) -> A(x * x)\n}\n");
    assert_contains(d, "not a finite number (step 1, module ");
    free(d);
}

static void negative_weight_at_run_time(void **state) {
    char *d = runtime_error("lsystem T {\n  axiom A(-1)\n  A(x) -> B : x\n  A(x) -> C : 1\n}\n");
    assert_contains(d, "test.syl:3:15: error: a rule's weight is negative (step 1, module ");
    free(d);
}

static void runaway_recursion(void **state) {
    char *d = runtime_error("lsystem T {\n  fn f(n) = n + f(n - 1)\n  axiom A(3)\n  A(x) -> B(f(x))\n}\n");
    assert_contains(d, "functions call each other too deeply (step 1, module ");
    free(d);
}

/* The same errors in constants are reported by the compiler, with the line. */
static void compile_time_errors(void **state) {
    static const struct { const char *expr, *where, *what; } cases[] = {
        {"1/0", "test.syl:2:12: error: ", "division by zero"},
        {"5 % 0", "test.syl:2:13: error: ", "division by zero"},
        {"sqrt(-1)", "test.syl:2:11: error: ", "sqrt: argument out of the function's domain"},
        {"exp(1000)", "test.syl:2:11: error: ", "exp: the result is not a finite number"},
        {"1e300 * 1e300", "test.syl:2:17: error: ", "not a finite number"},
        {"(-8)^(1/3)", "test.syl:2:15: error: ", "out of the function's domain"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char text[256], *diag = NULL;
        int st = -1;
        snprintf(text, sizeof text, "lsystem T {\n  axiom A(%s)\n}\n", cases[i].expr);
        assert_null(unit_compile(text, &diag, &st));
        assert_int_equal(st, SYL_EMODEL);
        assert_contains(diag, cases[i].where);
        assert_contains(diag, cases[i].what);
        free(diag);
    }
    /* a division by a literal zero is refused even where it depends on a parameter */
    char *diag = NULL;
    assert_null(unit_compile("lsystem T {\n  axiom A(1)\n  A(x) -> B(x / 0)\n}\n", &diag, NULL));
    assert_contains(diag, "test.syl:3:15: error: division by zero");
    free(diag);
}

static void dump_shows_bytecode(void **state) {
    SylProgram *p = unit_compile("lsystem T {\n  axiom A(1)\n  A(x) -> A(x*2) B(sin(x) + x)\n}\n", NULL, NULL);
    assert_non_null(p);
    char *out = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&out, &len);
    syl_program_dump(p, mem);
    fclose(mem);
    assert_contains(out, "lsystem T\n");
    assert_contains(out, "rule 1, line 3: A/1(x)\n");
    assert_contains(out, "successor (2 modules): A/1 B/1\n");
    assert_contains(out, "LOCAL  x\n");
    assert_contains(out, "MULK   2\n");
    assert_contains(out, "CALLB  sin/1\n");
    assert_contains(out, "ADD");
    assert_contains(out, "RET");
    /* the axiom's constant needs no code */
    assert_contains(out, "parameter 1: constant 1\n");
    free(out);
    syl_program_free(p);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(arithmetic),
        cmocka_unit_test(comparisons),
        cmocka_unit_test(logic),
        cmocka_unit_test(short_circuit),
        cmocka_unit_test(ternary),
        cmocka_unit_test(trigonometry_in_degrees),
        cmocka_unit_test(builtins),
        cmocka_unit_test(functions),
        cmocka_unit_test(curves),
        cmocka_unit_test(params_and_consts),
        cmocka_unit_test(slot_shortcuts),
        cmocka_unit_test(division_by_zero_names_the_step),
        cmocka_unit_test(domain_errors),
        cmocka_unit_test(non_finite_results),
        cmocka_unit_test(negative_weight_at_run_time),
        cmocka_unit_test(runaway_recursion),
        cmocka_unit_test(compile_time_errors),
        cmocka_unit_test(dump_shows_bytecode),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
