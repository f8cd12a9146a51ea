/* Reading a `strands` block: one directive a parameter, each checked against its range, the
 * per-order ones as `NAME G [weibull W]` or `NAME gravelius G [weibull W]` where G and W are
 * numbers or curve names (docs/strands.md), and --set NAME=VALUE over the numbers. */
#include "strands/params.h"

#include <math.h>
#include <stdbool.h>
#include <string.h>

#include "lang/schema.h"
#include "lang/textures.h"
#include "util/closest.h"

typedef struct Reader {
    const SylProgram *p;
    FILE *diag;
    int errors, set_errors;
    bool lateral_given[3]; /* lateral_length_max, _min, _scale: given, not the main one's */
} Reader;

/* The global parameters: a number each, in [lo, hi]; whole numbers where integer. */
typedef struct Global {
    const char *name, *symbol;
    double lo, hi, def;
    bool integer;
    size_t off; /* into StrandsParams, a double (or the int64/uint64 for integers) */
} Global;

#define OFF(m) offsetof(StrandsParams, m)
static const Global globals[] = {
#define ST_G(f, nm, sym, integer, lo, hi, d, unit, mean) {nm, sym, lo, hi, d, integer, OFF(f)},
#include "params.def"
};
enum { NGLOBALS = sizeof globals / sizeof *globals };

/* The per-order parameters: the ranges of the two factors and of their product (Zamuda's
 * eqs. 3.17-3.22), and the default (a constant Gravelius factor; the Weibull one is 1). */
typedef struct OrderDef {
    const char *name, *symbol;
    double glo, ghi, wlo, whi, lo, hi, def;
} OrderDef;

static const OrderDef orders[SP_ORDER_COUNT] = {
#define ST_O(i, nm, sym, glo, ghi, wlo, whi, lo, hi, d, unit, mean) [i] = {nm, sym, glo, ghi, wlo, whi, lo, hi, d},
#include "params.def"
};

#define ERR_AT(r, d, a, ...) (syl_directive_error((r)->p, (r)->diag, (d), (a), __VA_ARGS__), (r)->errors++)

#define number_of sch_number

/* " (did you mean 'x'?)" for a name or word the block does not know. */
static void suggest(const char *typed, const char *const *names, int n, char *buf, size_t size) {
    char list[512];
    if (closest_list(typed, names, n, list, sizeof list) > 0) snprintf(buf, size, " (did you mean %s?)", list);
    else buf[0] = 0;
}

static bool store_global(const Global *g, StrandsParams *P, double v) {
    if (!(v >= g->lo && v <= g->hi) || (g->integer && v != floor(v))) return false;
    char *at = (char *)P + g->off;
    if (g->off == OFF(strands)) *(int64_t *)at = (int64_t)v;
    else if (g->off == OFF(seed)) *(uint64_t *)at = (uint64_t)v;
    else *(double *)at = v;
    return true;
}

static void range_text(const Global *g, char *buf, size_t size) {
    if (g->integer) snprintf(buf, size, "a whole number from %.17g to %.17g", g->lo, g->hi);
    else snprintf(buf, size, "a number from %g to %g", g->lo, g->hi);
}

static void read_global(Reader *r, const SylDirective *d, const Global *g, StrandsParams *P) {
    double v;
    char range[96];
    range_text(g, range, sizeof range);
    if (d->nargs != 1 || !number_of(&d->args[0], &v)) {
        ERR_AT(r, d, d->nargs ? &d->args[d->nargs > 1 ? 1 : 0] : NULL, "'%s' (%s) takes one value, %s",
               d->name, g->symbol, range);
        return;
    }
    if (!store_global(g, P, v)) ERR_AT(r, d, &d->args[0], "%s (%s) is %g: it must be %s", d->name, g->symbol, v, range);
}

/* One factor: a number or a curve whose every point lies in [lo, hi]. */
static bool read_factor(Reader *r, const SylDirective *d, const SylDirArg *a, const OrderDef *o, bool weibull,
                        StrandsFactor *f) {
    double lo = weibull ? o->wlo : o->glo, hi = weibull ? o->whi : o->ghi, v;
    const char *which = weibull ? "w" : "g";
    if (number_of(a, &v)) {
        if (!(v >= lo && v <= hi)) {
            ERR_AT(r, d, a, "%s: the %s factor %s^%s is %g: it must be from %g to %g", d->name,
                   weibull ? "Weibull" : "Gravelius", o->symbol, which, v, lo, hi);
            return false;
        }
        *f = (StrandsFactor){.k = v};
        return true;
    }
    if (a->kind != SYL_DARG_WORD) {
        ERR_AT(r, d, a, "%s: expected a number or the name of a curve", d->name);
        return false;
    }
    const Curve *c = lang_curve_find(r->p, a->text);
    if (!c) {
        const char *names[256];
        int n = 0;
        for (int i = 0; i < r->p->ncurves && n < 256; i++) names[n++] = r->p->curves[i].name;
        char hint[600];
        suggest(a->text, names, n, hint, sizeof hint);
        ERR_AT(r, d, a, "%s: no curve '%s'%s", d->name, a->text, hint);
        return false;
    }
    for (int i = 0; i < c->n; i++)
        if (!(c->y[i] >= lo && c->y[i] <= hi)) {
            ERR_AT(r, d, a, "%s: curve '%s' is %g at %g: the %s factor %s^%s must be from %g to %g", d->name, c->name,
                   c->y[i], c->x[i], weibull ? "Weibull" : "Gravelius", o->symbol, which, lo, hi);
            return false;
        }
    *f = (StrandsFactor){.curve = c};
    return true;
}

