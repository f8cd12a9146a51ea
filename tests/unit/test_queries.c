/* The query seam (SylQueryOps): the engine hands the string the turtle reads to the caller's
 * environment after the axiom and every step and copies the answers back; without one,
 * syl_derive fills queries with the stand-alone environment, the same as holding it. */
#include "unit.h"

typedef struct Calls {
    int n, last_step;
    size_t length; /* of the string fill saw */
} Calls;

/* Writes 7 into every parameter of every module named ?E, counting the calls. */
static int sevens(void *user, const SylProgram *p, SylString *s, int step) {
    Calls *c = user;
    c->n++;
    c->last_step = step;
    c->length = syl_string_length(s);
    int e = syl_program_symbol_find(p, "?E");
    for (size_t i = 0; i < syl_string_length(s); i++) {
        int na;
        const double *a;
        if (syl_string_module(s, i, &na, &a) == e)
            for (int k = 0; k < na; k++) ((double *)a)[k] = 7;
    }
    return SYL_OK;
}

static char *text_of(const SylProgram *p, const SylString *s) {
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    syl_string_write(p, s, f);
    fclose(f);
    return buf;
}

/* The interpret rule turns X into two F: the environment sees the interpreted string, the
 * derived one keeps X and gets the answers. */
static void caller_environment_fills(void **state) {
    (void)state;
    const char *text = "lsystem Q {\n  derive 2\n  axiom X ?E(0, 0)\n  X -> X F\n"
                       "  interpret {\n    X -> F F\n  }\n}\n";
    int st;
    SylProgram *p = unit_compile(text, NULL, &st);
    assert_non_null(p);
    static const SylQueryOps ops = {.fill = sevens};
    Calls c = {0};
    SylDeriveOptions d = {.steps = -1, .threads = 1, .queries = &ops, .queries_user = &c};
    SylString *s = NULL;
    assert_int_equal(syl_derive(p, &d, &s), SYL_OK);
    assert_int_equal(c.n, 3); /* the axiom and two steps */
    assert_int_equal(c.last_step, 2);
    assert_int_equal(c.length, 5); /* F F F F ?E */
    char *out = text_of(p, s);
    assert_string_equal(out, "XFF?E(7,7)");
    free(out);
    syl_string_free(s);
    syl_program_free(p);
}

/* No environment given: the stand-alone one, as when the caller holds it. */
static void standalone_by_default(void **state) {
    (void)state;
    const char *text = "lsystem C {\n  derive 3\n  axiom A\n  A -> F [ +(30) F ?E(0, 0) A ] ?E(1, 0) ?P(0, 0, 0) A\n}\n";
    int st;
    SylProgram *p = unit_compile(text, NULL, &st);
    assert_non_null(p);
    SylString *a = NULL, *b = NULL;
    assert_int_equal(syl_derive(p, NULL, &a), SYL_OK);
    SylEnvStandalone *alone = syl_env_standalone_new(p, NULL);
    assert_non_null(alone);
    SylDeriveOptions d = {.steps = -1, .queries = syl_env_standalone_ops(), .queries_user = alone};
    assert_int_equal(syl_derive(p, &d, &b), SYL_OK);
    syl_env_standalone_free(alone);
    char *x = text_of(p, a), *y = text_of(p, b);
    assert_string_equal(x, y);
    assert_null(strstr(x, "?P(0,0,0)A")); /* the positions were filled */
    free(x);
    free(y);
    syl_string_free(a);
    syl_string_free(b);
    syl_program_free(p);
}

/* An environment of one's own, on the public API only: the turtle collects the ?E probes,
 * and each is answered with its height; the segment ends are counted too. */
static int heights(void *user, const SylProgram *p, SylString *s, int step) {
    (void)step;
    SylEnvFill f = {0};
    int st = syl_turtle_query(p, s, &f);
    double *par = syl_string_params(s, NULL);
    for (size_t i = 0; !st && i < f.nprobes; i++) par[f.probes[i].par + 1] = f.probes[i].pos[1];
    *(size_t *)user = f.nends;
    syl_env_fill_free(&f);
    return st;
}

static void own_environment_reads_probes(void **state) {
    (void)state;
    /* up 2, a probe; turn right (+ turns left about U: -90 to the right of up is +X), 1 more, a probe */
    const char *text = "lsystem H {\n  derive 0\n  angle 90\n  axiom F(2) ?E(2, 0) - F(1) ?E(2, 0) ?P(0, 0, 0)\n}\n";
    int st;
    SylProgram *p = unit_compile(text, NULL, &st);
    assert_non_null(p);
    static const SylQueryOps ops = {.fill = heights};
    size_t ends = 0;
    SylDeriveOptions d = {.steps = -1, .threads = 1, .queries = &ops, .queries_user = &ends};
    SylString *s = NULL;
    assert_int_equal(syl_derive(p, &d, &s), SYL_OK);
    char *out = text_of(p, s);
    assert_string_equal(out, "F(2)?E(2,2)-F(1)?E(2,2)?P(1,2,0)");
    assert_int_equal(ends, 2);
    free(out);
    syl_string_free(s);
    syl_program_free(p);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(caller_environment_fills),
        cmocka_unit_test(standalone_by_default),
        cmocka_unit_test(own_environment_reads_probes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
