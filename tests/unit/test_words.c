/* Every word of the language is contextual (docs/language.md, Names): a fn, const, param,
 * module and formal parameter may be named by any keyword or setting word. The words come
 * from the one list of each (syl_keywords, lang/kinds.def, syl_setting_name), so a new word is covered. */
#include <stdbool.h>

#include "unit.h"
#include "lang/kinds.h"
#include "lang/parse_state.h"

/* Each program derives one step; %1$s is the word. `derive 1` stands in statement position
 * beside the declaration, so the setting and a name spelled `derive` work side by side. */
static const struct {
    const char *what, *text, *expected;
} uses[] = {
    {"fn", "fn %1$s(x) = x + 1\nlsystem T {\n  derive 1\n  A(x) -> A(%1$s(x))\n  axiom A(1)\n}\n", "A(2)"},
    {"const", "const %1$s = 5\nlsystem T {\n  derive 1\n  A(x) -> A(x + %1$s)\n  axiom A(1)\n}\n", "A(6)"},
    {"param", "param %1$s = 7\nlsystem T {\n  derive 1\n  A(x) -> A(x + %1$s)\n  axiom A(1)\n}\n", "A(8)"},
    {"module", "module %1$s(x)\nlsystem T {\n  derive 1\n  %1$s(x) -> %1$s(x + 1) [%1$s(0)]\n  axiom %1$s(1)\n}\n",
     "%1$s(2)[%1$s(0)]"},
    {"formal parameter",
     "fn f(%1$s) = %1$s * 3\nlsystem T {\n  derive 1\n  A(%1$s) -> A(f(%1$s) + %1$s)\n  axiom A(1)\n}\n", "A(4)"},
};

static void check_word(const char *word) {
    for (size_t i = 0; i < sizeof uses / sizeof *uses; i++) {
        char text[1024], expected[256];
        snprintf(text, sizeof text, uses[i].text, word);
        snprintf(expected, sizeof expected, uses[i].expected, word);
        UnitRun r = unit_run(text, (SylDeriveOptions){.steps = -1, .threads = 1});
        if (r.status != SYL_OK) fail_msg("a %s named '%s' fails:\n%s\n%s", uses[i].what, word, text, r.diag);
        char *got = unit_string(&r);
        if (strcmp(got, expected)) fail_msg("a %s named '%s': got %s, expected %s", uses[i].what, word, got, expected);
        free(got);
        unit_run_free(&r);
    }
}

static void every_setting_word_is_a_name(void **state) {
    (void)state;
    int n = 0;
    for (int i = 0; syl_setting_name(i); i++, n++) check_word(syl_setting_name(i));
    assert_true(n >= 9);
}

static void every_keyword_is_a_name(void **state) {
    (void)state;
    int n = 0;
    bool group = false, use = false; /* the tables' words (docs/language.md §20) are in the list */
    for (const SylKeyword *k = syl_keywords; k->word; k++, n++) {
        check_word(k->word);
        group |= !strcmp(k->word, "group");
        use |= !strcmp(k->word, "use");
    }
    for (int k = 0; k < LANG_KIND_COUNT; k++, n++) check_word(lang_kind_keyword((SylModelKind)k)); /* lang/kinds.def */
    assert_true(n >= 15);
    assert_true(group && use);
}

/* `group` and `use` name a module, a group and a module's use beside the lines they head: the
 * group named use is used at step 2 only. */
static void group_and_use_as_names_beside_tables(void **state) {
    (void)state;
    assert_derives("module group(x), use\nlsystem T {\n  derive 2\n  axiom use group(1)\n  group use {\n"
                   "    group(x) -> group(x + 1) use\n  }\n  use use when step == 2\n}\n",
                   -1, "usegroup(2)use");
}

/* The directive words of grow and scene blocks are listed where they are read (src/sot/params.def,
 * src/scene/spec.c, outside the language): every word-like string literal there is tried, so a
 * new directive, mode or key is covered. Run from the top of the source tree (tests/run-all). */
static int directive_words_in(const char *path) {
    FILE *f = fopen(path, "r");
    if (!f) fail_msg("cannot read %s (run from the top of the source tree)", path);
    int n = 0, c, prev = 0;
    while ((c = fgetc(f)) != EOF) {
        if (c == '"' && prev != '\\' && prev != '\'') {
            char w[64];
            size_t k = 0;
            while ((c = fgetc(f)) != EOF && c != '"' && c != '\n' && k + 1 < sizeof w) w[k++] = (char)c;
            w[k] = 0;
            bool word = k > 0 && c == '"' && w[0] >= 'a' && w[0] <= 'z';
            for (size_t i = 0; i < k; i++)
                if (!((w[i] >= 'a' && w[i] <= 'z') || (w[i] >= '0' && w[i] <= '9') || w[i] == '_')) word = false;
            if (word) check_word(w), n++;
            prev = 0;
            continue;
        }
        prev = c;
    }
    fclose(f);
    return n;
}

static void every_directive_word_is_a_name(void **state) {
    (void)state;
    assert_true(directive_words_in("src/sot/params.def") >= 40);
    assert_true(directive_words_in("src/scene/spec.c") >= 4);
}

/* A setting and a name spelled alike are two things: `angle 30` sets the turtle's angle, and
 * `angle` in an expression is the declared const (as a variable named after a setting is in
 * L-Py's Python and lpfg's C); `angle angle` sets the setting to the const's value. */
static void setting_and_name_spelled_alike(void **state) {
    (void)state;
    UnitRun r = unit_run("const angle = 20\nconst step = 2\nlsystem T {\n  angle 30\n  step step\n"
                         "  derive 1\n  A(x) -> A(x + angle)\n  axiom A(1)\n}\n",
                         (SylDeriveOptions){.steps = -1, .threads = 1});
    assert_int_equal(r.status, SYL_OK);
    char *got = unit_string(&r);
    assert_string_equal(got, "A(21)");
    free(got);
    assert_true(syl_program_setting(r.p, "angle") == 30);
    assert_true(syl_program_setting(r.p, "step") == 2);
    unit_run_free(&r);
    /* a setting is no value: without a declaration, `angle` in an expression is unknown */
    r = unit_run("lsystem T {\n  angle 30\n  axiom A(angle)\n}\n", (SylDeriveOptions){.steps = 0, .threads = 1});
    assert_int_not_equal(r.status, SYL_OK);
    assert_non_null(strstr(r.diag, "angle"));
    unit_run_free(&r);
}

/* The first word of a rule is a module even when it is a setting or keyword word; a setting
 * or keyword line stays one (derive, ignore and axiom below). */
static void rules_headed_by_words(void **state) {
    (void)state;
    assert_derives("module angle, axiom, ignore\nlsystem T {\n  derive 2\n  ignore angle\n"
                   "  angle -> angle axiom\n  axiom < ignore -> ignore ignore\n  axiom angle ignore axiom\n}\n",
                   -1, "angleaxiomaxiomignoreignoreaxiom"); /* step 1: ignore's left is only angle, ignored */
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_setting_word_is_a_name),
        cmocka_unit_test(every_keyword_is_a_name),
        cmocka_unit_test(every_directive_word_is_a_name),
        cmocka_unit_test(setting_and_name_spelled_alike),
        cmocka_unit_test(rules_headed_by_words),
        cmocka_unit_test(group_and_use_as_names_beside_tables),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
