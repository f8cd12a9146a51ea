/* The schema's keyed reader (lang/schema_keyed.c) is the kinds', not grow's: a made-up table
 * with each shape a row can say (a bare value, modes with an implied one and a key of one
 * mode, a mode word with a count, a vector, a repeated line with symbols) is read into a
 * made-up struct by rows and slots alone, with its errors at their places and --set
 * DIRECTIVE.N.KEY. The expected values are the text's own numbers. */
#include "keyed.h"

#include <stddef.h>
#include <stdint.h>

#include "lang/program.h"
#include "lang/schema.h"

typedef struct Leaf {
    uint8_t kind;
    float len;
} Leaf;

typedef struct Toy {
    float size;
    int pot;
    float width;
    int depth;
    int row, seeds;
    float dir[3];
    Leaf leaves[2];
    int nleaves;
} Toy;

static const SchRow toy_rows[] = {
    {.name = "size", .type = SCH_NUMBER, .lo = 0, .hi = 10, .def = {1}, .unit = "", .doc = "a bare value"},
    {.name = "pot.width", .type = SCH_NUMBER, .lo = 0, .hi = 5, .def = {1}, .unit = "", .doc = "round", .when = "round"},
    {.name = "pot.depth", .type = SCH_INTEGER, .lo = 1, .hi = 9, .def = {2}, .unit = "", .doc = "every pot"},
    {.name = "pot", .type = SCH_ENUM, .def = {NAN}, .def_text = "square", .words = "round|square", .unit = "",
     .doc = "modes", .required = true, .implied = "round"},
    {.name = "row", .type = SCH_ENUM, .def = {NAN}, .def_text = "a", .words = "a|b", .unit = "", .doc = "counted",
     .counted = "b", .count_lo = 1, .count_hi = 4, .count_of = "seeds"},
    {.name = "wind.dir", .type = SCH_VECTOR, .lo = -1e9, .hi = 1e9, .def = {NAN}, .unit = "", .doc = "a vector"},
    {.name = "leaf.len", .type = SCH_NUMBER, .lo = 0, .hi = 2, .def = {0.25}, .unit = "", .doc = "each",
     .group = "leaf line"},
    {.name = "leaf", .type = SCH_ENUM, .def = {NAN}, .def_text = "x", .words = "x|y", .unit = "", .doc = "repeated",
     .group = "leaf line", .required = true, .repeat = 2, .symbols = "x=x|z=y", .symbol_key = "len"},
};
static const SchTable toy = {"toy", "directive", toy_rows, 8, SCH_KEYED, ""};

static const int pot_values[] = {7, 9}; /* stored values that are not the words' indices */
static const SchSlot toy_slots[] = {
    {SCH_AT_F32, offsetof(Toy, size), sizeof(float), NULL},
    {SCH_AT_F32, offsetof(Toy, width), sizeof(float), NULL},
    {SCH_AT_INT, offsetof(Toy, depth), sizeof(int), NULL},
    {SCH_AT_INT, offsetof(Toy, pot), sizeof(int), pot_values},
    {SCH_AT_INT, offsetof(Toy, row), sizeof(int), NULL},
    {SCH_AT_F32X3, offsetof(Toy, dir), sizeof(float[3]), NULL},
    {SCH_AT_F32, offsetof(Leaf, len), sizeof(float), NULL},
    {SCH_AT_U8, offsetof(Leaf, kind), 1, NULL},
};

static void toy_mode(void *base, const SchRow *row, int word, int count) {
    if (!strcmp(row->name, "row") && word == 1) ((Toy *)base)->seeds = count;
}

static const SchKeyed toy_keyed = {
    .t = &toy,
    .slots = toy_slots,
    .nslots = 8,
    .groups = (const SchGroup[]){{"leaf", offsetof(Toy, leaves), sizeof(Leaf), offsetof(Toy, nleaves)}},
    .ngroups = 1,
    .mode_read = toy_mode,
};

/* Read the lines of a block (any kind that keeps its lines: a grow block, without its own
 * check) with the toy table; the errors' text into *diag. */
static int read_toy(const char *lines, const SylOverride *sets, int nsets, Toy *t, char **diag) {
    return keyed_read("toy.syl", &toy_keyed, lines, sets, nsets, t, sizeof *t, diag);
}

