/* The directive schema: each block is read once on its way from syl_compile to a plant
 * (counted by the program's read statistic), and docs/directives.md is the tables' text.
 *   test_schema                 run the tests
 *   test_schema --write FILE    write the reference (tools/gen-directives) */
#include "unit.h"

#include "lang/program.h"
#include "lang/schema.h"
#include "sylva/ecosystem.h"
#include "sylva/plant.h"

static int validate_all(void *user, const SylProgram *p, FILE *diag) { /* the CLI's hook: every kind's check */
    return syl_validate(user, p, diag);
}

static SylProgram *compile(const char *text, const char *model, bool hook) {
    SylCompileOptions opt = {.model = model, .validate = hook ? validate_all : NULL};
    int st;
    SylProgram *p = syl_compile("test.syl", text, strlen(text), &opt, &st);
    assert_non_null(p);
    return p;
}

/* compile (the validate hook reads the block), then build: one read in all */
static int reads_to_build(const char *text, bool hook, int builds) {
    SylProgram *p = compile(text, NULL, hook);
    SylPlantOptions o = {.until = SYL_PLANT_SKELETON, .threads = 1};
    for (int k = 0; k < builds; k++) {
        SylPlant pl;
        assert_int_equal(syl_plant_build(p, &o, &pl), SYL_OK);
        assert_non_null(pl.skeleton);
        syl_plant_free(&pl);
    }
    int n = sch_reads(p);
    syl_program_free(p);
    return n;
}

static const char weber[] = "weber W {\n  Levels 2\n  Branches 1 5\n  lod 2\n}\n";
static const char strands[] = "strands S {\n  strands 50\n  angle 30\n}\n";
static const char grow[] = "grow G {\n  years 3\n  internode 0.2\n}\n";

static void a_block_is_read_once(void **state) {
    (void)state;
    assert_int_equal(reads_to_build(weber, true, 1), 1);
    assert_int_equal(reads_to_build(strands, true, 1), 1);
    assert_int_equal(reads_to_build(grow, true, 1), 1);
    assert_int_equal(reads_to_build(weber, true, 3), 1); /* builds after the first take the kept reading */
}

/* an embedder that passes no validate hook: each build reads (nothing is kept after compiling) */
static void without_the_hook_each_build_reads(void **state) {
    (void)state;
    assert_int_equal(reads_to_build(weber, false, 2), 2);
    assert_int_equal(reads_to_build(strands, false, 1), 1);
}

static void an_ecosystem_is_read_once(void **state) {
    (void)state;
    SylProgram *p = compile("lsystem B {\n  axiom F\n}\necosystem E {\n  terrain \"flat.asc\"\n  years 4\n"
                            "  species a\n    model B\n    maturity 3\n}\n",
                            "E", true);
    SylEcoModel m;
    assert_int_equal(syl_ecosystem_read(p, &m, NULL), 0);
    assert_int_equal(m.years, 4);
    assert_true(m.nspecies == 1 && m.species[0].maturity == 3);
    assert_int_equal(sch_reads(p), 1);
    syl_program_free(p);
}

/* the kept reading is the reading: --set values included */
static void the_kept_reading_has_the_sets(void **state) {
    (void)state;
    SylOverride set[] = {{"years", 7}};
    const char *text = "lsystem B {\n  axiom F\n}\necosystem E {\n  terrain \"flat.asc\"\n  years 4\n"
                       "  species a\n    model B\n}\n";
    SylCompileOptions opt = {.model = "E", .validate = validate_all, .overrides = set, .noverrides = 1};
    int st;
    SylProgram *p = syl_compile("test.syl", text, strlen(text), &opt, &st);
    assert_non_null(p);
    SylEcoModel m;
    assert_int_equal(syl_ecosystem_read(p, &m, NULL), 0);
    assert_int_equal(m.years, 7);
    syl_program_free(p);
}

static char *reference(size_t *len) {
    char *text = NULL;
    FILE *f = open_memstream(&text, len);
    lang_directives_reference(f);
    fclose(f);
    return text;
}

/* docs/directives.md is what tools/gen-directives writes from the tables */
static void the_reference_doc_is_up_to_date(void **state) {
    (void)state;
    size_t len, doc_len = 0;
    char *want = reference(&len), *doc = NULL;
    FILE *f = fopen("docs/directives.md", "rb") /* the tests run at the root */;
    if (f) {
        doc = calloc(1, len + 2);
        doc_len = fread(doc, 1, len + 1, f);
        fclose(f);
    }
    if (!doc || doc_len != len || memcmp(doc, want, len))
        fail_msg("docs/directives.md differs from the tables: run tools/gen-directives");
    free(doc);
    free(want);
}

int main(int argc, char **argv) {
    if (argc == 3 && !strcmp(argv[1], "--write")) {
        FILE *f = fopen(argv[2], "w");
        if (!f) return 4;
        lang_directives_reference(f);
        return fclose(f) ? 4 : 0;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_block_is_read_once),          cmocka_unit_test(without_the_hook_each_build_reads),
        cmocka_unit_test(an_ecosystem_is_read_once),     cmocka_unit_test(the_kept_reading_has_the_sets),
        cmocka_unit_test(the_reference_doc_is_up_to_date),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
