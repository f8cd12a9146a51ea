/* Reading a `pafco` block, or a Pafčo file read into one (lang/pafco_cfg.c): each line one of
 * the 42 parameters of params.def, checked against its row of the schema (lang/schema.h), and
 * --set NAME=VALUE over the numbers and switches. */
#include "pafco/params.h"

#include <math.h>
#include <stdlib.h>
#include <stddef.h>
#include <string.h>
#include <strings.h>

#include "lang/kinds.h"
#include "lang/pafco_cfg.h"
#include "lang/program.h"
#include "lang/schema.h"

/* Where each row's value lives in PafcoParams (params.def's order, the schema's): a number, a
 * whole number, a switch; the bark file and the leaf files are read here (SCH_AT_KIND). */
#define PF_AT_SCH_NUMBER SCH_AT_F64
#define PF_AT_SCH_INTEGER SCH_AT_INT
#define PF_AT_SCH_BOOLEAN SCH_AT_BOOL
#define PF_AT_SCH_FILE SCH_AT_KIND
#define PF_AT_SCH_LIST SCH_AT_KIND
static const SchSlot slots[] = {
#define PF(f, nm, al, ty, ...) {.store = PF_AT_##ty, .off = offsetof(PafcoParams, f)},
#include "pafco/params.def"
};
_Static_assert(sizeof slots / sizeof *slots == PAFCO_NPARAMS, "Pafčo's appendix lists 42 parameters");

static int row_index(const SchRow *r) { return (int)(r - sch_pafco.rows); }

static bool is_word(const SylDirArg *a) { return a->kind == SYL_DARG_WORD || a->kind == SYL_DARG_STRING; }

/* A Pafčo file's bad value is a warning, its default kept. */
static const char *fallback(bool lenient) { return lenient ? "; its default is kept" : ""; }

/* The words of Pafčo's messages (the reader's own where none). */
static void say(SchProblem *pr, char *buf, size_t size) {
    const char *name = pr->row ? pr->row->name : pr->name, *fb = fallback(pr->lenient);
    bool boolean = pr->row && pr->row->type == SCH_BOOLEAN;
    switch (pr->what) {
    case SCH_BAD_UNKNOWN: snprintf(buf, size, "Pafčo's generator has no parameter '%s'%s", pr->name, pr->hint); break;
    case SCH_BAD_TWICE: snprintf(buf, size, "%s is given twice (first on line %d)", name, pr->line); break;
    case SCH_BAD_COUNT: snprintf(buf, size, "%s takes one value%s", name, fb); break;
    case SCH_BAD_WORD: snprintf(buf, size, "%s takes true or false, not '%s'%s", name, pr->at->text, fb); break;
    case SCH_BAD_NUMBER: snprintf(buf, size, "%s takes %s%s", name, boolean ? "true or false" : "a number", fb); break;
    case SCH_BAD_RANGE: snprintf(buf, size, "%s %s%s", name, pr->why, fb); break;
    case SCH_BAD_SET_RANGE:
        if (boolean) snprintf(buf, size, "--set %s: %s %s", pr->typed, name, pr->why);
        break;
    default: break;
    }
}

/* One value's problem: an error in a block, a warning (default kept) in a Pafčo file. */
#define BAD(r, d, a, ...)                                                                                  \
    do {                                                                                                   \
        const SylProgram *p_ = sch_lines_program(r);                                                       \
        if (sch_lines_lenient(r)) {                                                                        \
            const SylDirArg *a_ = (a);                                                                     \
            program_warning(p_, sch_lines_diag(r), a_ ? a_->line : (d)->line, a_ ? a_->col : (d)->col, __VA_ARGS__); \
        } else {                                                                                           \
            sch_lines_error((r), (d), (a), __VA_ARGS__);                                                   \
        }                                                                                                  \
    } while (0)

/* The bark file and the leaf files (TEX_SUBORY); sch_lines_error counts what it reports. */
static int read_files(SchLineRead *r, const SchRow *row, const SylDirective *d, void *base) {
    PafcoParams *P = base;
    const char *fb = fallback(sch_lines_lenient(r));
    if (row->type == SCH_FILE) {
        if (d->nargs > 1 && d->args[1].kind == SYL_DARG_WORD && !strcmp(d->args[1].text, "tile")) {
            BAD(r, d, &d->args[1], "%s's tiles are H_TEX_MUL and V_TEX_MUL in a pafco block, not `tile U V`%s",
                d->name, fb);
        } else if (d->nargs != 1 || !is_word(&d->args[0]) || strlen(d->args[0].text) >= PAFCO_PATH) {
            BAD(r, d, d->nargs ? &d->args[0] : NULL, "%s takes one file name (shorter than %d characters)%s",
                row->name, PAFCO_PATH, fb);
        } else
            snprintf((char *)P + slots[row_index(row)].off, PAFCO_PATH, "%s", d->args[0].text);
        return 0;
    }
    if (d->nargs < 1 || d->nargs > PAFCO_MAX_TEX) {
        BAD(r, d, d->nargs ? &d->args[PAFCO_MAX_TEX] : NULL, "%s takes 1 to %d file names%s", row->name,
            PAFCO_MAX_TEX, fb);
        return 0;
    }
    for (int i = 0; i < d->nargs; i++)
        if (!is_word(&d->args[i]) || strlen(d->args[i].text) >= PAFCO_PATH) {
            BAD(r, d, &d->args[i], "%s takes file names (shorter than %d characters)%s", row->name, PAFCO_PATH, fb);
            return 0;
        }
    for (int i = 0; i < d->nargs; i++) snprintf(P->tex_files[i], PAFCO_PATH, "%s", d->args[i].text);
    P->ntex = d->nargs;
    return 0;
}

