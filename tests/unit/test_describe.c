/* sylva describe through the kinds table: every kind that is a model has a directive table
 * (its row's describe column, the same for the language and the registry), every row of it
 * has a type, a meaning, a unit and a range its default lies in, and syl_describe_json prints
 * every row for a model of each kind. */
#include "unit.h"

#include <math.h>

#include "kinds/kinds.h"
#include "lang/kinds.h"
#include "lang/program.h"
#include "lang/schema.h"
#include "sylva/describe.h"

static void every_model_kind_has_a_table(void **state) {
    (void)state;
    for (int k = 0; k < LANG_KIND_COUNT; k++) {
        const SchTable *t = lang_kind_schema((SylModelKind)k);
        assert_ptr_equal(kinds_ops((SylModelKind)k)->describe, t); /* one column, read by both */
        if (!t) fail_msg("kind '%s' has no directive table", lang_kind_keyword((SylModelKind)k));
        assert_string_equal(t->kind, lang_kind_keyword((SylModelKind)k));
    }
}

/* A default outside the range is allowed only when the meaning says what it stands for,
 * "(0: the internode)". */
static void every_row_is_filled(void **state) {
    (void)state;
    for (int k = 0; k < LANG_KIND_COUNT; k++) {
        const SchTable *t = lang_kind_schema((SylModelKind)k);
        for (int i = 0; t && i < t->n; i++) {
            const SchRow *r = &t->rows[i];
            if (!r->name || !*r->name || !r->doc || !*r->doc || !r->unit || strchr(r->doc, '\n'))
                fail_msg("%s row %d ('%s'): a name, a unit (\"\" for none) and a one-line meaning", t->kind, i,
                         r->name ? r->name : "?");
            if (strcmp(sch_type_name(r->type), "?") == 0) fail_msg("%s.%s: no type", t->kind, r->name);
            if (r->type == SCH_ENUM && (!r->words || !*r->words)) fail_msg("%s.%s: an enum without words", t->kind, r->name);
            bool numeric = r->type == SCH_NUMBER || r->type == SCH_INTEGER || r->levels;
            if (!numeric) continue;
            if (!(r->lo < r->hi)) fail_msg("%s.%s: no range", t->kind, r->name);
            for (int l = 0; l < (r->levels ? r->levels : 1); l++) {
                char why[160];
                if (isnan(r->def[l]) || sch_value_ok(r, r->def[l], why, sizeof why)) continue;
                char sentinel[32];
                snprintf(sentinel, sizeof sentinel, "(%g: ", r->def[l]);
                if (!strstr(r->doc, sentinel)) fail_msg("%s.%s: the default %s", t->kind, r->name, why);
            }
        }
    }
}

static void describe(const char *text, const char *model, char **out) {
    SylCompileOptions opt = {.model = model};
    int st;
    SylProgram *p = syl_compile("test.syl", text, strlen(text), &opt, &st);
    assert_non_null(p);
    size_t len;
    FILE *f = open_memstream(out, &len);
    assert_int_equal(syl_describe_json(p, f), SYL_OK);
    fclose(f);
    syl_program_free(p);
}

/* The line that opens an element of a table's group of rows. */
static const char *group_element(const char *group) {
    if (!strcmp(group, "species")) return "  species a\n    model M0\n"; /* M0: the first kind's model */
    if (!strcmp(group, "organ line")) return "  organ leaf\n";
    fail_msg("no element of group '%s' in this test: add the line that opens one", group);
    return "";
}

/* each row of each table is a param of its model: a group's rows under the group's name. The
 * file has a model of each kind with a table, from the kinds' table (a new kind is in it by
 * its row): an empty block, but for one element of each group of its rows and an L-system's
 * axiom. It is not validated (no hook), so no block needs more. */
