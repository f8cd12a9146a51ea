/* The schema's reader of NAME VALUE lines (lang/schema_lines.c) is the kinds', not one
 * kind's: a made-up table with each type a row can have (a number, a whole number, a number
 * per level, an enum stored as other values, a file, a switch, a row its kind reads itself) is
 * read into a made-up struct by rows and slots alone: `(expr)` values, levels (`2rings 3`,
 * `rings 0.5 1.5`), errors at their line and column, --set with its level, a kind's own words
 * (say), lenience (warnings, the default kept), describe's reading, which stores nothing, and
 * groups (an ecosystem's species: a made-up garden's beds), --set over them and their errors.
 * The expected values are the text's own numbers; the expected places are where the text
 * puts each value. The messages without a kind's words are the reader's own (a snapshot of
 * its wording, marked as such below). */
#include "keyed.h"

#include <stddef.h>
#include <stdint.h>

#include "lang/program.h"
#include "lang/schema.h"

typedef struct Pot {
    double size, rings[4];
    int count, glaze, clay;
    bool hot, hot_given;
    const SylDirective *label;
    char label_text[32]; /* the label's name, kept past the program's life by read_pot */
} Pot;

static const SchRow pot_rows[] = {
    {.name = "size", .type = SCH_NUMBER, .lo = 0, .hi = 10, .def = {1}, .unit = "", .doc = "a number"},
    {.name = "count", .type = SCH_INTEGER, .lo = 1, .hi = 9, .def = {2}, .unit = "", .doc = "a whole number"},
    {.name = "rings", .type = SCH_NUMBER, .lo = 0, .hi = 5, .levels = 4, .def = {1, 2, 3, 4}, .unit = "",
     .doc = "per level"},
    {.name = "glaze", .type = SCH_ENUM, .def = {NAN}, .def_text = "matte", .words = "matte|glossy", .unit = "",
     .doc = "an enum"},
    {.name = "label", .type = SCH_FILE, .def = {NAN}, .unit = "", .doc = "a file"},
    {.name = "hot", .type = SCH_BOOLEAN, .lo = 0, .hi = 1, .def = {0}, .unit = "", .doc = "a switch"},
    {.name = "clay", .type = SCH_CURVE, .def = {NAN}, .unit = "", .doc = "the kind's own", .aliases = "earth"},
};
static const SchTable pot = {"pot", "parameter", pot_rows, 7, SCH_LINES, ""};

static const int glaze_values[] = {7, 9};
static const SchSlot pot_slots[] = {
    {.store = SCH_AT_F64, .off = offsetof(Pot, size)},
    {.store = SCH_AT_INT, .off = offsetof(Pot, count)},
    {.store = SCH_AT_F64, .off = offsetof(Pot, rings)},
    {.store = SCH_AT_INT, .off = offsetof(Pot, glaze), .values = glaze_values},
    {.store = SCH_AT_LINE, .off = offsetof(Pot, label)},
    {.store = SCH_AT_BOOL, .off = offsetof(Pot, hot)},
    {.store = SCH_AT_KIND},
};

/* clay: its number of values, as the kind's own reading */
static int clay_line(SchLineRead *r, const SchRow *row, const SylDirective *d, void *base) {
    (void)row;
    if (d->nargs == 0) sch_lines_error(r, d, NULL, "clay wants something");
    ((Pot *)base)->clay = d->nargs;
    return 0;
}
static int clay_set(SchLineRead *r, const SchRow *row, const char *typed, double v, void *base) {
    (void)r, (void)row, (void)typed, (void)v, (void)base;
    return 0;
}
static void pot_took(void *base, const SchRow *row) {
    if (!strcmp(row->name, "hot")) ((Pot *)base)->hot_given = true;
}

static SchLines pot_lines = {
    .t = &pot,
    .slots = pot_slots,
    .nslots = 7,
    .line = clay_line,
    .set = clay_set,
    .took = pot_took,
};

/* The lines read by pot_lines (with --set sets), into *out; the errors' text into *diag. */
static int read_pot(const char *lines, const SylOverride *sets, int nsets, Pot *out, char **diag, int *set_errors) {
    SylProgram *p = keyed_compile("pot.syl", lines, sets, nsets);
    size_t len = 0;
    FILE *f = open_memstream(diag, &len);
    memset(out, 0, sizeof *out);
    sch_lines_defaults(&pot_lines, out);
    int dummy, e = sch_read_lines(p, &pot_lines, out, f, set_errors ? set_errors : &dummy);
    if (out->label) snprintf(out->label_text, sizeof out->label_text, "%s", out->label->args[0].text);
    out->label = NULL; /* it points into p */
    fclose(f);
    syl_program_free(p);
    return e;
}

