/* The command line's tables (cli/options.h): every option a command's --help names parses,
 * every option it takes is in its --help and sets something, and docs/cli.md's option tables
 * list what the commands take. Links the CLI's objects but its main. */
#include <ctype.h>
#include <getopt.h>

#include "unit.h"
#include "cli/cli.h"

const OutHooks cli_temp_hooks = {NULL, NULL, NULL}; /* main.c's, which is not linked */

/* Every command, `sylva FILE` too. */
static const CliCommand *command(int i) {
    int n = 0;
    while (cli_commands[n]) n++;
    return i < n ? cli_commands[i] : i == n ? &cli_plant_command : NULL;
}

static char *help_of(const CliCommand *cmd) {
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    cli_help(cmd, f);
    fclose(f);
    return text;
}

/* Whether text holds word as a whole token ("--set" in "--set NAME", not in "--settings"). */
static bool has_token(const char *text, const char *word) {
    size_t n = strlen(word);
    for (const char *p = strstr(text, word); p; p = strstr(p + 1, word)) {
        bool before = p == text || !(isalnum((unsigned char)p[-1]) || p[-1] == '-');
        bool after = !(isalnum((unsigned char)p[n]) || p[n] == '-');
        if (before && after) return true;
    }
    return false;
}

/* The option cmd takes as --name or -x (name a letter), or CLI_OPT_NONE. */
static CliOptionId taken(const CliCommand *cmd, const char *name, size_t len) {
    for (int id = 1; id < CLI_OPT_COUNT; id++) {
        const CliOption *o = &cli_options[id];
        if (!cli_takes(cmd, (CliOptionId)id)) continue;
        if (len == 1 ? o->letter == name[0] : strlen(o->name) == len && !strncmp(o->name, name, len)) return id;
    }
    return CLI_OPT_NONE;
}

/* A value the option accepts, that differs from a zeroed default. */
static const char *example(const CliOption *o, char *buf, size_t n) {
    static const struct { const char *arg, *value; } reads[] = {
        {"S", "1"}, {"NAME=VALUE", "k=1"}, {"V", "top"}, {"WxH", "8x8"},
        {"csv|json", "json"}, {"model|pipe[:EXP]", "pipe:3"}, {"N", "1"},
        {"LO,HI", "0,1"}, {"Y1,Y2,..", "10,20"}, {"NxM", "3x2"}, {"MODE", "cards"}, {"NAME", "maple"},
        {"X,Z", "1,1"}, {"CAMERA", "walker"}, {"DIR", "."}, {"WHICH", "zamuda"},
    };
    switch (o->kind) {
    case CLI_FLAG:
    case CLI_CHOICE: return NULL;
    case CLI_TEXT: return "x";
    case CLI_SIZE: return "1M";
    case CLI_INT:
    case CLI_COUNT:
    case CLI_REAL: snprintf(buf, n, "%.17g", o->max); return buf;
    case CLI_READ:
        for (size_t i = 0; i < sizeof reads / sizeof *reads; i++)
            if (!strcmp(reads[i].arg, o->arg)) return reads[i].value;
    }
    fail_msg("no example value for --%s", o->name);
    return NULL;
}

typedef struct Parsed {
    ModelArgs m;
    SylDeriveOptions d;
    SylMeshOptions mo;
    SylRenderOptions ro;
    CliArgs a;
} Parsed;

static void zero(Parsed *p) {
    memset(p, 0, sizeof *p);
    p->a = (CliArgs){.m = &p->m, .d = &p->d, .mo = &p->mo, .ro = &p->ro};
}

static bool changed(const Parsed *before, const Parsed *after) {
    CliArgs a = after->a, b = before->a; /* the plain values, files aside */
    a.files = b.files = NULL;
    a.nfiles = b.nfiles = 0;
    return memcmp(&before->m, &after->m, sizeof before->m) || memcmp(&before->d, &after->d, sizeof before->d) ||
           memcmp(&before->mo, &after->mo, sizeof before->mo) || memcmp(&before->ro, &after->ro, sizeof before->ro) ||
           memcmp(&a, &b, sizeof a);
}

