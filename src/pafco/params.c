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

/* Where each row's value lives in PafcoParams (params.def's order, the schema's). */
static const size_t offsets[] = {
#define PF(f, ...) offsetof(PafcoParams, f),
#include "pafco/params.def"
};
_Static_assert(sizeof offsets / sizeof *offsets == PAFCO_NPARAMS, "Pafčo's appendix lists 42 parameters");

static int row_index(const SchRow *r) { return (int)(r - sch_pafco.rows); }

/* A number into its field by the row's type (false: out of range, why says so). */
static bool store_number(PafcoParams *P, const SchRow *r, double v, char *why, size_t size) {
    if (r->type == SCH_BOOLEAN) {
        if (v != 0 && v != 1) {
            snprintf(why, size, "takes true or false (or 1 or 0), not %g", v);
            return false;
        }
    } else if (!sch_value_ok(r, v, why, size)) {
        return false;
    }
    char *at = (char *)P + offsets[row_index(r)];
    if (r->type == SCH_BOOLEAN) *(bool *)at = v != 0;
    else if (r->type == SCH_INTEGER) *(int *)at = (int)v;
    else *(double *)at = v;
    return true;
}

void pafco_defaults(PafcoParams *P) {
    memset(P, 0, sizeof *P);
    char why[160];
    for (int i = 0; i < sch_pafco.n; i++)
        if (!isnan(sch_pafco.rows[i].def[0])) store_number(P, &sch_pafco.rows[i], sch_pafco.rows[i].def[0], why, sizeof why);
    P->gen[0] = true;
}

typedef struct Reader {
    const SylProgram *p;
    FILE *diag;
    bool lenient; /* a Pafčo file: bad values fall back with a warning */
    int errors, set_errors, warnings;
} Reader;

static bool is_word(const SylDirArg *a) { return a->kind == SYL_DARG_WORD || a->kind == SYL_DARG_STRING; }

/* One value's problem: an error in a block, a warning (default kept) in a Pafčo file. */
#define BAD(r, d, a, ...)                                                                                  \
    do {                                                                                                   \
        if ((r)->lenient) {                                                                                \
            const SylDirArg *a_ = (a);                                                                     \
            program_warning((r)->p, (r)->diag, a_ ? a_->line : (d)->line, a_ ? a_->col : (d)->col, __VA_ARGS__); \
            (r)->warnings++;                                                                               \
        } else {                                                                                           \
            syl_directive_error((r)->p, (r)->diag, (d), (a), __VA_ARGS__);                                 \
            (r)->errors++;                                                                                 \
        }                                                                                                  \
    } while (0)

static const char *fallback(const Reader *r) { return r->lenient ? "; its default is kept" : ""; }

static void read_value(Reader *r, const SylDirective *d, const SchRow *row, PafcoParams *P) {
    char *at = (char *)P + offsets[row_index(row)];
    if (row->type == SCH_FILE) {
        if (d->nargs > 1 && d->args[1].kind == SYL_DARG_WORD && !strcmp(d->args[1].text, "tile")) {
            BAD(r, d, &d->args[1], "%s's tiles are H_TEX_MUL and V_TEX_MUL in a pafco block, not `tile U V`%s",
                d->name, fallback(r));
            return;
        }
        if (d->nargs != 1 || !is_word(&d->args[0]) || strlen(d->args[0].text) >= PAFCO_PATH) {
            BAD(r, d, d->nargs ? &d->args[0] : NULL, "%s takes one file name (shorter than %d characters)%s",
                row->name, PAFCO_PATH, fallback(r));
            return;
        }
        snprintf(at, PAFCO_PATH, "%s", d->args[0].text);
        return;
    }
    if (row->type == SCH_LIST) { /* TEX_SUBORY: file names */
        if (d->nargs < 1 || d->nargs > PAFCO_MAX_TEX) {
            BAD(r, d, d->nargs ? &d->args[PAFCO_MAX_TEX] : NULL, "%s takes 1 to %d file names%s", row->name,
                PAFCO_MAX_TEX, fallback(r));
            return;
        }
        for (int i = 0; i < d->nargs; i++)
            if (!is_word(&d->args[i]) || strlen(d->args[i].text) >= PAFCO_PATH) {
                BAD(r, d, &d->args[i], "%s takes file names (shorter than %d characters)%s", row->name, PAFCO_PATH,
                    fallback(r));
                return;
            }
        for (int i = 0; i < d->nargs; i++) snprintf(P->tex_files[i], PAFCO_PATH, "%s", d->args[i].text);
        P->ntex = d->nargs;
        return;
    }
    double v;
    const SylDirArg *a = d->nargs ? &d->args[0] : NULL;
    if (d->nargs != 1) {
        BAD(r, d, d->nargs > 1 ? &d->args[1] : NULL, "%s takes one value%s", row->name, fallback(r));
        return;
    }
    if (row->type == SCH_BOOLEAN && is_word(a)) {
        if (!strcasecmp(a->text, "true")) v = 1;
        else if (!strcasecmp(a->text, "false")) v = 0;
        else {
            BAD(r, d, a, "%s takes true or false, not '%s'%s", row->name, a->text, fallback(r));
            return;
        }
    } else if (!sch_number(a, &v)) {
        BAD(r, d, a, "%s takes %s%s", row->name, row->type == SCH_BOOLEAN ? "true or false" : "a number", fallback(r));
        return;
    }
    char why[160];
    if (!store_number(P, row, v, why, sizeof why)) BAD(r, d, a, "%s %s%s", row->name, why, fallback(r));
}

