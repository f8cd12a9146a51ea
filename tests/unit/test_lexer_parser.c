/* The lexer and the parser: syl_parse on small texts, and what the parse means once compiled. */
#include "unit.h"
#include "lang/ast.h"
#include "util/arena.h"

typedef struct Parsed {
    Arena arena;
    Source src;
    FileAst ast;
    int errors;
    char *diag;
} Parsed;

static Parsed *parse(const char *text) {
    Parsed *ps = calloc(1, sizeof *ps);
    size_t len = 0;
    FILE *mem = open_memstream(&ps->diag, &len);
    ps->src = (Source){.path = "test.syl", .text = text, .len = strlen(text)};
    Diag d = {.out = mem, .src = &ps->src};
    ps->errors = syl_parse(&ps->src, &ps->arena, &d, &ps->ast);
    fclose(mem);
    return ps;
}

static void parsed_free(Parsed *ps) {
    arena_free(&ps->arena);
    free(ps->diag);
    free(ps);
}

/* The nth statement of kind k in the first model, or NULL. */
static const Stmt *stmt_of(const Parsed *ps, StmtKind k, int nth) {
    if (ps->ast.nmodels < 1) return NULL;
    const Model *m = &ps->ast.models[0];
    for (int i = 0; i < m->n; i++)
        if (m->v[i].kind == k && nth-- == 0) return &m->v[i];
    return NULL;
}

static void assert_item(const Item *it, ItemKind kind, const char *text, int nargs) {
    assert_int_equal(it->kind, kind);
    assert_string_equal(it->text, text);
    assert_int_equal(it->args.n, nargs);
}

/* Derive `axiom A(expr)` for 0 steps and return A's first parameter. */
static double axiom_value(const char *expr) {
    char text[512];
    snprintf(text, sizeof text, "lsystem T {\n  axiom A(%s)\n}\n", expr);
    UnitRun r = unit_run(text, (SylDeriveOptions){.steps = 0, .threads = 1});
    if (r.status != SYL_OK) fail_msg("`%s` failed:\n%s", expr, r.diag);
    double v = unit_param(&r, 0, 0);
    unit_run_free(&r);
    return v;
}

/* ---- statements ---- */

static void statement_kinds_and_counts(void **state) {
    Parsed *ps = parse("const a = 1, b = 2\n"
                       "lsystem T {\n"
                       "  derive 3\n"
                       "  module Apex(x, y), Bud\n"
                       "  param lat = 45\n"
                       "  fn f(u, v) = u + v\n"
                       "  curve c = (0, 0), (1, 2)\n"
                       "  ignore + -\n"
                       "  axiom F\n"
                       "  A -> B\n"
                       "  interpret {\n"
                       "    B -> F\n"
                       "  }\n"
                       "}\n"
                       "lsystem U {\n"
                       "  axiom X\n"
                       "}\n");
    assert_int_equal(ps->errors, 0);
    assert_int_equal(ps->ast.top.n, 2);
    assert_int_equal(ps->ast.top.v[0].kind, ST_CONST);
    assert_string_equal(ps->ast.top.v[1].name, "b");
    assert_int_equal(ps->ast.nmodels, 2);
    assert_string_equal(ps->ast.models[0].name, "T");
    assert_string_equal(ps->ast.models[1].name, "U");
    const Model *m = &ps->ast.models[0];
    static const StmtKind want[] = {ST_SETTING, ST_MODULE, ST_MODULE, ST_PARAM, ST_FN,
                                    ST_CURVE,   ST_IGNORE, ST_AXIOM,  ST_RULE,  ST_RULE};
    assert_int_equal(m->n, (int)(sizeof want / sizeof *want));
    for (int i = 0; i < m->n; i++) assert_int_equal(m->v[i].kind, want[i]);
    assert_string_equal(m->v[0].name, "derive");
    assert_string_equal(m->v[1].name, "Apex");
    assert_true(m->v[1].has_params);
    assert_int_equal(m->v[1].params.n, 2);
    assert_string_equal(m->v[2].name, "Bud");
    assert_false(m->v[2].has_params);
    assert_int_equal(m->v[4].params.n, 2);
    assert_int_equal(m->v[5].args.n, 4); /* x0, y0, x1, y1 */
    assert_int_equal(m->v[6].items.n, 2);
    assert_int_equal(m->v[8].block, BLOCK_PRODUCE);
    assert_int_equal(m->v[9].block, BLOCK_INTERPRET);
    assert_int_equal(m->v[9].loc.first_line, 12);
    assert_int_equal(ps->ast.models[1].n, 1);
    parsed_free(ps);
}