static void every_type_is_read_by_its_row(void **state) {
    (void)state;
    Pot t;
    char *diag = NULL;
    int e = read_pot("  size (1 + 2)\n  count 4\n  rings 0.5 1.5 3.5\n  glaze glossy\n"
                     "  label \"a.png\"\n  hot true\n  earth 1 2 3\n",
                     NULL, 0, &t, &diag, NULL);
    if (e) fail_msg("%s", diag);
    free(diag);
    assert_near(t.size, 3, 0);
    assert_int_equal(t.count, 4);
    assert_near(t.rings[0], 0.5, 0);
    assert_near(t.rings[1], 1.5, 0);
    assert_near(t.rings[2], 3.5, 0);
    assert_near(t.rings[3], 4, 0); /* the default of level 3 */
    assert_int_equal(t.glaze, 9);  /* glossy, stored as its value */
    assert_string_equal(t.label_text, "a.png"); /* the line that named it */
    assert_true(t.hot && t.hot_given);
    assert_int_equal(t.clay, 3); /* by its alias, read by the kind */
    e = read_pot("  2rings 0.75\n", NULL, 0, &t, &diag, NULL); /* one level */
    free(diag);
    assert_int_equal(e, 0);
    assert_near(t.rings[1], 2, 0);
    assert_near(t.rings[2], 0.75, 0);
    /* the defaults: the rows' own, the enum's default word by its value; a default is not given */
    e = read_pot("", NULL, 0, &t, &diag, NULL);
    free(diag);
    assert_int_equal(e, 0);
    assert_near(t.size, 1, 0);
    assert_int_equal(t.count, 2);
    assert_near(t.rings[1], 2, 0);
    assert_int_equal(t.glaze, 7);
    assert_false(t.hot_given);
}

/* Each problem at its line and column (the place of the value the text gives). The words
 * after "error:" are the reader's own, a snapshot of its wording. */