static void read_order(Reader *r, const SylDirective *d, const OrderDef *o, StrandsOrderParam *out) {
    int i = 0;
    StrandsOrderParam v = *out;
    bool ok = true, any = false;
    if (i < d->nargs && d->args[i].kind == SYL_DARG_WORD && !strcmp(d->args[i].text, "gravelius")) i++;
    if (i < d->nargs && !(d->args[i].kind == SYL_DARG_WORD && !strcmp(d->args[i].text, "weibull"))) {
        ok &= read_factor(r, d, &d->args[i], o, false, &v.g);
        i++, any = true;
    } else if (i > 0) {
        ERR_AT(r, d, &d->args[i - 1], "%s: 'gravelius' takes a number or a curve", d->name);
        return;
    }
    if (ok && i < d->nargs && d->args[i].kind == SYL_DARG_WORD && !strcmp(d->args[i].text, "weibull")) {
        if (i + 1 >= d->nargs) {
            ERR_AT(r, d, &d->args[i], "%s: 'weibull' takes a number or a curve", d->name);
            return;
        }
        ok &= read_factor(r, d, &d->args[i + 1], o, true, &v.w);
        i += 2, any = true;
    }
    if (ok && i < d->nargs) {
        ERR_AT(r, d, &d->args[i], "%s: unexpected value: write %s G [weibull W], G and W numbers or curves", d->name,
               d->name);
        return;
    }
    if (ok && !any) {
        ERR_AT(r, d, NULL, "%s (%s) takes a value: %s G [weibull W], G and W numbers or curves", d->name, o->symbol,
               d->name);
        return;
    }
    if (ok) *out = v;
}

static void read_leaves(Reader *r, const SylDirective *d, StrandsParams *P) {
    if (d->nargs != 1 || d->args[0].kind != SYL_DARG_WORD) {
        ERR_AT(r, d, d->nargs ? &d->args[0] : NULL, "'leaves' takes one of none, stacked, staggered, spiral, bunched "
                                                     "or coniferous");
        return;
    }
    const char *words = sch_find(&sch_strands, "leaves", NULL)->words; /* in LeafType's order */
    int k = sch_word_index(words, d->args[0].text);
    if (k >= 0) {
        P->leaf_type = (LeafType)k;
        return;
    }
    char hint[600];
    sch_suggest_word(words, d->args[0].text, hint, sizeof hint);
    ERR_AT(r, d, &d->args[0], "no leaf type '%s'%s: none, stacked, staggered, spiral, bunched or coniferous",
           d->args[0].text, hint);
}

static bool is_param(const SylProgram *p, const char *name) {
    for (int i = 0; i < p->nparams; i++)
        if (!strcmp(p->params[i].name, name)) return true;
    return false;
}

/* --set NAME=VALUE: a global's number, or a per-order parameter's Gravelius factor. */
static void apply_set(Reader *r, StrandsParams *P, const char *typed, const char *name, double v) {
    int before = r->errors;
    if (!strcmp(name, "lod")) { /* sylva mesh reads it (lang/lod.c) */
        r->errors += lang_lod_set_check(r->p, v, typed, r->diag);
        goto done;
    }
    for (int i = 0; i < NGLOBALS; i++)
        if (!strcmp(name, globals[i].name)) {
            char range[96];
            range_text(&globals[i], range, sizeof range);
            if (!store_global(&globals[i], P, v))
                syl_program_error(r->p, r->diag, 0, 0, "--set %s: %s (%s) must be %s", typed, name, globals[i].symbol,
                                  range),
                    r->errors++;
            goto done;
        }
    for (int i = 0; i < SP_ORDER_COUNT; i++)
        if (!strcmp(name, orders[i].name)) {
            if (!(v >= orders[i].glo && v <= orders[i].ghi))
                syl_program_error(r->p, r->diag, 0, 0, "--set %s: the Gravelius factor %s^g must be from %g to %g",
                                  typed, orders[i].symbol, orders[i].glo, orders[i].ghi),
                    r->errors++;
            else P->order[i].g = (StrandsFactor){.k = v};
            if (i >= SP_LAT_LENGTH_MAX) r->lateral_given[i - SP_LAT_LENGTH_MAX] = true;
            goto done;
        }
    if (r->p->sibling) return; /* meant for another model of the file */
    char hint[600];
    sch_suggest(&sch_strands, name, hint, sizeof hint);
    syl_program_error(r->p, r->diag, 0, 0, "--set %s: strands block '%s' has no parameter '%s'%s", typed,
                      syl_program_name(r->p), name, hint);
    r->errors++;
done:
    r->set_errors += r->errors - before;
}

