/* Reading a `strands` block: the schema's reader of NAME VALUE lines (lang/schema_lines.c)
 * with params.def's rows. What is strands' own is here: where each value is kept, the
 * per-order rows (`NAME G [weibull W]` or `NAME gravelius G [weibull W]`, G and W numbers or
 * curve names, docs/strands.md), the messages' words, and the lateral's defaults. */
#include "strands/params.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "lang/schema.h"
#include "util/closest.h"

/* Where each row is kept in StrandsParams (params.def's order, the schema's): the globals'
 * numbers, the leaf type; the per-order rows (a number or a curve each factor) are read here. */
#define ST_STORE(f) _Generic(((StrandsParams *)0)->f, int64_t: SCH_AT_I64, uint64_t: SCH_AT_U64, default: SCH_AT_F64)
static const SchSlot slots[] = {
#define ST_G(f, ...) {.store = ST_STORE(f), .off = offsetof(StrandsParams, f)},
#define ST_O(i, ...) {.store = SCH_AT_KIND},
#define ST_X(nm, ty, ...) {.store = (ty) == SCH_ENUM ? SCH_AT_INT : SCH_AT_NONE, .off = offsetof(StrandsParams, leaf_type)},
#include "params.def"
};
enum { NSLOTS = sizeof slots / sizeof *slots };

/* The thesis' symbol of each row (Zamuda's notation), and each per-order row's ranges: of the
 * two factors and of their product (eqs. 3.17-3.22), and its default (a constant Gravelius
 * factor; the Weibull one is 1). */
static const char *const symbols[] = {
#define ST_G(f, nm, sym, ...) sym,
#define ST_O(i, nm, sym, ...) sym,
#include "params.def"
};
enum { NSYMBOLS = sizeof symbols / sizeof *symbols };
static const int first_order = 0
#define ST_G(...) +1
#include "params.def"
    ;

typedef struct OrderDef {
    double glo, ghi, wlo, whi, lo, hi, def;
} OrderDef;

static const OrderDef orders[SP_ORDER_COUNT] = {
#define ST_O(i, nm, sym, glo, ghi, wlo, whi, lo, hi, d, unit, mean) [i] = {glo, ghi, wlo, whi, lo, hi, d},
#include "params.def"
};

static int row_index(const SchRow *row) { return (int)(row - sch_strands.rows); }

static void range_text(const SchRow *row, char *buf, size_t size) {
    if (row->type == SCH_INTEGER) snprintf(buf, size, "a whole number from %.17g to %.17g", row->lo, row->hi);
    else snprintf(buf, size, "a number from %g to %g", row->lo, row->hi);
}

#define LEAF_TYPES "none, stacked, staggered, spiral, bunched or coniferous"

/* The words of strands' messages (the reader's own where none). */
static void say(SchProblem *pr, char *buf, size_t size) {
    const SchRow *row = pr->row;
    int i = row ? row_index(row) : -1;
    const char *sym = i >= 0 && i < NSYMBOLS ? symbols[i] : "";
    char range[96] = "";
    if (row) range_text(row, range, sizeof range);
    bool leaves = row && row->type == SCH_ENUM;
    switch (pr->what) {
    case SCH_BAD_UNKNOWN: snprintf(buf, size, "a strands block has no parameter '%s'%s", pr->name, pr->hint); break;
    case SCH_BAD_COUNT:
    case SCH_BAD_NUMBER:
    case SCH_BAD_WORD:
        if (leaves && pr->what == SCH_BAD_WORD && pr->at->kind == SYL_DARG_WORD) {
            snprintf(buf, size, "no leaf type '%s'%s: " LEAF_TYPES, pr->at->text, pr->hint);
        } else if (leaves) {
            pr->at = pr->d->nargs ? &pr->d->args[0] : NULL;
            snprintf(buf, size, "'%s' takes one of " LEAF_TYPES, pr->name);
        } else
            snprintf(buf, size, "'%s' (%s) takes one value, %s", pr->name, sym, range);
        break;
    case SCH_BAD_RANGE: snprintf(buf, size, "%s (%s) is %g: it must be %s", pr->name, sym, pr->x, range); break;
    case SCH_BAD_SET_RANGE:
        if (i >= first_order) snprintf(buf, size, "--set %s: the Gravelius factor %s^g must be from %g to %g", pr->typed, sym, row->lo, row->hi);
        else snprintf(buf, size, "--set %s: %s (%s) must be %s", pr->typed, pr->name, sym, range);
        break;
    case SCH_BAD_SET_NOT_NUMBER: /* only numbers are set */
        snprintf(buf, size, "--set %s: strands block '%s' has no parameter '%s'%s", pr->typed, pr->block, pr->name, pr->hint);
        break;
    default: break;
    }
}

