/* The kinds of model are listed once (src/lang/kinds.def) and each has a row in the registry
 * (src/kinds/kinds.c): every value of SylModelKind has both, the keyword, the noun and the id
 * agree (a block opened by the keyword compiles to that kind), and the flags and functions
 * are consistent, so that code that asks them never falls through to a wrong engine. */
#include <stdbool.h>

#include "unit.h"
#include "kinds/kinds.h"
#include "lang/kinds.h"
#include "lang/schema.h"

/* Compile text without the validate hook (the language only); the program or NULL. */
static SylProgram *compile_bare(const char *text) {
    int st;
    SylCompileOptions opt = {0};
    return syl_compile("test.syl", text, strlen(text), &opt, &st);
}

static void every_enum_value_has_a_row(void **state) {
    (void)state;
    /* No value of the public enum lacks its row: kinds_ops's switch, made from the table, has
     * no default (a value without its case is an error under -Wall -Werror), and lang/kinds.c
     * asserts at compile time that the rows are in the enum's order; so no test here names the
     * last kind, which a new kind would have to change. */
    for (int k = 0; k < LANG_KIND_COUNT; k++) {
        assert_non_null(lang_kind_keyword((SylModelKind)k));
        assert_string_not_equal(syl_model_kind_name((SylModelKind)k), "model");
        assert_true(lang_kind_flags((SylModelKind)k) != 0);
        assert_non_null(kinds_ops((SylModelKind)k));
    }
    /* outside the enum: no flags, the generic noun, the empty row */
    assert_int_equal(lang_kind_flags((SylModelKind)LANG_KIND_COUNT), 0);
    assert_null(lang_kind_keyword((SylModelKind)-1));
    assert_string_equal(syl_model_kind_name((SylModelKind)LANG_KIND_COUNT), "model");
    assert_null(kinds_ops((SylModelKind)LANG_KIND_COUNT)->validate);
}

static void keyword_noun_and_id_agree(void **state) {
    (void)state;
    for (int k = 0; k < LANG_KIND_COUNT; k++) {
        const char *kw = lang_kind_keyword((SylModelKind)k), *noun = syl_model_kind_name((SylModelKind)k);
        assert_int_equal(lang_kind_of_keyword(kw, strlen(kw)), k); /* and so no keyword twice */
        /* the noun is the keyword, or "KEYWORD block" for a block of directive lines */
        char block[64];
        snprintf(block, sizeof block, "%s block", kw);
        assert_string_equal(noun, lang_kind_is((SylModelKind)k, KF_DIRECTIVES) ? block : kw);
    }
    assert_int_equal(lang_kind_of_keyword("webe", 4), -1);
    assert_int_equal(lang_kind_of_keyword("weberx", 6), -1);
}

/* A named block opened by each keyword compiles to its kind, and --dump names it back. */
static void each_keyword_opens_its_kind(void **state) {
    (void)state;
    for (int k = 0; k < LANG_KIND_COUNT; k++) {
        if (lang_kind_is((SylModelKind)k, KF_UNNAMED)) continue; /* the scene: below */
        char text[256];
        snprintf(text, sizeof text, "%s Some {\n%s}\n", lang_kind_keyword((SylModelKind)k),
                 lang_kind_is((SylModelKind)k, KF_RULES) ? "  axiom F\n" : "");
        SylProgram *p = compile_bare(text);
        if (!p) fail_msg("a %s does not compile:\n%s", syl_model_kind_name((SylModelKind)k), text);
        assert_int_equal(syl_program_kind(p), k);
        assert_string_equal(syl_program_name(p), "Some");
        syl_program_free(p);
    }
    SylProgram *p = compile_bare("scene {\n  plant \"other.syl\" at (0, 0, 0)\n}\n");
    assert_non_null(p);
    assert_int_equal(syl_program_kind(p), SYL_MODEL_SCENE);
    syl_program_free(p);
}

/* What the engines above ask: a block of directives has its check; each kind that stands in a
 * scene is made exactly one way (grown, built from parameters, or derived); ages are a build's;
 * a string is a derived model's; what is not a plant stands nowhere a plant does. */