/* A Pafčo file: what is missing takes its predefined value (the thesis), said once. */
static int missing(SchLineRead *r, void *base) {
    (void)base;
    if (!sch_lines_lenient(r) || sch_lines_errors(r)) return 0;
    char list[1024] = "";
    int n = 0;
    for (int k = 0; k < PAFCO_NPARAMS; k++) /* the bark and leaf files are optional: none by default */
        if (!sch_lines_given(r, k) && sch_pafco.rows[k].type != SCH_FILE && sch_pafco.rows[k].type != SCH_LIST) {
            size_t at = strlen(list);
            if (n < 8) snprintf(list + at, sizeof list - at, "%s%s", n ? ", " : "", sch_pafco.rows[k].name);
            n++;
        }
    if (n)
        program_warning(sch_lines_program(r), sch_lines_diag(r), 0, 0,
                        "%d parameters are not given, their defaults are used: %s%s", n, list, n > 8 ? ", ..." : "");
    return 0;
}

static bool lenient(const SylProgram *p) {
    size_t len = 0;
    const char *text = syl_program_source(p, &len);
    return text && lang_pafco_cfg_detect(text, len);
}

static const SchLines pafco_lines = {
    .t = &sch_pafco,
    .slots = slots,
    .nslots = PAFCO_NPARAMS,
    .say = say,
    .line = read_files,
    .lines_done = missing,
    .lenient = lenient,
};

void pafco_defaults(PafcoParams *P) {
    memset(P, 0, sizeof *P);
    sch_lines_defaults(&pafco_lines, P);
    P->gen[0] = true;
}

static int read_all(const SylProgram *p, void *params, FILE *diag, int *set_errors) {
    pafco_defaults(params);
    sch_count_read(p);
    return sch_read_lines(p, &pafco_lines, params, diag, set_errors);
}

int pafco_params_read(const SylProgram *p, PafcoParams *P, FILE *diag) {
    return sch_read_once(p, P, sizeof *P, read_all, diag);
}

int pafco_params_check(const SylProgram *p, FILE *diag) {
    PafcoParams P;
    return sch_check_once(p, &P, sizeof P, read_all, diag);
}

int pafco_ring_points(int detail, int generation) {
    static const int t1[3][4] = {{6, 5, 3, 3}, {8, 6, 5, 3}, {12, 8, 6, 5}}; /* Table T.1 */
    if (detail < 1) detail = 1;
    if (detail > 3) detail = 3;
    if (generation < 0) generation = 0;
    if (generation > 3) generation = 3;
    return t1[detail - 1][generation];
}

/* ---- writing (sylva convert) ---- */

/* The shortest of %.15g, %.16g, %.17g that reads back as the same double. */
static void exact(double x, char *buf, size_t size) {
    for (int digits = 15; digits <= 17; digits++) {
        snprintf(buf, size, "%.*g", digits, x);
        if (strtod(buf, NULL) == x) return;
    }
}

static void value_text(const PafcoParams *P, const SchRow *row, char *buf, size_t size, bool cfg) {
    const char *at = (const char *)P + slots[row_index(row)].off;
    if (row->type == SCH_BOOLEAN) snprintf(buf, size, "%s", *(const bool *)at ? "true" : "false");
    else if (row->type == SCH_INTEGER) snprintf(buf, size, "%d", *(const int *)at);
    else if (row->type == SCH_NUMBER) exact(*(const double *)at, buf, size);
    else if (row->type == SCH_FILE) snprintf(buf, size, cfg ? "%s" : "\"%s\"", at);
    else {
        size_t n = 0;
        buf[0] = 0;
        for (int i = 0; i < P->ntex && n < size; i++)
            n += (size_t)snprintf(buf + n, size - n, cfg ? "%s%s" : "%s\"%s\"", i ? " " : "", P->tex_files[i]);
    }
}

static bool skip_row(const PafcoParams *P, const SchRow *row) {
    return (row->type == SCH_FILE && !P->bark_file[0]) || (row->type == SCH_LIST && !P->ntex);
}

int pafco_write_cfg(const PafcoParams *P, FILE *out) {
    char buf[PAFCO_MAX_TEX * (PAFCO_PATH + 3) + 64];
    for (int i = 0; i < sch_pafco.n; i++) {
        if (skip_row(P, &sch_pafco.rows[i])) continue;
        value_text(P, &sch_pafco.rows[i], buf, sizeof buf, true);
        fprintf(out, "%s=%s\n", sch_pafco.rows[i].name, buf);
    }
    return ferror(out) ? SYL_EIO : SYL_OK;
}

int pafco_write_syl(const PafcoParams *P, const char *name, FILE *out) {
    char buf[PAFCO_MAX_TEX * (PAFCO_PATH + 3) + 64];
    fprintf(out, "# Pafčo's generator (docs/pafco.md), written by `sylva convert`\npafco %s {\n", name);
    for (int i = 0; i < sch_pafco.n; i++) {
        if (skip_row(P, &sch_pafco.rows[i])) continue;
        value_text(P, &sch_pafco.rows[i], buf, sizeof buf, false);
        fprintf(out, "    %-16s %s\n", sch_pafco.rows[i].name, buf);
    }
    fputs("}\n", out);
    return ferror(out) ? SYL_EIO : SYL_OK;
}

int pafco_convert(const SylProgram *p, unsigned format, const char *note, FILE *out, FILE *diag) {
    (void)note;
    PafcoParams P;
    if (pafco_params_read(p, &P, diag)) return SYL_EMODEL;
    return format == KC_CFG ? pafco_write_cfg(&P, out) : pafco_write_syl(&P, syl_program_name(p), out);
}