/* One factor: a number or a curve whose every point lies in [lo, hi]. */
static bool read_factor(SchLineRead *r, const SylDirective *d, const SylDirArg *a, int k, bool weibull,
                        StrandsFactor *f) {
    const OrderDef *o = &orders[k];
    const char *sym = symbols[first_order + k];
    double lo = weibull ? o->wlo : o->glo, hi = weibull ? o->whi : o->ghi, v;
    const char *which = weibull ? "w" : "g";
    if (sch_number(a, &v)) {
        if (!(v >= lo && v <= hi)) {
            sch_lines_error(r, d, a, "%s: the %s factor %s^%s is %g: it must be from %g to %g", d->name,
                            weibull ? "Weibull" : "Gravelius", sym, which, v, lo, hi);
            return false;
        }
        *f = (StrandsFactor){.k = v};
        return true;
    }
    if (a->kind != SYL_DARG_WORD) {
        sch_lines_error(r, d, a, "%s: expected a number or the name of a curve", d->name);
        return false;
    }
    const SylProgram *p = sch_lines_program(r);
    const Curve *c = lang_curve_find(p, a->text);
    if (!c) {
        const char *names[256];
        int n = 0;
        for (int i = 0; i < p->ncurves && n < 256; i++) names[n++] = p->curves[i].name;
        char list[512];
        if (closest_list(a->text, names, n, list, sizeof list) > 0)
            sch_lines_error(r, d, a, "%s: no curve '%s' (did you mean %s?)", d->name, a->text, list);
        else
            sch_lines_error(r, d, a, "%s: no curve '%s'", d->name, a->text);
        return false;
    }
    for (int i = 0; i < c->n; i++)
        if (!(c->y[i] >= lo && c->y[i] <= hi)) {
            sch_lines_error(r, d, a, "%s: curve '%s' is %g at %g: the %s factor %s^%s must be from %g to %g", d->name,
                            c->name, c->y[i], c->x[i], weibull ? "Weibull" : "Gravelius", sym, which, lo, hi);
            return false;
        }
    *f = (StrandsFactor){.curve = c};
    return true;
}

/* A per-order row: `NAME G [weibull W]` or `NAME gravelius G [weibull W]`. */
static int read_order(SchLineRead *r, const SchRow *row, const SylDirective *d, void *base) {
    int k = row_index(row) - first_order, i = 0;
    StrandsOrderParam *out = &((StrandsParams *)base)->order[k], v = *out;
    bool ok = true, any = false;
    if (i < d->nargs && d->args[i].kind == SYL_DARG_WORD && !strcmp(d->args[i].text, "gravelius")) i++;
    if (i < d->nargs && !(d->args[i].kind == SYL_DARG_WORD && !strcmp(d->args[i].text, "weibull"))) {
        ok &= read_factor(r, d, &d->args[i], k, false, &v.g);
        i++, any = true;
    } else if (i > 0) {
        sch_lines_error(r, d, &d->args[i - 1], "%s: 'gravelius' takes a number or a curve", d->name);
        return 0;
    }
    if (ok && i < d->nargs && d->args[i].kind == SYL_DARG_WORD && !strcmp(d->args[i].text, "weibull")) {
        if (i + 1 >= d->nargs) {
            sch_lines_error(r, d, &d->args[i], "%s: 'weibull' takes a number or a curve", d->name);
            return 0;
        }
        ok &= read_factor(r, d, &d->args[i + 1], k, true, &v.w);
        i += 2, any = true;
    }
    if (ok && i < d->nargs) {
        sch_lines_error(r, d, &d->args[i], "%s: unexpected value: write %s G [weibull W], G and W numbers or curves",
                        d->name, d->name);
        return 0;
    }
    if (ok && !any) {
        sch_lines_error(r, d, NULL, "%s (%s) takes a value: %s G [weibull W], G and W numbers or curves", d->name,
                        symbols[row_index(row)], d->name);
        return 0;
    }
    if (ok) *out = v;
    return 0;
}

/* --set NAME=VALUE of a per-order row: its Gravelius factor (in range by then). */
static int set_order(SchLineRead *r, const SchRow *row, const char *typed, double v, void *base) {
    (void)r, (void)typed;
    ((StrandsParams *)base)->order[row_index(row) - first_order].g = (StrandsFactor){.k = v};
    return 0;
}

/* The lateral's bounds and scale are the main one's unless given (Zamuda merges them). */
static int merge_lateral(SchLineRead *r, void *base) {
    StrandsParams *P = base;
    for (int k = 0; k < 3; k++)
        if (!sch_lines_took(r, first_order + SP_LAT_LENGTH_MAX + k)) P->order[SP_LAT_LENGTH_MAX + k] = P->order[SP_LENGTH_MAX + k];
    return 0;
}

static const SchLines strands_lines = {
    .t = &sch_strands,
    .slots = slots,
    .nslots = NSLOTS,
    .textures = true,
    .say = say,
    .line = read_order,
    .set = set_order,
    .done = merge_lateral,
};

static void defaults(StrandsParams *P) {
    memset(P, 0, sizeof *P);
    sch_lines_defaults(&strands_lines, P);
    for (int i = 0; i < SP_ORDER_COUNT; i++)
        P->order[i] = (StrandsOrderParam){.g = {.k = orders[i].def}, .w = {.k = 1}, .lo = orders[i].lo,
                                          .hi = orders[i].hi};
}

static int read_all(const SylProgram *p, void *params, FILE *diag, int *set_errors) {
    defaults(params);
    sch_count_read(p);
    return sch_read_lines(p, &strands_lines, params, diag, set_errors);
}

int strands_params_read(const SylProgram *p, StrandsParams *P, FILE *diag) {
    return sch_read_once(p, P, sizeof *P, read_all, diag);
}

int strands_params_check(const SylProgram *p, FILE *diag) {
    StrandsParams P;
    return sch_check_once(p, &P, sizeof P, read_all, diag);
}

/* The tables, for the docs' check that every parameter is documented. */
int strands_param_names(const char **names, const char **symbols_out, int max) {
    int n = 0;
    for (int i = 0; i < NSYMBOLS && n < max; i++, n++) names[n] = sch_strands.rows[i].name, symbols_out[n] = symbols[i];
    if (n < max) names[n] = "leaves", symbols_out[n] = "l_type", n++;
    return n;
}
