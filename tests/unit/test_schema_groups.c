/* A keyed table may have several repeated lines: a made-up table with two (`pot` and
 * `stake`, each line its own element of its own array, counted apart) is read by the schema's
 * one keyed reader (lang/schema_keyed.c) into a made-up struct, --set reaches each as
 * DIRECTIVE.N.KEY, their limits are their own, and describe's reading (sch_see_keyed, which
 * stores nothing) is told every element and value the same reader takes. The expected values
 * are the text's own numbers. */
#include "keyed.h"

#include <stddef.h>
#include <stdint.h>

#include "lang/program.h"
#include "lang/schema.h"

typedef struct Pot {
    uint8_t shape;
    float width;
} Pot;
typedef struct Stake {
    uint8_t wood;
    float height;
    int ties;
} Stake;
typedef struct Garden {
    float size;
    Pot pots[3];
    int npots;
    Stake stakes[2];
    int nstakes;
} Garden;

static const SchRow rows[] = {
    {.name = "size", .type = SCH_NUMBER, .lo = 0, .hi = 10, .def = {1}, .unit = "", .doc = "a bare value"},
    {.name = "pot.width", .type = SCH_NUMBER, .lo = 0, .hi = 5, .def = {0.5}, .unit = "", .doc = "each pot",
     .group = "pot line"},
    {.name = "pot", .type = SCH_ENUM, .def = {NAN}, .def_text = "round", .words = "round|square", .unit = "",
     .doc = "a pot", .group = "pot line", .repeat = 3},
    {.name = "stake.height", .type = SCH_NUMBER, .lo = 0, .hi = 3, .def = {1}, .unit = "", .doc = "each stake",
     .group = "stake line"},
    {.name = "stake.ties", .type = SCH_INTEGER, .lo = 0, .hi = 9, .def = {2}, .unit = "", .doc = "each stake",
     .group = "stake line"},
    {.name = "stake", .type = SCH_ENUM, .def = {NAN}, .def_text = "pine", .words = "pine|oak", .unit = "",
     .doc = "a stake", .group = "stake line", .required = true, .repeat = 2, .symbols = "p=pine|o=oak",
     .symbol_key = "height"},
};
static const SchTable garden = {"garden", "directive", rows, 6, SCH_KEYED, ""};

static const SchSlot slots[] = {
    {SCH_AT_F32, offsetof(Garden, size), sizeof(float), NULL},
    {SCH_AT_F32, offsetof(Pot, width), sizeof(float), NULL},
    {SCH_AT_U8, offsetof(Pot, shape), 1, NULL},
    {SCH_AT_F32, offsetof(Stake, height), sizeof(float), NULL},
    {SCH_AT_INT, offsetof(Stake, ties), sizeof(int), NULL},
    {SCH_AT_U8, offsetof(Stake, wood), 1, NULL},
};

static const SchGroup groups[] = {
    {"stake", offsetof(Garden, stakes), sizeof(Stake), offsetof(Garden, nstakes)},
    {"pot", offsetof(Garden, pots), sizeof(Pot), offsetof(Garden, npots)},
};
static const SchKeyed keyed = {.t = &garden, .slots = slots, .nslots = 6, .groups = groups, .ngroups = 2};

static SylProgram *compile(const char *lines, const SylOverride *sets, int nsets) {
    return keyed_compile("garden.syl", lines, sets, nsets);
}

static int read_garden(const char *lines, const SylOverride *sets, int nsets, Garden *g, char **diag) {
    return keyed_read("garden.syl", &keyed, lines, sets, nsets, g, sizeof *g, diag);
}

static const char *lines = "  pot square width 2\n  stake oak height 2.5 ties 4\n  pot\n  size 3\n"
                           "  stake pine ~o(0.75)\n  pot round width 1.5\n";