static void every_shape_is_read_by_its_row(void **state) {
    (void)state;
    Toy t;
    char *diag = NULL;
    int e = read_toy("  size 3\n  pot width 2.5 depth 4\n  row b 3\n  wind dir (1, 2, 3)\n"
                     "  leaf y len 0.5\n  leaf x ~z(0.75)\n",
                     NULL, 0, &t, &diag);
    if (e) fail_msg("%s", diag);
    free(diag);
    assert_near(t.size, 3, 1e-6);
    assert_int_equal(t.pot, 7); /* implied: round, stored as its value */
    assert_near(t.width, 2.5, 1e-6);
    assert_int_equal(t.depth, 4);
    assert_int_equal(t.row, 1);
    assert_int_equal(t.seeds, 3); /* the count after `b`, through the mode hook */
    for (int k = 0; k < 3; k++) assert_near(t.dir[k], k + 1, 0);
    assert_int_equal(t.nleaves, 2);
    assert_int_equal(t.leaves[0].kind, 1);
    assert_near(t.leaves[0].len, 0.5, 1e-6);
    assert_int_equal(t.leaves[1].kind, 1); /* ~z is y */
    assert_near(t.leaves[1].len, 0.75, 1e-6);
    /* the defaults: rows' own, the enum's default word by its value */
    e = read_toy("", NULL, 0, &t, &diag);
    free(diag);
    assert_int_equal(e, 0);
    assert_near(t.size, 1, 0);
    assert_int_equal(t.pot, 9);
    assert_int_equal(t.depth, 2);
    assert_int_equal(t.nleaves, 0);
}

static void errors_at_their_places(void **state) {
    (void)state;
    static const struct {
        const char *lines, *message;
    } cases[] = {
        {"  pot square width 2\n", "toy.syl:2:14: error: 'width' is not a key of 'pot square' (keys: depth)"},
        {"  pot\n", "toy.syl:2:3: error: 'pot' expects round or square after it"},
        {"  row b 5\n", "toy.syl:2:9: error: 'b' expects a whole number of seeds from 1 to 4 after it"},
        {"  wind dir 3\n", "toy.syl:2:12: error: 'dir' expects a direction (x, y, z)"},
        {"  leaf x\n  leaf x\n  leaf y\n", "toy.syl:4:3: error: at most 2 leaf lines"},
        {"  leaf x ~w(1)\n", "toy.syl:2:10: error: '~w' is not a symbol of a leaf line: use ~x or ~y"},
        {"  pot depth 2.5\n", "toy.syl:2:13: error: depth takes a whole number in [1, 9], not 2.5"},
        {"  sise 2\n", "toy.syl:2:3: error: unknown directive 'sise' in a toy block (did you mean 'size'?)"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        Toy t;
        char *diag = NULL;
        assert_true(read_toy(cases[i].lines, NULL, 0, &t, &diag) > 0);
        assert_contains(diag, cases[i].message);
        free(diag);
    }
}

static void set_reaches_a_repeated_line(void **state) {
    (void)state;
    Toy t;
    char *diag = NULL;
    SylOverride sets[] = {{"leaf.2.len", 1.5}, {"width", 4}, {"size", 7}};
    assert_int_equal(read_toy("  pot round\n  leaf x len 0.1\n  leaf y len 0.2\n", sets, 3, &t, &diag), 0);
    free(diag);
    assert_near(t.leaves[0].len, 0.1, 1e-6);
    assert_near(t.leaves[1].len, 1.5, 1e-6);
    assert_near(t.width, 4, 1e-6);
    assert_near(t.size, 7, 1e-6);
    SylOverride bad[] = {{"leaf.3.len", 1}, {"leaf.1.len", 3}};
    assert_int_equal(read_toy("  leaf x\n  leaf y\n", bad, 2, &t, &diag), 2);
    assert_contains(diag, "--set leaf.3.len: toy block 'G' has 2 leaf lines");
    assert_contains(diag, "--set leaf.1.len: 'len' must be in [0, 2], not 3");
    free(diag);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_shape_is_read_by_its_row),
        cmocka_unit_test(errors_at_their_places),
        cmocka_unit_test(set_reaches_a_repeated_line),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