static void axiom_items_split(void **state) {
    Parsed *ps = parse("lsystem T {\n  axiom F(1)[+(25.7)F(0.5)]X\n}\n");
    assert_int_equal(ps->errors, 0);
    const Stmt *ax = stmt_of(ps, ST_AXIOM, 0);
    assert_non_null(ax);
    assert_int_equal(ax->items.n, 6);
    const Item *it = ax->items.v;
    assert_item(&it[0], IT_WORD, "F", 1);
    assert_int_equal(it[0].args.v[0]->kind, EX_NUM);
    assert_true(it[0].args.v[0]->num == 1);
    assert_item(&it[1], IT_SYMBOL, "[", 0);
    assert_item(&it[2], IT_SYMBOL, "+", 1);
    assert_true(it[2].args.v[0]->num == 25.7);
    assert_item(&it[3], IT_WORD, "F", 1);
    assert_true(it[3].args.v[0]->num == 0.5);
    assert_item(&it[4], IT_SYMBOL, "]", 0);
    assert_item(&it[5], IT_WORD, "X", 0);
    assert_false(it[5].parens);
    /* columns count from 1: "  axiom F(1)[" puts F at 9 and '[' at 13 */
    assert_int_equal(it[0].loc.first_line, 2);
    assert_int_equal(it[0].loc.first_column, 9);
    assert_int_equal(it[1].loc.first_column, 13);
    parsed_free(ps);
    assert_derives("lsystem T {\n  axiom F(1)[+(25.7)F(0.5)]X\n}\n", 0, "F(1)[+(25.7)F(0.5)]X");
}

/* A word is split by the checker: letters are modules, declared names are taken greedily. */
static void words_split_into_modules(void **state) {
    UnitRun r = unit_run("lsystem T {\n  module Apex, Ap\n  axiom ApexApF12 FX()\n}\n",
                         (SylDeriveOptions){.steps = 0, .threads = 1});
    assert_int_equal(r.status, SYL_OK);
    assert_int_equal(syl_string_length(r.s), 7); /* Apex Ap F 1 2 F X */
    static const char *const names[] = {"Apex", "Ap", "F", "1", "2", "F", "X"};
    for (size_t i = 0; i < 7; i++) {
        int np = -1;
        const double *par;
        int sym = syl_string_module(r.s, i, &np, &par);
        assert_string_equal(syl_program_symbol_name(r.p, sym), names[i]);
        assert_int_equal(np, 0);
    }
    assert_int_equal(syl_program_symbol_find(r.p, "FX"), -1);
    unit_run_free(&r);
}

static void arrows_are_equivalent(void **state) {
    Parsed *ps = parse("lsystem T {\n  axiom ABC\n  A -> X\n  B --> Y\n  C \xe2\x86\x92 Z\n}\n");
    assert_int_equal(ps->errors, 0);
    for (int i = 0; i < 3; i++) {
        const Stmt *s = stmt_of(ps, ST_RULE, i);
        assert_non_null(s);
        assert_int_equal(s->rule.pred.n, 1);
        assert_int_equal(s->rule.succ.n, 1);
        assert_string_equal(s->rule.succ.v[0].text, i == 0 ? "X" : i == 1 ? "Y" : "Z");
        assert_false(s->rule.has_left);
        assert_false(s->rule.has_right);
    }
    parsed_free(ps);
    assert_derives("lsystem T {\n  axiom ABC\n  A -> X\n  B --> Y\n  C \xe2\x86\x92 Z\n}\n", 1, "XYZ");
}