static void two_repeated_lines_each_its_own_array(void **state) {
    (void)state;
    Garden g;
    char *diag = NULL;
    int e = read_garden(lines, NULL, 0, &g, &diag);
    if (e) fail_msg("%s", diag);
    free(diag);
    assert_near(g.size, 3, 1e-6);
    assert_int_equal(g.npots, 3);
    assert_int_equal(g.pots[0].shape, 1);
    assert_near(g.pots[0].width, 2, 1e-6);
    assert_int_equal(g.pots[1].shape, 0);
    assert_near(g.pots[1].width, 0.5, 1e-6); /* the row's default, in an element of its own */
    assert_int_equal(g.pots[2].shape, 0);
    assert_near(g.pots[2].width, 1.5, 1e-6);
    assert_int_equal(g.nstakes, 2);
    assert_int_equal(g.stakes[0].wood, 1);
    assert_near(g.stakes[0].height, 2.5, 1e-6);
    assert_int_equal(g.stakes[0].ties, 4);
    assert_int_equal(g.stakes[1].wood, 1); /* ~o is oak */
    assert_near(g.stakes[1].height, 0.75, 1e-6);
    assert_int_equal(g.stakes[1].ties, 2);
}

static void each_line_its_own_limit_and_set(void **state) {
    (void)state;
    Garden g;
    char *diag = NULL;
    SylOverride sets[] = {{"stake.2.ties", 7}, {"pot.3.width", 4}};
    assert_int_equal(read_garden(lines, sets, 2, &g, &diag), 0);
    free(diag);
    assert_int_equal(g.stakes[1].ties, 7);
    assert_near(g.pots[2].width, 4, 1e-6);
    assert_int_equal(g.stakes[0].ties, 4);
    /* three stakes are one too many, three pots are not; a fourth pot is */
    assert_int_equal(read_garden("  stake oak\n  pot\n  stake pine\n  pot\n  stake oak\n  pot\n", NULL, 0, &g, &diag), 1);
    assert_contains(diag, "garden.syl:6:3: error: at most 2 stake lines");
    free(diag);
    assert_int_equal(g.npots, 3);
    assert_int_equal(g.nstakes, 2);
    SylOverride bad[] = {{"pot.2.ties", 1}, {"stake.3.height", 1}};
    assert_int_equal(read_garden("  pot\n  pot\n  stake oak\n", bad, 2, &g, &diag), 2);
    assert_contains(diag, "--set pot.2.ties: a pot line has no number 'ties' (width)");
    assert_contains(diag, "--set stake.3.height: garden block 'G' has 1 stake line");
    free(diag);
}

/* describe's reading: what the reader took, element by element, with nothing stored. */
typedef struct Told {
    char text[1024];
    size_t used;
} Told;

static void told_element(void *ctx, const SchRow *head, int elem) {
    Told *t = ctx;
    t->used += (size_t)snprintf(t->text + t->used, sizeof t->text - t->used, "[%s %d]", head->name, elem);
}

static void told_value(void *ctx, const SchRow *row, int elem, const double *x, int n, const char *word) {
    Told *t = ctx;
    t->used += (size_t)snprintf(t->text + t->used, sizeof t->text - t->used, " %s@%d=", row->name, elem);
    if (word) t->used += (size_t)snprintf(t->text + t->used, sizeof t->text - t->used, "%s", word);
    for (int i = 0; i < n; i++)
        t->used += (size_t)snprintf(t->text + t->used, sizeof t->text - t->used, "%s%g", i ? "," : "", x[i]);
}

static void describe_is_told_by_the_same_reader(void **state) {
    (void)state;
    SylOverride sets[] = {{"stake.2.ties", 7}, {"size", 4}};
    SylProgram *p = compile(lines, sets, 2);
    Told t = {0};
    assert_int_equal(sch_see_keyed(p, &garden, &(SchSeen){.element = told_element, .value = told_value, .ctx = &t}), 0);
    syl_program_free(p);
    assert_string_equal(t.text, "[pot 0] pot@0=square pot.width@0=2[stake 0] stake@0=oak stake.height@0=2.5"
                                " stake.ties@0=4[pot 1] size@-1=3[stake 1] stake@1=pine"
                                " stake@1=oak stake.height@1=0.75[pot 2] pot@2=round pot.width@2=1.5 stake.ties@1=7 size@-1=4");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(two_repeated_lines_each_its_own_array),
        cmocka_unit_test(each_line_its_own_limit_and_set),
        cmocka_unit_test(describe_is_told_by_the_same_reader),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