static void flags_and_functions_agree(void **state) {
    (void)state;
    for (int k = 0; k < LANG_KIND_COUNT; k++) {
        SylModelKind kind = (SylModelKind)k;
        const KindOps *ops = kinds_ops(kind);
        const char *noun = syl_model_kind_name(kind);
        if (lang_kind_is(kind, KF_DIRECTIVES) && !ops->validate) fail_msg("the %s has no validate", noun);
        if (lang_kind_is(kind, KF_IN_SCENE)) {
            int ways = lang_kind_is(kind, KF_GROWS) + (ops->build != NULL) + lang_kind_is(kind, KF_RULES);
            if (ways != 1) fail_msg("the %s stands in a scene and is made %d ways", noun, ways);
        }
        if (lang_kind_is(kind, KF_AGES) && !ops->build) fail_msg("the %s has ages but no build", noun);
        if (lang_kind_is(kind, KF_STRING) && !lang_kind_is(kind, KF_RULES)) fail_msg("the %s has a string", noun);
        if (lang_kind_is(kind, KF_LOOK) && !lang_kind_is(kind, KF_IN_SCENE)) fail_msg("the %s is a look only", noun);
        if (lang_kind_is(kind, KF_NOT_A_PLANT) && lang_kind_is(kind, KF_IN_SCENE | KF_LOOK | KF_RULES))
            fail_msg("the %s is not a plant, yet a plant's flag is set", noun);
        if (lang_kind_is(kind, KF_UNNAMED) && lang_kind_is(kind, KF_DIRECTIVES | KF_RULES | KF_IN_SCENE))
            fail_msg("the scene is a model");
    }
}

/* `sylva convert` asks the converts and convert columns: a kind converts to some files exactly
 * when it has the function that writes them, each bit names an extension, and a kind that
 * converts is a named block of directives (what the writers read back). A row that left
 * either column out, or filled one and not the other, fails here. */
static void converts_and_convert_agree(void **state) {
    (void)state;
    int converting = 0;
    for (int k = 0; k < LANG_KIND_COUNT; k++) {
        SylModelKind kind = (SylModelKind)k;
        const KindOps *ops = kinds_ops(kind);
        const char *noun = syl_model_kind_name(kind);
        if ((ops->converts != 0) != (ops->convert != NULL)) fail_msg("the %s: converts and convert disagree", noun);
        if (ops->converts & ~(unsigned)KC_ALL) fail_msg("the %s converts to an unknown file", noun);
        if (ops->converts && !lang_kind_is(kind, KF_DIRECTIVES)) fail_msg("the %s converts but has no directives", noun);
        if (ops->converts && !(ops->converts & KC_SYL)) fail_msg("the %s converts, but not back to a block", noun);
        converting += ops->converts != 0;
    }
    assert_true(converting > 0); /* sylva convert has something to write (tests/cases/convert.test) */
    assert_string_equal(lang_convert_ext(KC_XML), ".xml");
    assert_string_equal(lang_convert_ext(KC_CFG), ".cfg");
    assert_string_equal(lang_convert_ext(KC_SYL), ".syl");
    assert_null(lang_convert_ext(0));
    assert_null(lang_convert_ext(KC_XML | KC_SYL));
    assert_null(kinds_ops((SylModelKind)LANG_KIND_COUNT)->convert);
}

/* What a binding asks of a kind (syl_model_kind_is) is its flags, and nothing outside the enum. */
static void traits_are_the_flags(void **state) {
    (void)state;
    for (int k = 0; k < LANG_KIND_COUNT; k++) {
        SylModelKind kind = (SylModelKind)k;
        assert_int_equal(syl_model_kind_is(kind, SYL_MODEL_HAS_STRING), lang_kind_is(kind, KF_STRING));
        assert_int_equal(syl_model_kind_is(kind, SYL_MODEL_HAS_STEPS), lang_kind_is(kind, KF_RULES | KF_GROWS));
        assert_int_equal(syl_model_kind_is(kind, SYL_MODEL_IS_PLANT), !lang_kind_is(kind, KF_NOT_A_PLANT));
        assert_string_equal(syl_model_kind_keyword(kind), lang_kind_keyword(kind));
    }
    assert_int_equal(syl_model_kind_is((SylModelKind)LANG_KIND_COUNT, SYL_MODEL_IS_PLANT), 0);
    assert_null(syl_model_kind_keyword((SylModelKind)-1));
}