static void andand_in_successor_is_two_modules(void **state) {
    Parsed *ps = parse("lsystem T {\n  axiom A\n  A -> B&&C||D\n}\n");
    assert_int_equal(ps->errors, 0);
    const Stmt *s = stmt_of(ps, ST_RULE, 0);
    assert_non_null(s);
    assert_int_equal(s->rule.succ.n, 7);
    assert_string_equal(s->rule.succ.v[1].text, "&");
    assert_string_equal(s->rule.succ.v[2].text, "&");
    assert_string_equal(s->rule.succ.v[4].text, "|");
    assert_string_equal(s->rule.succ.v[5].text, "|");
    parsed_free(ps);
    UnitRun r = unit_run("lsystem T {\n  axiom A\n  A -> B&&C\n}\n", (SylDeriveOptions){.steps = 1, .threads = 1});
    assert_int_equal(r.status, SYL_OK);
    assert_int_equal(syl_string_length(r.s), 4);
    assert_int_equal(unit_count(&r, "&"), 2);
    unit_run_free(&r);
}

/* cpfg writes `&&(30)` for `&` then `&(30)`: the second module keeps its parameter. */
static void andand_with_parameter(void **state) {
    UnitRun r = unit_run("lsystem T {\n  axiom A\n  A -> F&&(30)F\n}\n", (SylDeriveOptions){.steps = 1, .threads = 1});
    if (r.status != SYL_OK) print_error("F&&(30)F was refused:\n%s", r.diag);
    char *s = unit_string(&r), got[64];
    snprintf(got, sizeof got, "%s", s);
    free(s);
    unit_run_free(&r);
    assert_string_equal(got, "F&&(30)F");
}

static void comments(void **state) {
    const char *text = "# a comment line\n"
                       "lsystem T { # after the brace\n"
                       "  /* a block comment\n"
                       "     over lines, with -> and ( inside */\n"
                       "  axiom A /* inline */ B # trailing\n"
                       "  A -> X # A -> Y\n"
                       "}\n";
    Parsed *ps = parse(text);
    assert_int_equal(ps->errors, 0);
    assert_int_equal(ps->ast.nmodels, 1);
    assert_int_equal(ps->ast.models[0].n, 2);
    const Stmt *ax = stmt_of(ps, ST_AXIOM, 0);
    assert_int_equal(ax->loc.first_line, 5); /* lines inside the block comment still count */
    assert_int_equal(ax->items.n, 2);
    const Stmt *rule = stmt_of(ps, ST_RULE, 0);
    assert_int_equal(rule->loc.first_line, 6);
    assert_int_equal(rule->rule.succ.n, 1);
    parsed_free(ps);
    assert_derives(text, 1, "XB");
}

static void unterminated_comment(void **state) {
    Parsed *ps = parse("lsystem T {\n  axiom A /* never closed\n}\n");
    assert_true(ps->errors >= 1);
    assert_contains(ps->diag, "test.syl:2:11: error: unterminated comment");
    parsed_free(ps);
}

static void no_final_newline(void **state) {
    Parsed *ps = parse("lsystem T {\n  axiom A\n  A -> B\n}");
    assert_int_equal(ps->errors, 0);
    assert_int_equal(ps->ast.models[0].n, 2);
    parsed_free(ps);
    ps = parse("lsystem T {\n  axiom A\n}\nconst k = 2"); /* a statement on the last line */
    assert_int_equal(ps->errors, 0);
    assert_int_equal(ps->ast.top.n, 1);
    assert_string_equal(ps->ast.top.v[0].name, "k");
    parsed_free(ps);
    ps = parse("lsystem T {\n  axiom A # comment at the end");
    assert_int_equal(ps->errors, 1); /* the model is not closed */
    parsed_free(ps);
    assert_derives("lsystem T {\n  axiom A\n  A -> B\n}", 1, "B");
}

static void expressions_span_lines_in_parentheses(void **state) {
    const char *text = "lsystem T {\n"
                       "  axiom A((1 +\n"
                       "          2) *\n"
                       "         3,\n"
                       "         4)\n"
                       "  A(x, y) -> B(x +\n"
                       "               y)\n"
                       "}\n";
    Parsed *ps = parse(text);
    assert_int_equal(ps->errors, 0);
    assert_int_equal(ps->ast.models[0].n, 2);
    const Stmt *ax = stmt_of(ps, ST_AXIOM, 0);
    assert_int_equal(ax->items.n, 1);
    assert_int_equal(ax->items.v[0].args.n, 2);
    const Stmt *rule = stmt_of(ps, ST_RULE, 0);
    assert_int_equal(rule->loc.first_line, 6);
    parsed_free(ps);
    assert_derives(text, 0, "A(9,4)");
    assert_derives(text, 1, "B(13)");
}