/* sylva CMD OPTION [VALUE] model.syl: runs, and sets something. */
static void parses(const CliCommand *cmd, const char *option, const char *value) {
    char name[64], opt[64], val[64], file[] = "model.syl";
    snprintf(name, sizeof name, "sylva %s", cmd->name);
    snprintf(opt, sizeof opt, "%s", option);
    snprintf(val, sizeof val, "%s", value ? value : "");
    char *argv[] = {name, opt, value ? val : file, file, NULL};
    int argc = value ? 4 : 3;
    Parsed before, p;
    zero(&before);
    zero(&p);
    int done = cli_parse(cmd, argc, argv, &p.a);
    if (done != CLI_RUN) fail_msg("sylva %s %s %s: exit %d", cmd->name, option, value ? value : "", done);
    if (!changed(&before, &p)) fail_msg("sylva %s %s %s changes nothing", cmd->name, option, value ? value : "");
    assert_int_equal(p.a.nfiles, 1);
    assert_string_equal(p.a.files[0], "model.syl");
}

/* Every option a command takes is in its --help (a row, or the usage line) and parses. */
static void every_option_taken_is_listed_and_parses(void **state) {
    (void)state;
    for (int i = 0; command(i); i++) {
        const CliCommand *cmd = command(i);
        char *help = help_of(cmd);
        int n = 0;
        for (int id = 1; id < CLI_OPT_COUNT; id++) {
            if (!cli_takes(cmd, (CliOptionId)id)) continue;
            const CliOption *o = &cli_options[id];
            char word[64], buf[64];
            snprintf(word, sizeof word, "--%s", o->name);
            if (!has_token(help, word)) fail_msg("sylva %s takes %s; its --help does not name it", cmd->name, word);
            parses(cmd, word, example(o, buf, sizeof buf));
            if (o->letter) {
                snprintf(word, sizeof word, "-%c", o->letter);
                if (!has_token(help, word)) fail_msg("sylva %s takes %s; its --help does not name it", cmd->name, word);
                parses(cmd, word, example(o, buf, sizeof buf));
            }
            n++;
        }
        assert_true(n > 0);
        free(help);
    }
}

/* Every -x and --name in a command's --help is an option it takes. */
static void every_option_listed_is_taken(void **state) {
    (void)state;
    for (int i = 0; command(i); i++) {
        const CliCommand *cmd = command(i);
        char *help = help_of(cmd);
        for (const char *p = help; *p; p++) {
            if (*p != '-' || (p > help && !strchr(" ([|`", p[-1]))) continue;
            size_t dashes = p[1] == '-' ? 2 : 1, len = 0;
            while (islower((unsigned char)p[dashes + len]) || (len && p[dashes + len] == '-')) len++;
            if (!len || (dashes == 1 && len != 1)) continue; /* "- is standard output", "-Z" */
            if (dashes == 2 && len == 4 && !strncmp(p + 2, "help", 4)) continue;
            if (!taken(cmd, p + dashes, len))
                fail_msg("sylva %s --help names %.*s, which it does not take", cmd->name, (int)(dashes + len), p);
        }
        free(help);
    }
}

/* getopt_long's answers to what the old hand-written loops handled: --help anywhere before
 * a bad value, a bad value before --help, an unknown option, an abbreviation. */