/* The capabilities a front end asks by name are the flags, one name a bit (lang/kind_flags.def):
 * every bit named, each name once and a word a JSON key or a Python attribute can be, nothing
 * past the last. A TAKES_ bit is a promise to the Blender add-on, which writes the object into
 * the block as the directive the bit names: the kind's table has that directive, of that type
 * (the scene's obstacles: the kind is planted in a scene). */
static void capabilities_are_the_flags_by_name(void **state) {
    (void)state;
    for (int i = 0; i < KF_COUNT; i++) {
        const char *name = syl_model_cap_name(i);
        assert_non_null(name);
        assert_non_null(syl_model_cap_doc(i));
        assert_int_equal(strspn(name, "abcdefghijklmnopqrstuvwxyz_"), strlen(name));
        for (int j = 0; j < i; j++) assert_string_not_equal(syl_model_cap_name(j), name);
    }
    assert_null(syl_model_cap_name(KF_COUNT));
    assert_null(syl_model_cap_name(-1));
    assert_string_equal(syl_model_cap_name(KF_BIT_NOT_A_PLANT), "not_a_plant");
    static const struct { unsigned flag; const char *dir; SchType type; } takes[] = {
        {KF_TAKES_TRUNK, "trunk", SCH_CURVE}, {KF_TAKES_ENVELOPE, "envelope", SCH_FILE},
        {KF_TAKES_TERRAIN, "terrain", SCH_FILE}};
    for (int k = 0; k < LANG_KIND_COUNT; k++) {
        SylModelKind kind = (SylModelKind)k;
        assert_int_equal(syl_model_kind_caps(kind), lang_kind_flags(kind));
        for (size_t t = 0; t < sizeof takes / sizeof *takes; t++) {
            if (!lang_kind_is(kind, takes[t].flag)) continue;
            int level;
            const SchRow *r = lang_kind_schema(kind) ? sch_find(lang_kind_schema(kind), takes[t].dir, &level) : NULL;
            if (!r || r->type != takes[t].type)
                fail_msg("the %s takes a %s but has no %s directive of that type", syl_model_kind_name(kind), takes[t].dir,
                         takes[t].dir);
        }
        if (lang_kind_is(kind, KF_TAKES_OBSTACLES) && !lang_kind_is(kind, KF_IN_SCENE))
            fail_msg("the %s takes a scene's obstacles but stands in no scene", syl_model_kind_name(kind));
    }
    assert_int_equal(syl_model_kind_caps((SylModelKind)LANG_KIND_COUNT), 0);
}

/* The refusal is worded from the row: the article follows the noun, and a kind that is not a
 * plant says so whatever it was asked for. */
static void refusals_are_worded_from_the_row(void **state) {
    (void)state;
    char *buf = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&buf, &len);
    lang_kind_refuse(NULL, mem, "E", SYL_MODEL_ECOSYSTEM, false);
    lang_kind_refuse(NULL, mem, "T", SYL_MODEL_STRANDS, false);
    lang_kind_refuse(NULL, NULL, "T", SYL_MODEL_STRANDS, false); /* no sink: nothing */
    fclose(mem);
    assert_string_equal(buf, "sylva: error: 'E' is an ecosystem block, not a plant: run `sylva ecosystem`\n"
                             "sylva: error: 'T' is a strands block, not an lsystem: it has no string; mesh or "
                             "render it\n");
    free(buf);
}

/* syl_validate checks an ecosystem block, which the language alone does not. */
static void validate_covers_every_directive_kind(void **state) {
    (void)state;
    const char *text = "ecosystem Field {\n  yeras 3\n}\n";
    SylProgram *p = compile_bare(text);
    assert_non_null(p); /* the language has nothing to say */
    char *buf = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&buf, &len);
    int e1 = syl_validate(NULL, p, mem);
    fclose(mem);
    assert_true(e1 > 0);
    assert_non_null(strstr(buf, "test.syl:2:3: error:"));
    free(buf);
    syl_program_free(p);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_enum_value_has_a_row),
        cmocka_unit_test(keyword_noun_and_id_agree),
        cmocka_unit_test(each_keyword_opens_its_kind),
        cmocka_unit_test(flags_and_functions_agree),
        cmocka_unit_test(converts_and_convert_agree),
        cmocka_unit_test(traits_are_the_flags),
        cmocka_unit_test(capabilities_are_the_flags_by_name),
        cmocka_unit_test(refusals_are_worded_from_the_row),
        cmocka_unit_test(validate_covers_every_directive_kind),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
