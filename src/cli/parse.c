/* The one option parser of `sylva`: getopt_long built from a command's table, and its --help. */
#include <getopt.h>
#include <stdint.h>
#include <string.h>

#include "cli/cli.h"
#include "util/budget.h"

/* A command's options flattened: row[i] the i-th row of its --help. */
typedef struct Rows {
    CliOptionId id[CLI_OPT_COUNT];
    const char *help[CLI_OPT_COUNT];
    int n;
} Rows;

static void flatten(const CliUse *u, Rows *r) {
    for (; u->option || u->group; u++) {
        if (u->group) flatten(u->group, r);
        else if (r->n < CLI_OPT_COUNT) {
            r->id[r->n] = u->option;
            r->help[r->n++] = u->help ? u->help : cli_options[u->option].help;
        }
    }
}

bool cli_takes(const CliCommand *cmd, CliOptionId id) {
    Rows r = {0};
    flatten(cmd->options, &r);
    for (int i = 0; i < r.n; i++)
        if (r.id[i] == id) return true;
    return false;
}

/* "  -o, --output FILE     text", further lines of the text under its first. */
static void print_row(FILE *out, const CliOption *o, const char *help, int width) {
    char left[64], letter[8] = "";
    if (o->letter) snprintf(letter, sizeof letter, "-%c, ", o->letter);
    snprintf(left, sizeof left, "%s--%s%s%s", letter, o->name, o->arg ? " " : "", o->arg ? o->arg : "");
    if ((int)strlen(left) < width) fprintf(out, "  %-*s", width, left);
    else fprintf(out, "  %s\n%*s", left, width + 2, "");
    for (const char *line = help;;) {
        const char *end = strchr(line, '\n');
        if (!end) {
            fprintf(out, "%s\n", line);
            break;
        }
        fprintf(out, "%.*s\n%*s", (int)(end - line), line, width + 2, "");
        line = end + 1;
    }
    if (o == &cli_options[CLI_OPT_MAX_MEMORY]) { /* the default here, and what set it */
        const char *why;
        uint64_t d = budget_default_why(&why);
        fprintf(out, "%*shere %.1fM, set by %s\n", width + 2, "", (double)d / (1 << 20), why);
    }
}

void cli_help(const CliCommand *cmd, FILE *out) {
    fprintf(out, "usage: %s\n\n%s", cmd->usage, cmd->about);
    Rows r = {0};
    flatten(cmd->options, &r);
    bool first = true;
    for (int i = 0; i < r.n; i++) {
        if (!*r.help[i]) continue; /* the usage line names it */
        if (first) fputc('\n', out);
        first = false;
        print_row(out, &cli_options[r.id[i]], r.help[i], cmd->width ? cmd->width : 22);
    }
    if (cmd->epilogue) fputs(cmd->epilogue, out);
    if (cmd->more) cmd->more(out);
}

static void *target(CliArgs *a, CliTarget in) {
    switch (in) {
    case CLI_IN_MODEL: return a->m;
    case CLI_IN_DERIVE: return a->d;
    case CLI_IN_MESH: return a->mo;
    case CLI_IN_RENDER: return a->ro;
    default: return a;
    }
}

bool cli_apply(CliOptionId id, char *arg, CliArgs *a) {
    const CliOption *o = &cli_options[id];
    char name[32]; /* as messages name it: -n when it has a letter, else --name */
    if (o->letter) snprintf(name, sizeof name, "-%c", o->letter);
    else snprintf(name, sizeof name, "--%s", o->name);
    char *at = (char *)target(a, o->in) + o->at;
    double v;
    unsigned long long size;
    switch (o->kind) {
    case CLI_FLAG: *(bool *)at = true; return true;
    case CLI_CHOICE: *(int *)at = o->value; return true;
    case CLI_TEXT: *(const char **)at = arg; return true;
    case CLI_INT:
        if (!cli_integer(name, arg, o->min, o->max, &v)) return false;
        *(int *)at = (int)v;
        return true;
    case CLI_COUNT:
        if (!cli_integer(name, arg, o->min, o->max, &v)) return false;
        *(uint64_t *)at = (uint64_t)v;
        return true;
    case CLI_REAL:
        if (!cli_number(name, arg, o->min, o->max, &v)) return false;
        *(float *)at = (float)v;
        return true;
    case CLI_SIZE:
        if (!cli_size(name, arg, &size)) return false;
        *(uint64_t *)at = size;
        return true;
    case CLI_READ: return o->read(a, arg);
    }
    return false;
}

enum { HELP = 'h', LONG = 256 }; /* getopt's answer for a long option: LONG + its id */

int cli_parse(const CliCommand *cmd, int argc, char **argv, CliArgs *a) {
    Rows r = {0};
    flatten(cmd->options, &r);
    bool takes[CLI_OPT_COUNT] = {0};
    for (int i = 0; i < r.n; i++) takes[r.id[i]] = true;
    /* In the order of cli_options (getopt lists an ambiguous abbreviation's options so),
     * --help last. */
    struct option longs[CLI_OPT_COUNT + 1];
    char shorts[2 * CLI_OPT_COUNT + 2];
    int nl = 0, ns = 0;
    for (int id = 1; id < CLI_OPT_COUNT; id++) {
        if (!takes[id]) continue;
        const CliOption *o = &cli_options[id];
        longs[nl++] = (struct option){o->name, o->arg ? required_argument : no_argument, NULL, LONG + id};
        if (o->letter) {
            shorts[ns++] = o->letter;
            if (o->arg) shorts[ns++] = ':';
        }
    }
    longs[nl++] = (struct option){"help", no_argument, NULL, HELP};
    longs[nl] = (struct option){0, 0, 0, 0};
    shorts[ns++] = HELP;
    shorts[ns] = 0;
    int c;
    optind = 0; /* glibc: start afresh, forgetting where the last parse stopped inside "-abc" */
    while ((c = getopt_long(argc, argv, shorts, longs, NULL)) != -1) {
        int id = c >= LONG ? c - LONG : 0;
        for (int i = 1; !id && c != HELP && c != '?' && i < CLI_OPT_COUNT; i++)
            if (takes[i] && cli_options[i].letter == c) id = i;
        if (c == HELP) {
            cli_help(cmd, stdout);
            return SYL_OK;
        }
        if (!id) { /* getopt said why */
            cli_help(cmd, stderr);
            return SYL_EUSAGE;
        }
        if (!cli_apply((CliOptionId)id, optarg, a)) return SYL_EUSAGE;
    }
    int n = argc - optind;
    if (n < 1 || (!cmd->several && n != 1)) {
        if (cmd->args_error) fprintf(stderr, "sylva %s: %s\n", cmd->name, cmd->args_error);
        cli_help(cmd, stderr);
        return SYL_EUSAGE;
    }
    a->files = argv + optind;
    a->nfiles = n;
    return CLI_RUN;
}