static void errors_at_their_places(void **state) {
    (void)state;
    static const struct {
        const char *lines, *message;
    } cases[] = {
        {"  sise 3\n", "pot.syl:2:3: error: no parameter 'sise' (did you mean 'size'?)"},
        {"  size 3\n  size 4\n", "pot.syl:3:3: error: 'size' is given twice (first on line 2)"},
        {"  size 12\n", "pot.syl:2:8: error: size must be in [0, 10], not 12"},
        {"  count 2.5\n", "pot.syl:2:9: error: count takes a whole number in [1, 9], not 2.5"},
        {"  size 1 2\n", "pot.syl:2:10: error: size takes one value"},
        {"  size\n", "pot.syl:2:3: error: size takes one value"},
        {"  rings 1 2 3 4 5\n", "pot.syl:2:17: error: rings takes 1 to 4 values, for levels 0 to 3"},
        {"  rings 1 9\n", "pot.syl:2:11: error: 1rings must be in [0, 5], not 9"},
        {"  5rings 1\n", "pot.syl:2:3: error: levels above 3 reuse level 3's parameters: write 3rings"},
        {"  2rings x\n", "pot.syl:2:10: error: 2rings takes a number"},
        {"  glaze glosy\n", "pot.syl:2:9: error: glaze is one of matte|glossy (did you mean 'glossy'?)"},
        {"  label png\n", "pot.syl:2:9: error: label takes a file name in quotes"},
        {"  hot 2\n", "pot.syl:2:7: error: hot takes true or false (or 1 or 0), not 2"},
        {"  clay\n", "pot.syl:2:3: error: clay wants something"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        Pot t;
        char *diag = NULL;
        int e = read_pot(cases[i].lines, NULL, 0, &t, &diag, NULL);
        if (e != 1 || strncmp(diag, cases[i].message, strlen(cases[i].message)))
            fail_msg("case %zu: %d errors:\n%s\nwanted: %s", i, e, diag, cases[i].message);
        assert_non_null(strstr(diag, "^")); /* the caret under the place */
        free(diag);
    }
}

static void set_reaches_rows_and_levels(void **state) {
    (void)state;
    Pot t;
    char *diag = NULL;
    int set_errors;
    SylOverride good[] = {{"size", 4}, {"2rings", 0.25}, {"hot", 1}, {"size", 5}};
    int e = read_pot("  size 3\n", good, 4, &t, &diag, &set_errors);
    if (e) fail_msg("%s", diag);
    free(diag);
    assert_near(t.size, 5, 0); /* the last one wins */
    assert_near(t.rings[2], 0.25, 0);
    assert_true(t.hot_given);
    SylOverride bad[] = {{"rings", 1}, {"7rings", 1}, {"glaze", 1}, {"sise", 1}, {"count", 1.5}};
    e = read_pot("", bad, 5, &t, &diag, &set_errors);
    assert_int_equal(e, 5);
    assert_int_equal(set_errors, 5);
    assert_non_null(strstr(diag, "--set rings: 'rings' is per level: write 0rings to 3rings"));
    assert_non_null(strstr(diag, "--set 7rings: levels above 3"));
    assert_non_null(strstr(diag, "--set glaze: 'glaze' is not a number"));
    assert_non_null(strstr(diag, "--set sise: pot block 'G' has no parameter 'sise' (did you mean 'size'?)"));
    assert_non_null(strstr(diag, "--set count: 'count' takes a whole number in [1, 9], not 1.5"));
    free(diag);
}

/* A kind words its own messages; a lenient reading warns and keeps the default. */
static void say(SchProblem *pr, char *buf, size_t size) {
    if (pr->what == SCH_BAD_UNKNOWN) snprintf(buf, size, "a pot has no '%s'", pr->name);
    if (pr->what == SCH_BAD_RANGE) snprintf(buf, size, "%s is %g%s", pr->shown, pr->x, pr->lenient ? ", kept" : "");
}
static bool always(const SylProgram *p) { return (void)p, true; }

static void a_kind_words_and_lenience(void **state) {
    (void)state;
    Pot t;
    char *diag = NULL;
    pot_lines.say = say;
    int e = read_pot("  bowl 1\n", NULL, 0, &t, &diag, NULL);
    assert_int_equal(e, 1);
    assert_non_null(strstr(diag, "pot.syl:2:3: error: a pot has no 'bowl'"));
    free(diag);
    pot_lines.lenient = always;
    e = read_pot("  size 12\n  bowl 1\n", NULL, 0, &t, &diag, NULL);
    pot_lines.say = NULL, pot_lines.lenient = NULL;
    assert_int_equal(e, 1); /* an unknown name stays an error */
    assert_non_null(strstr(diag, "pot.syl:2:8: warning: size is 12, kept"));
    assert_near(t.size, 1, 0);
    free(diag);
}

/* describe's reading: told each line (its row and level) and each --set value; nothing stored. */
typedef struct Told {
    char text[512];
} Told;

static void told_line(void *ctx, const SchRow *row, int level, const SylDirective *d) {
    Told *t = ctx;
    size_t n = strlen(t->text);
    snprintf(t->text + n, sizeof t->text - n, " %s@%d:%d", row->name, level, d->line);
}
static void told_value(void *ctx, const SchRow *row, int level, const double *x, int n, const char *word) {
    (void)n, (void)word;
    Told *t = ctx;
    size_t k = strlen(t->text);
    snprintf(t->text + k, sizeof t->text - k, " set %s@%d=%g", row->name, level, x[0]);
}

static void describe_is_told_by_the_same_reader(void **state) {
    (void)state;
    SylOverride sets[] = {{"1rings", 0.5}, {"size", 4}};
    SylProgram *p = keyed_compile("pot.syl", "  size 3\n  2rings 1\n  earth 1\n", sets, 2);
    Told t = {0};
    assert_int_equal(sch_see_lines(p, &pot, &(SchSeen){.value = told_value, .ctx = &t, .line = told_line}), 0);
    syl_program_free(p);
    assert_string_equal(t.text, " size@-1:2 rings@2:3 clay@-1:4 set rings@1=0.5 set size@-1=4");
}

/* Groups (an ecosystem's species): a head line opens an element, the group's rows that follow
 * are stored in it; --set NAME of a group's row sets every element, ELEM.NAME the one named.
 * A made-up garden: `area` is the block's, `bed NAME` opens a bed, `depth` and `width` are a
 * bed's. The expected values are the text's own numbers. */
typedef struct Bed {
    char name[16];
    double depth, width;
} Bed;
typedef struct Garden {
    double area;
    Bed beds[4];
    int nbeds;
} Garden;

static const SchRow garden_rows[] = {
    {.name = "area", .type = SCH_NUMBER, .lo = 0, .hi = 100, .def = {1}, .unit = "", .doc = "the block's"},
    {.name = "bed", .type = SCH_STRING, .def = {NAN}, .unit = "", .doc = "opens a bed"},
    {.name = "depth", .type = SCH_NUMBER, .lo = 0, .hi = 10, .def = {1}, .unit = "", .doc = "a bed's", .group = "bed"},
    {.name = "width", .type = SCH_NUMBER, .lo = 0, .hi = 10, .def = {1}, .unit = "", .doc = "a bed's", .group = "bed"},
};
static const SchTable garden = {"garden", "directive", garden_rows, 4, SCH_GROUPS, ""};
static const SchSlot garden_slots[] = {
    {.store = SCH_AT_F64, .off = offsetof(Garden, area)},
    {.store = SCH_AT_NONE},
    {.store = SCH_AT_F64, .off = offsetof(Bed, depth)}, /* a group's row: in its element */
    {.store = SCH_AT_F64, .off = offsetof(Bed, width)},
};

static void *open_bed(SchLineRead *r, const SylDirective *d, void *base) {
    Garden *g = base;
    if (d->nargs != 1 || g->nbeds == 4) {
        sch_lines_error(r, d, NULL, "bed takes one name");
        return NULL;
    }
    Bed *b = &g->beds[g->nbeds++];
    snprintf(b->name, sizeof b->name, "%s", d->args[0].text);
    b->depth = b->width = 1;
    return b;
}

static const SchLines garden_lines = {
    .t = &garden,
    .slots = garden_slots,
    .nslots = 4,
    .again = true,
    .group = {.dir = "bed", .off = offsetof(Garden, beds), .size = sizeof(Bed), .count_off = offsetof(Garden, nbeds),
              .name_off = offsetof(Bed, name), .open = open_bed},
    .set_if_clean = true,
};

static int read_garden(const char *lines, const SylOverride *sets, int nsets, Garden *out, char **diag) {
    SylProgram *p = keyed_compile("garden.syl", lines, sets, nsets);
    size_t len = 0;
    FILE *f = open_memstream(diag, &len);
    memset(out, 0, sizeof *out);
    sch_lines_defaults(&garden_lines, out);
    int set_errors, e = sch_read_lines(p, &garden_lines, out, f, &set_errors);
    fclose(f);
    syl_program_free(p);
    return e;
}

static const char garden_text[] = "  area 5\n  bed roses\n  depth 2\n  bed herbs\n  width 3\n";

static void groups_take_their_rows_and_sets(void **state) {
    (void)state;
    Garden g;
    char *diag = NULL;
    int e = read_garden(garden_text, NULL, 0, &g, &diag);
    if (e) fail_msg("%s", diag);
    free(diag);
    assert_near(g.area, 5, 0);
    assert_int_equal(g.nbeds, 2);
    assert_string_equal(g.beds[0].name, "roses");
    assert_near(g.beds[0].depth, 2, 0); /* the line after `bed roses` */
    assert_near(g.beds[0].width, 1, 0); /* its default */
    assert_near(g.beds[1].depth, 1, 0);
    assert_near(g.beds[1].width, 3, 0);
    /* NAME: every bed; ELEM.NAME: the one named; the last one wins */
    SylOverride sets[] = {{"depth", 7}, {"herbs.width", 9}, {"area", 8}};
    e = read_garden(garden_text, sets, 3, &g, &diag);
    if (e) fail_msg("%s", diag);
    free(diag);
    assert_near(g.beds[0].depth, 7, 0);
    assert_near(g.beds[1].depth, 7, 0);
    assert_near(g.beds[0].width, 1, 0); /* roses untouched by herbs.width */
    assert_near(g.beds[1].width, 9, 0);
    assert_near(g.area, 8, 0);
}

/* What is wrong with a group's lines and sets, at its place. The words are the reader's own
 * (a snapshot of its wording). */
static void groups_errors(void **state) {
    (void)state;
    Garden g;
    char *diag = NULL;
    /* an element no head opened, with did-you-mean */
    SylOverride typo[] = {{"rozes.depth", 4}};
    int e = read_garden(garden_text, typo, 1, &g, &diag);
    assert_int_equal(e, 1);
    assert_non_null(strstr(diag, "--set rozes.depth: no 'rozes' (did you mean 'roses'?)"));
    free(diag);
    assert_near(g.beds[0].depth, 2, 0); /* nothing set */
    /* a row of the block's given an element's prefix */
    SylOverride block[] = {{"roses.area", 4}};
    e = read_garden(garden_text, block, 1, &g, &diag);
    assert_int_equal(e, 1);
    assert_non_null(strstr(diag, "--set roses.area: 'area' is the block's"));
    free(diag);
    assert_near(g.area, 5, 0);
    /* a group's row before any head is unknown to the block, at its line */
    e = read_garden("  depth 2\n  bed roses\n", NULL, 0, &g, &diag);
    assert_int_equal(e, 1);
    assert_non_null(strstr(diag, "garden.syl:2:3: error: "));
    free(diag);
    /* set_if_clean: a line with an error keeps --set from being applied */
    SylOverride all[] = {{"depth", 7}};
    e = read_garden("  bed roses\n  depht 2\n", all, 1, &g, &diag);
    assert_int_equal(e, 1);
    assert_non_null(strstr(diag, "garden.syl:3:3: error: no parameter 'depht' (did you mean 'depth'?)"));
    free(diag);
    assert_near(g.beds[0].depth, 1, 0);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_type_is_read_by_its_row),
        cmocka_unit_test(errors_at_their_places),
        cmocka_unit_test(set_reaches_rows_and_levels),
        cmocka_unit_test(a_kind_words_and_lenience),
        cmocka_unit_test(describe_is_told_by_the_same_reader),
        cmocka_unit_test(groups_take_their_rows_and_sets),
        cmocka_unit_test(groups_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