static void numbers(void **state) {
    assert_true(axiom_value("1.") == 1);
    assert_true(axiom_value(".5") == 0.5);
    assert_true(axiom_value("1e3") == 1000);
    assert_true(axiom_value("2.5e+1") == 25);
    assert_true(axiom_value("1E-2") == 0.01);
    assert_true(axiom_value("007") == 7);
}

static void precedence(void **state) {
    assert_true(axiom_value("-2^2") == -4);
    assert_true(axiom_value("2^3^2") == 512);
    assert_true(axiom_value("1+2*3") == 7);
    assert_true(axiom_value("(1+2)*3") == 9);
    assert_true(axiom_value("10-4-3") == 3);
    assert_true(axiom_value("64/4/2") == 8);
    assert_true(axiom_value("2*3%4") == 2);
    assert_true(axiom_value("(-3)^2") == 9);
    assert_true(axiom_value("2^-1") == 0.5);
    assert_true(axiom_value("!0+1") == 2);
    assert_true(axiom_value("1 || 0 && 0") == 1);
    assert_true(axiom_value("1 < 2 == 1") == 1);
    assert_true(axiom_value("1 + 1 < 3") == 1);
    assert_true(axiom_value("0 ? 1 : 0 ? 2 : 3") == 3);
    assert_true(axiom_value("1 ? 0 ? 4 : 5 : 6") == 5);
    assert_true(axiom_value("0 && 1 ? 7 : 8") == 8);
}

/* ---- errors ---- */

static void syntax_errors_are_counted_and_located(void **state) {
    Parsed *ps = parse("lsystem T {\n"
                       "  axiom A\n"
                       "  A -> B )\n"
                       "  C -> D\n"
                       "  A => E\n"
                       "  axiom A(1 2)\n"
                       "}\n");
    assert_int_equal(ps->errors, 3);
    assert_int_equal(unit_occurrences(ps->diag, ": error:"), 3);
    assert_contains(ps->diag, "test.syl:3:10: error:");
    assert_contains(ps->diag, "unexpected ')'");
    assert_contains(ps->diag, "test.syl:5:5: error:");
    assert_contains(ps->diag, "test.syl:6:13: error:");
    /* the good lines between the bad ones are kept */
    assert_int_equal(ps->ast.nmodels, 1);
    assert_non_null(stmt_of(ps, ST_RULE, 0));
    assert_int_equal(stmt_of(ps, ST_RULE, 0)->loc.first_line, 4);
    /* the source line and a caret follow the message */
    assert_contains(ps->diag, "    5 |   A => E\n      |     ^");
    parsed_free(ps);
}

static void bad_characters(void **state) {
    Parsed *ps = parse("lsystem T {\n  axiom A\n  A -> `B\n  B -> \x01" "C\n}\n");
    assert_int_equal(ps->errors, 2);
    assert_contains(ps->diag, "test.syl:3:8: error: unexpected character '`'");
    assert_contains(ps->diag, "test.syl:4:8: error: unexpected byte 0x01");
    parsed_free(ps);
}

static void unclosed_model_and_stray_statement(void **state) {
    Parsed *ps = parse("lsystem T {\n  axiom A\n");
    assert_int_equal(ps->errors, 1);
    assert_contains(ps->diag, "test.syl:2:");
    assert_contains(ps->diag, "unexpected end of file");
    parsed_free(ps);
    ps = parse("axiom A\nlsystem T {\n  axiom B\n}\n");
    assert_int_equal(ps->errors, 1);
    assert_contains(ps->diag, "test.syl:1:1: error:");
    assert_int_equal(ps->ast.nmodels, 1);
    parsed_free(ps);
    int st = -1;
    char *diag = NULL;
    SylProgram *p = unit_compile("lsystem T {\n  axiom A(1 +)\n}\n", &diag, &st);
    assert_null(p);
    assert_int_equal(st, SYL_EMODEL);
    assert_contains(diag, "test.syl:2:14: error:");
    free(diag);
}