static bool is_param(const SylProgram *p, const char *name) {
    for (int i = 0; i < p->nparams; i++)
        if (!strcmp(p->params[i].name, name)) return true;
    return false;
}

static void apply_set(Reader *r, PafcoParams *P, const char *typed, const char *name, double v) {
    int level;
    const SchRow *row = sch_find(&sch_pafco, name, &level);
    if (!row && r->p->sibling) return; /* meant for another model of the file */
    int before = r->errors;
    char why[160];
    if (row && row->type == SCH_BOOLEAN) {
        if (!store_number(P, row, v, why, sizeof why))
            syl_program_error(r->p, r->diag, 0, 0, "--set %s: %s %s", typed, row->name, why), r->errors++;
    } else if (sch_set_check(r->p, r->diag, &sch_pafco, typed, name, v, &row, &level)) {
        r->errors++;
    } else {
        store_number(P, row, v, why, sizeof why);
    }
    r->set_errors += r->errors - before;
}

static int read_all(const SylProgram *p, void *params, FILE *diag, int *set_errors) {
    PafcoParams *P = params;
    size_t len = 0;
    const char *text = syl_program_source(p, &len);
    Reader r = {.p = p, .diag = diag, .lenient = text && lang_pafco_cfg_detect(text, len)};
    pafco_defaults(P);
    sch_count_read(p);
    int n = 0;
    const SylDirective *dirs = syl_program_directives(p, &n);
    const SylDirective *seen[PAFCO_NPARAMS] = {0};
    for (int i = 0; i < n; i++) {
        const SylDirective *d = &dirs[i];
        const SchRow *row = sch_find(&sch_pafco, d->name, NULL);
        if (!row) {
            char hint[600];
            sch_suggest(&sch_pafco, d->name, hint, sizeof hint);
            syl_directive_error(p, diag, d, NULL, "Pafčo's generator has no parameter '%s'%s", d->name, hint);
            r.errors++;
            continue;
        }
        int k = row_index(row);
        if (seen[k]) {
            syl_directive_error(p, diag, d, NULL, "%s is given twice (first on line %d)", row->name, seen[k]->line);
            r.errors++;
            continue;
        }
        seen[k] = d;
        read_value(&r, d, row, P);
    }
    if (r.lenient && !r.errors) { /* the thesis: what is missing takes its predefined value */
        char missing[1024] = "";
        int nmissing = 0;
        for (int k = 0; k < PAFCO_NPARAMS; k++) /* the bark and leaf files are optional: none by default */
            if (!seen[k] && sch_pafco.rows[k].type != SCH_FILE && sch_pafco.rows[k].type != SCH_LIST) {
                size_t at = strlen(missing);
                if (nmissing < 8) snprintf(missing + at, sizeof missing - at, "%s%s", nmissing ? ", " : "",
                                           sch_pafco.rows[k].name);
                nmissing++;
            }
        if (nmissing)
            program_warning(p, diag, 0, 0, "%d parameters are not given, their defaults are used: %s%s",
                            nmissing, missing, nmissing > 8 ? ", ..." : "");
    }
    for (int i = 0; i < p->noverrides; i++) {
        const char *name = p->set_local ? p->set_local[i] : NULL;
        if (name && !is_param(p, name)) apply_set(&r, P, p->overrides[i].name, name, p->overrides[i].value);
    }
    *set_errors = r.set_errors;
    return r.errors;
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
    const char *at = (const char *)P + offsets[row_index(row)];
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