static void describe_prints_every_row(void **state) {
    (void)state;
    char text[4096];
    size_t at_text = 0;
    int tables = 0;
    for (int k = 0; k < LANG_KIND_COUNT; k++) {
        SylModelKind kind = (SylModelKind)k;
        const SchTable *t = lang_kind_schema(kind);
        if (!t) continue;
        tables++;
        if (lang_kind_is(kind, KF_UNNAMED)) { /* a scene: plant and obstacle lines are its groups */
            at_text += (size_t)snprintf(text + at_text, sizeof text - at_text,
                                        "scene {\n  plant M0 at (1, 0, 2) seed 3\n"
                                        "  obstacle \"wall.obj\" at (0, 0, 1) scale 2\n  ground 0.5\n}\n");
            continue;
        }
        at_text += (size_t)snprintf(text + at_text, sizeof text - at_text, "%s M%d {\n%s", lang_kind_keyword(kind), k,
                                    lang_kind_is(kind, KF_RULES) ? "  axiom F\n" : "");
        for (int i = 0; i < t->n; i++) /* each group once, at its first row */
            if (t->rows[i].group && (i == 0 || !t->rows[i - 1].group || strcmp(t->rows[i - 1].group, t->rows[i].group)))
                at_text += (size_t)snprintf(text + at_text, sizeof text - at_text, "%s", group_element(t->rows[i].group));
        at_text += (size_t)snprintf(text + at_text, sizeof text - at_text, "}\n");
        assert_true(at_text < sizeof text);
    }
    char *json = NULL;
    describe(text, "M0", &json);
    assert_non_null(json);
    int models = 0;
    for (int k = 0; k < LANG_KIND_COUNT; k++) {
        const SchTable *t = lang_kind_schema((SylModelKind)k);
        if (!t) continue;
        char kind[64];
        snprintf(kind, sizeof kind, "\"kind\":\"%s\"", t->kind);
        const char *at = strstr(json, kind);
        if (!at) {
            fail_msg("describe has no %s model", t->kind);
            return;
        }
        models++;
        const char *end = strstr(at + 1, "\"kind\":"); /* the next model's */
        if (!end) end = at + strlen(at);
        for (int i = 0; i < t->n; i++) {
            const SchRow *r = &t->rows[i];
            char name[160], key[200];
            const char *pre = t->shape == SCH_SCENE ? "scene." : ""; /* named as --set takes them */
            if (!r->group) snprintf(name, sizeof name, "%s%s", pre, r->name);
            else if (!strcmp(r->group, "species")) snprintf(name, sizeof name, "a.%s", r->name);
            else { /* organ: organ.1, organ.1.size */
                const char *dot = strchr(r->name, '.');
                snprintf(name, sizeof name, "%s%.*s.1%s", pre, dot ? (int)(dot - r->name) : (int)strlen(r->name), r->name,
                         dot ? dot : "");
            }
            snprintf(key, sizeof key, "{\"name\":\"%s\",", name);
            const char *hit = strstr(at, key);
            if (!hit || hit > end) fail_msg("describe of the %s model lacks '%s'", t->kind, name);
        }
    }
    assert_int_equal(models, tables);
    assert_true(tables >= 8); /* lsystem grow scene weber strands ecosystem curvetree pafco, at least */
    /* the scene's lines as written, its plant and obstacle lines' rows by their place (scene/params.def) */
    const char *scene = strstr(json, "\"kind\":\"scene\"");
    assert_non_null(scene);
    assert_non_null(strstr(scene, "{\"name\":\"scene.ground\",\"type\":\"number\",\"min\":-1000000,\"max\":1000000,\"default\":null,\"value\":0.5,"));
    assert_non_null(strstr(scene, "{\"name\":\"scene.plant.1\",\"type\":\"string\",\"min\":null,\"max\":null,\"default\":null,\"value\":\"M0\","));
    assert_non_null(strstr(scene, "{\"name\":\"scene.plant.1.z\",\"type\":\"number\",\"min\":-1000000,\"max\":1000000,\"default\":null,\"value\":2,"));
    assert_non_null(strstr(scene, "{\"name\":\"scene.plant.1.seed\",\"type\":\"integer\",\"min\":0,\"max\":9.00719925474099e+15,\"default\":null,\"value\":3,"));
    assert_non_null(strstr(scene, "{\"name\":\"scene.obstacle.1.scale\",\"type\":\"number\",\"min\":0,\"max\":1000000,\"default\":1,\"value\":2,"));
    free(json);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_model_kind_has_a_table),
        cmocka_unit_test(every_row_is_filled),
        cmocka_unit_test(describe_prints_every_row),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