static void empty_file(void **state) {
    Parsed *ps = parse("");
    assert_int_equal(ps->errors, 0);
    assert_int_equal(ps->ast.nmodels, 0);
    assert_int_equal(ps->ast.top.n, 0);
    parsed_free(ps);
    int st = -1;
    char *diag = NULL;
    assert_null(unit_compile("# nothing here\n", &diag, &st));
    assert_int_equal(st, SYL_EMODEL);
    assert_contains(diag, "holds no lsystem");
    free(diag);
}

/* diag_quote: what a message may quote of the user's text. Printable ASCII and visible
 * UTF-8 stay; C0 controls are ^X, DEL ^?, C1 controls and invisible characters <U+XXXX>,
 * bytes that start no UTF-8 character (a lone continuation, an overlong form, a surrogate)
 * \xHH; and it is cut to fit, never in the middle of an escape. */
static void quoting_escapes_controls(void **state) {
    (void)state;
    char b[64];
    struct { const char *in; size_t n; const char *out; } cases[] = {
        {"F(x)", 4, "F(x)"},
        {"\x1b[31m", 5, "^[[31m"},
        {"a\0b", 3, "a^@b"},
        {"\t\n\x7f", 3, "^I^J^?"},
        {"\xc3\xa9", 2, "\xc3\xa9"},                /* é */
        {"\xc2\x9b", 2, "<U+009B>"},                /* CSI, a C1 control */
        {"\xef\xbb\xbf", 3, "<U+FEFF>"},            /* byte order mark */
        {"\xe2\x80\xae", 3, "<U+202E>"},            /* right-to-left override */
        {"\x80", 1, "\\x80"},                        /* a lone continuation byte */
        {"\xc0\xaf", 2, "\\xc0\\xaf"},              /* overlong '/' */
        {"\xed\xa0\x80", 3, "\\xed\\xa0\\x80"},     /* a surrogate */
        {"\xf0\x9f\x8c\xb3", 4, "\xf0\x9f\x8c\xb3"}, /* a tree, beyond the BMP */
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++)
        assert_string_equal(diag_quote(b, sizeof b, cases[i].in, cases[i].n), cases[i].out);
    assert_string_equal(diag_quote(b, 6, "ab\x1b\x1b", 4), "ab^[");
}

/* The line printer: the escaped line, and the caret padded as wide as what was shown
 * before it (a tab stays a tab); the message's own text is escaped too. */
static void caret_after_escapes(void **state) {
    (void)state;
    const char *text = "x\t\x1b\xc2\x9bY\n";
    Source src = {.path = "p\x1b.syl", .text = text, .len = strlen(text)};
    char *out = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&out, &len);
    Diag d = {.out = mem, .src = &src};
    diag_error(&d, ((SylLoc){1, 6, 1, 6}), "name '%s'", "a\x07");
    fclose(mem);
    assert_string_equal(out, "p^[.syl:1:6: error: name 'a^G'\n"
                             "    1 | x\t^[<U+009B>Y\n"
                             "      |  \t          ^\n");
    free(out);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(statement_kinds_and_counts),
        cmocka_unit_test(axiom_items_split),
        cmocka_unit_test(words_split_into_modules),
        cmocka_unit_test(arrows_are_equivalent),
        cmocka_unit_test(andand_in_successor_is_two_modules),
        cmocka_unit_test(andand_with_parameter),
        cmocka_unit_test(comments),
        cmocka_unit_test(unterminated_comment),
        cmocka_unit_test(no_final_newline),
        cmocka_unit_test(expressions_span_lines_in_parentheses),
        cmocka_unit_test(numbers),
        cmocka_unit_test(precedence),
        cmocka_unit_test(syntax_errors_are_counted_and_located),
        cmocka_unit_test(bad_characters),
        cmocka_unit_test(unclosed_model_and_stray_statement),
        cmocka_unit_test(empty_file),
        cmocka_unit_test(quoting_escapes_controls),
        cmocka_unit_test(caret_after_escapes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