static void defaults(StrandsParams *P) {
    memset(P, 0, sizeof *P);
    for (int i = 0; i < NGLOBALS; i++) store_global(&globals[i], P, globals[i].def);
    for (int i = 0; i < SP_ORDER_COUNT; i++)
        P->order[i] = (StrandsOrderParam){.g = {.k = orders[i].def}, .w = {.k = 1}, .lo = orders[i].lo,
                                          .hi = orders[i].hi};
    P->leaf_type = LEAVES_SPIRAL;
}

static int read_all(const SylProgram *p, void *params, FILE *diag, int *set_errors) {
    StrandsParams *P = params;
    Reader r = {.p = p, .diag = diag};
    defaults(P);
    sch_count_read(p);
    int n = 0;
    const SylDirective *dirs = syl_program_directives(p, &n);
    const SylDirective *seen[NGLOBALS + SP_ORDER_COUNT + 2] = {0};
    for (int i = 0; i < n; i++) {
        const SylDirective *d = &dirs[i];
        if (lang_texture_line(d->name)) continue; /* lang/textures.c reads it */
        int slot = -1;
        for (int k = 0; k < NGLOBALS && slot < 0; k++)
            if (!strcmp(d->name, globals[k].name)) slot = k;
        for (int k = 0; k < SP_ORDER_COUNT && slot < 0; k++)
            if (!strcmp(d->name, orders[k].name)) slot = NGLOBALS + k;
        if (slot < 0 && !strcmp(d->name, "leaves")) slot = NGLOBALS + SP_ORDER_COUNT;
        if (slot < 0 && !strcmp(d->name, "lod")) slot = NGLOBALS + SP_ORDER_COUNT + 1;
        if (slot < 0) {
            char hint[600];
            sch_suggest(&sch_strands, d->name, hint, sizeof hint);
            ERR_AT(&r, d, NULL, "a strands block has no parameter '%s'%s", d->name, hint);
            continue;
        }
        if (seen[slot]) {
            ERR_AT(&r, d, NULL, "'%s' is given twice (first on line %d)", d->name, seen[slot]->line);
            continue;
        }
        seen[slot] = d;
        if (slot < NGLOBALS) read_global(&r, d, &globals[slot], P);
        else if (slot < NGLOBALS + SP_ORDER_COUNT) {
            int k = slot - NGLOBALS;
            read_order(&r, d, &orders[k], &P->order[k]);
            if (k >= SP_LAT_LENGTH_MAX) r.lateral_given[k - SP_LAT_LENGTH_MAX] = true;
        } else if (slot == NGLOBALS + SP_ORDER_COUNT) read_leaves(&r, d, P);
        else r.errors += lang_lod_check(p, d, diag); /* sylva mesh reads it */
    }
    for (int i = 0; i < p->noverrides; i++) {
        const char *name = p->set_local ? p->set_local[i] : NULL;
        if (name && !is_param(p, name)) apply_set(&r, P, p->overrides[i].name, name, p->overrides[i].value);
    }
    /* the lateral's bounds and scale are the main one's unless given (Zamuda merges them) */
    for (int k = 0; k < 3; k++)
        if (!r.lateral_given[k]) P->order[SP_LAT_LENGTH_MAX + k] = P->order[SP_LENGTH_MAX + k];
    *set_errors = r.set_errors;
    return r.errors;
}

int strands_params_read(const SylProgram *p, StrandsParams *P, FILE *diag) {
    return sch_read_once(p, P, sizeof *P, read_all, diag);
}

int strands_params_check(const SylProgram *p, FILE *diag) {
    StrandsParams P;
    return sch_check_once(p, &P, sizeof P, read_all, diag);
}

/* The tables, for the docs' check that every parameter is documented. */
int strands_param_names(const char **names, const char **symbols, int max) {
    int n = 0;
    for (int i = 0; i < NGLOBALS && n < max; i++, n++) names[n] = globals[i].name, symbols[n] = globals[i].symbol;
    for (int i = 0; i < SP_ORDER_COUNT && n < max; i++, n++) names[n] = orders[i].name, symbols[n] = orders[i].symbol;
    if (n < max) names[n] = "leaves", symbols[n] = "l_type", n++;
    return n;
}