static void parser_answers_like_getopt(void **state) {
    (void)state;
    char n0[] = "sylva derive", h[] = "--help", j[] = "-j", zero_[] = "0", f[] = "m.syl", ab[] = "--interp";
    Parsed p;
    zero(&p);
    FILE *saved = stdout;
    stdout = fopen("/dev/null", "w"); /* --help's text */
    char *a1[] = {n0, h, j, zero_, NULL};
    assert_int_equal(cli_parse(&cli_derive_command, 4, a1, &p.a), SYL_OK);
    fclose(stdout);
    stdout = saved;
    FILE *err = stderr;
    stderr = fopen("/dev/null", "w");
    char *a2[] = {n0, j, zero_, h, NULL};
    assert_int_equal(cli_parse(&cli_derive_command, 4, a2, &p.a), SYL_EUSAGE);
    char *a3[] = {n0, f, f, NULL}; /* one model only */
    assert_int_equal(cli_parse(&cli_derive_command, 3, a3, &p.a), SYL_EUSAGE);
    fclose(stderr);
    stderr = err;
    char *a4[] = {n0, ab, f, NULL};
    assert_int_equal(cli_parse(&cli_derive_command, 3, a4, &p.a), CLI_RUN);
    assert_true(p.a.interpret);
}

/* The options in the first column of a table of docs/cli.md's section `heading`. */
static int doc_table(const char *heading, char names[][32], int max) {
    FILE *f = fopen("docs/cli.md", "r");
    if (!f) fail_msg("cannot read docs/cli.md (run from the project's root)");
    char line[1024];
    bool in = false;
    int n = 0;
    while (fgets(line, sizeof line, f)) {
        if (!strncmp(line, "#", 1)) in = strstr(line, heading) && line[strspn(line, "#")] == ' ';
        if (!in || strncmp(line, "| `", 3)) continue;
        char *end = strchr(line + 1, '|');
        for (char *p = line + 1; p && p < end; p = strchr(p + 1, '`')) {
            if (p[0] != '`' || p[1] != '-') continue;
            size_t len = strcspn(p + 1, " `=");
            if (n < max) snprintf(names[n++], 32, "%.*s", (int)len, p + 1);
            p = strchr(p + 1, '`');
            if (!p) break;
        }
    }
    fclose(f);
    return n;
}

static bool in_group(const CliUse *g, CliOptionId id) {
    for (; g->option || g->group; g++)
        if (g->option == id || (g->group && in_group(g->group, id))) return true;
    return false;
}

/* docs/cli.md's option table of a command names what it takes (but, with skip, that group). */
static void doc_lists(const char *heading, const CliCommand *cmd, const CliUse *skip) {
    char names[64][32];
    int n = doc_table(heading, names, 64);
    assert_true(n > 0);
    for (int i = 0; i < n; i++) {
        const char *w = names[i] + (names[i][1] == '-' ? 2 : 1);
        if (!taken(cmd, w, strlen(w)))
            fail_msg("docs/cli.md, %s: %s is not an option of sylva %s", heading, names[i], cmd->name);
    }
    for (int id = 1; id < CLI_OPT_COUNT; id++) {
        if (!cli_takes(cmd, (CliOptionId)id) || (skip && in_group(skip, (CliOptionId)id))) continue;
        bool found = false;
        for (int i = 0; i < n && !found; i++)
            found = names[i][1] == '-' ? !strcmp(names[i] + 2, cli_options[id].name)
                                       : names[i][1] == cli_options[id].letter && !names[i][2];
        if (!found)
            fail_msg("docs/cli.md, %s: no row for --%s of sylva %s", heading, cli_options[id].name, cmd->name);
    }
}

static void docs_tables_match_the_commands(void **state) {
    (void)state;
    doc_lists("`sylva derive`", &cli_derive_command, NULL);
    doc_lists("`sylva render`", &cli_render_command, cli_derive_uses);
    /* the resource limits: what derive takes of them, and grow's too */
    char names[16][32];
    int n = doc_table("Resource limits", names, 16);
    assert_int_equal(n, 5);
    for (int i = 0; i < n; i++) {
        const char *w = names[i] + 2;
        assert_true(taken(&cli_grow_command, w, strlen(w)));
        CliOptionId id = taken(&cli_grow_command, w, strlen(w));
        assert_true(in_group(cli_limits, id) || in_group(cli_grow_limits, id));
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_option_taken_is_listed_and_parses),
        cmocka_unit_test(every_option_listed_is_taken),
        cmocka_unit_test(parser_answers_like_getopt),
        cmocka_unit_test(docs_tables_match_the_commands),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
