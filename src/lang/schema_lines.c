/* The schema's reader of NAME VALUE lines (SCH_LINES: strands, curvetree, pafco, weber; SCH_GROUPS:
 * ecosystem, whose `species NAME` lines open a group of the species' rows):
 *
 *   NAME VALUE          a number, an enum's word, a file in quotes, a name
 *   NNAME VALUE         a per-level row at level N (1DownAngle 60)
 *   NAME V0 [V1 ...]    a per-level row from level 0 (DownAngle 0 60 45 45)
 *
 * then --set NAME=VALUE in the order given. The reader finds what is wrong and where; the
 * kind's say hook words it, so each kind keeps its messages. A row the kind reads itself (a
 * curve, a factor that may be a curve) has slot SCH_AT_KIND and goes to its hooks. */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "lang/program.h"
#include "lang/schema.h"
#include "lang/textures.h"
#include "util/closest.h"

enum { MAX_ROWS = 256 };

struct SchLineRead {
    const SylProgram *p;
    const SchLines *k;
    FILE *diag;
    const SylSink *sink; /* errors go here when set, else to diag */
    const SchSeen *seen; /* describe's: told each line and --set; nothing stored or reported */
    bool lenient, stopped;
    int errors, set_errors;
    void *elem; /* the open group element's base (NULL: none) */
    const SylDirective *heads[64]; /* describe's: the group heads seen, for --set ELEM.NAME */
    int nheads;
    const SylDirective *given[MAX_ROWS];
    bool set[MAX_ROWS]; /* given by --set */
};

const SylProgram *sch_lines_program(const SchLineRead *r) { return r->p; }
FILE *sch_lines_diag(const SchLineRead *r) { return r->diag; }
const SylDirective *sch_lines_given(const SchLineRead *r, int row) {
    return row >= 0 && row < MAX_ROWS ? r->given[row] : NULL;
}

int sch_lines_errors(const SchLineRead *r) { return r->errors; }
int sch_lines_set_errors(const SchLineRead *r) { return r->set_errors; }
bool sch_lines_took(const SchLineRead *r, int row) {
    return row >= 0 && row < MAX_ROWS && (r->given[row] || r->set[row]);
}
bool sch_lines_lenient(const SchLineRead *r) { return r->lenient; }
const SylSink *sch_lines_sink(const SchLineRead *r) { return r->sink; }
void sch_lines_stop(SchLineRead *r) { r->stopped = true; }

static void error_at(const SchLineRead *r, const SylDirective *d, const SylDirArg *a, const char *msg) {
    if (r->sink && d) directive_error_to(r->p, r->sink, d, a, "%s", msg);
    else if (r->sink) program_error_to(r->p, r->sink, 0, 0, "%s", msg);
    else if (d) syl_directive_report_error(r->p, r->diag, d, a, "%s", msg);
    else syl_program_report_error(r->p, r->diag, 0, 0, "%s", msg);
}

void sch_lines_error(SchLineRead *r, const SylDirective *d, const SylDirArg *a, const char *fmt, ...) {
    char buf[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    r->errors++;
    if (r->seen) return;
    error_at(r, d, a, buf);
}

static int row_index(const SchLineRead *r, const SchRow *row) { return (int)(row - r->k->t->rows); }
static const SchSlot *slot_of(const SchLineRead *r, const SchRow *row) {
    int i = row_index(r, row);
    return r->k->slots && i < r->k->nslots ? &r->k->slots[i] : NULL;
}
static bool is_lod(const SchRow *row) { return !strcmp(row->name, "lod"); }
static bool is_kind(const SchSlot *s) { return s && s->store == SCH_AT_KIND; }

/* ---- the words of a problem: the kind's, else these ---- */

static void say_default(const SchProblem *pr, char *buf, size_t size) {
    const char *name = pr->row ? pr->row->name : pr->name;
    switch (pr->what) {
    case SCH_BAD_UNKNOWN: snprintf(buf, size, "no parameter '%s'%s", pr->name, pr->hint); break;
    case SCH_BAD_TWICE: snprintf(buf, size, "'%s' is given twice (first on line %d)", pr->name, pr->line); break;
    case SCH_BAD_LEVEL: snprintf(buf, size, "levels above 3 reuse level 3's parameters: write 3%s", name); break;
    case SCH_BAD_COUNT:
        if (pr->most > 1) snprintf(buf, size, "%s takes 1 to %d values, for levels 0 to %d", pr->name, pr->most, pr->most - 1);
        else snprintf(buf, size, "%s takes one value", pr->name);
        break;
    case SCH_BAD_NUMBER: snprintf(buf, size, "%s takes a number", pr->shown); break;
    case SCH_BAD_RANGE: snprintf(buf, size, "%s %s", pr->shown, pr->why); break;
    case SCH_BAD_WORD: snprintf(buf, size, "%s is one of %s%s", pr->name, pr->row->words, pr->hint); break;
    case SCH_BAD_FILE: snprintf(buf, size, "%s takes a file name in quotes", pr->name); break;
    /* --set: as sch_set_check says it */
    case SCH_BAD_SET_UNKNOWN: break; /* the caller's (it names the block) */
    case SCH_BAD_SET_LEVELS: snprintf(buf, size, "--set %s: '%s' is per level: write 0%s to 3%s", pr->typed, pr->name, name, name); break;
    case SCH_BAD_SET_LEVEL: snprintf(buf, size, "--set %s: levels above 3 reuse level 3's parameters: write 3%s", pr->typed, name); break;
    case SCH_BAD_SET_NOT_NUMBER: snprintf(buf, size, "--set %s: '%s' is not a number (write it in the block)", pr->typed, pr->name); break;
    case SCH_BAD_SET_RANGE: snprintf(buf, size, "--set %s: '%s' %s", pr->typed, pr->name, pr->why); break;
    case SCH_BAD_SET_ELEMENT: snprintf(buf, size, "--set %s: no '%s'%s", pr->typed, pr->name, pr->hint); break;
    case SCH_BAD_SET_NOT_GROUP: snprintf(buf, size, "--set %s: '%s' is the block's", pr->typed, pr->name); break;
    }
}

static bool value_problem(SchBad b) { return b >= SCH_BAD_COUNT && b <= SCH_BAD_FILE; }

static void bad(SchLineRead *r, SchProblem pr) {
    if (r->seen) { /* the block was checked: counted, not reported */
        r->errors++;
        return;
    }
    char buf[1024] = "";
    if (!pr.hint) pr.hint = "";
    if (!pr.shown) pr.shown = pr.name;
    pr.block = syl_program_name(r->p);
    pr.lenient = r->lenient && value_problem(pr.what);
    if (r->k->say) r->k->say(&pr, buf, sizeof buf);
    if (!buf[0] && pr.what == SCH_BAD_SET_UNKNOWN)
        snprintf(buf, sizeof buf, "--set %s: %s block '%s' has no parameter '%s'%s", pr.typed, r->k->t->kind,
                 pr.block, pr.name, pr.hint);
    if (!buf[0]) say_default(&pr, buf, sizeof buf);
    if (pr.lenient) { /* the default is kept */
        const SylDirArg *a = pr.at;
        program_warning(r->p, r->diag, a ? a->line : pr.d->line, a ? a->col : pr.d->col, "%s", buf);
        return;
    }
    r->errors++;
    error_at(r, pr.d, pr.at, buf);
}

/* ---- storing ---- */

/* A line's or --set's value of row into base. */
static void take(const SchLineRead *r, const SchRow *row, void *base, int level, double v) {
    sch_slot_store(slot_of(r, row), base, level, v);
    if (base && r->k->took) r->k->took(base, row);
}

static double word_value(const SchSlot *s, int word) { return s && s->values ? s->values[word] : word; }

void sch_lines_defaults(const SchLines *k, void *base) {
    for (int i = 0; i < k->nslots && i < k->t->n; i++) {
        const SchRow *row = &k->t->rows[i];
        const SchSlot *s = &k->slots[i];
        if (row->type == SCH_ENUM) {
            int w = row->def_text ? sch_word_index(row->words, row->def_text) : -1;
            if (w >= 0) sch_slot_store(s, base, -1, word_value(s, w));
        } else if (row->levels)
            for (int l = 0; l < row->levels && l < 4; l++) sch_slot_store(s, base, l, row->def[l]);
        else if (!isnan(row->def[0]) && (row->type == SCH_NUMBER || row->type == SCH_INTEGER || row->type == SCH_BOOLEAN))
            sch_slot_store(s, base, -1, row->def[0]);
    }
}

/* ---- a line ---- */

static bool is_word(const SylDirArg *a) { return a->kind == SYL_DARG_WORD || a->kind == SYL_DARG_STRING; }

/* One number of row at level (shown: its name there); false when bad (reported). */
static bool take_number(SchLineRead *r, const SylDirective *d, const SchRow *row, int level, const SylDirArg *a,
                        const char *shown, void *base) {
    double v;
    if (row->type == SCH_BOOLEAN && is_word(a)) {
        if (!strcasecmp(a->text, "true")) v = 1;
        else if (!strcasecmp(a->text, "false")) v = 0;
        else {
            bad(r, (SchProblem){.what = SCH_BAD_WORD, .d = d, .row = row, .at = a, .name = d->name, .shown = shown});
            return false;
        }
    } else if (!sch_number(a, &v)) {
        bad(r, (SchProblem){.what = SCH_BAD_NUMBER, .d = d, .row = row, .at = a, .name = d->name, .shown = shown});
        return false;
    }
    char why[160];
    bool ok = row->type == SCH_BOOLEAN ? v == 0 || v == 1 : sch_value_ok(row, v, why, sizeof why);
    if (!ok && row->type == SCH_BOOLEAN) snprintf(why, sizeof why, "takes true or false (or 1 or 0), not %g", v);
    if (!ok) {
        bad(r, (SchProblem){.what = SCH_BAD_RANGE, .d = d, .row = row, .at = a, .name = d->name, .shown = shown,
                            .why = why, .x = v});
        return false;
    }
    take(r, row, base, level, v);
    return true;
}

static void count_problem(SchLineRead *r, const SylDirective *d, const SchRow *row, int most) {
    bad(r, (SchProblem){.what = SCH_BAD_COUNT, .d = d, .row = row, .at = d->nargs ? &d->args[most] : NULL,
                        .name = d->name, .most = most});
}

static void read_value(SchLineRead *r, const SylDirective *d, const SchRow *row, int level, void *base) {
    const SchSlot *s = slot_of(r, row);
    int most = row->levels && level < 0 ? row->levels : 1;
    if (d->nargs < 1 || d->nargs > most) {
        count_problem(r, d, row, most);
        return;
    }
    const SylDirArg *a = &d->args[0];
    switch (row->type) {
    case SCH_ENUM: {
        int w = a->kind == SYL_DARG_WORD ? sch_word_index(row->words, a->text) : -1;
        if (w < 0) {
            char hint[400] = "";
            if (a->kind == SYL_DARG_WORD) sch_suggest_word(row->words, a->text, hint, sizeof hint);
            bad(r, (SchProblem){.what = SCH_BAD_WORD, .d = d, .row = row, .at = a, .name = d->name, .hint = hint});
            return;
        }
        take(r, row, base, -1, word_value(s, w));
        return;
    }
    case SCH_FILE:
        if (a->kind != SYL_DARG_STRING) {
            bad(r, (SchProblem){.what = SCH_BAD_FILE, .d = d, .row = row, .at = a, .name = d->name});
            return;
        }
        if (s && s->store == SCH_AT_LINE && base) *(const SylDirective **)((char *)base + s->off) = d;
        return;
    case SCH_STRING: /* a name (weber's Species: not read) */
        if (s && s->store == SCH_AT_TEXT && base) snprintf((char *)base + s->off, s->size, "%s", a->text ? a->text : "");
        return;
    default: /* numbers, a number per level */
        for (int k = 0; k < d->nargs; k++) {
            int l = level >= 0 ? level : k;
            char shown[64];
            if (row->levels) snprintf(shown, sizeof shown, "%d%s", l, row->name);
            else snprintf(shown, sizeof shown, "%s", d->name);
            take_number(r, d, row, row->levels ? l : -1, &d->args[k], shown, base);
        }
    }
}

static bool is_head(const SchLineRead *r, const SylDirective *d) {
    return r->k->group.dir && !strcmp(d->name, r->k->group.dir);
}

static void read_line(SchLineRead *r, const SylDirective *d, void *base) {
    const SchTable *t = r->k->t;
    if (is_head(r, d) && !r->seen) { /* a group's element begins: its rows follow */
        r->elem = r->k->group.open(r, d, base);
        return;
    }
    if (is_head(r, d) && d->nargs == 1 && d->args[0].text && r->nheads < 64) r->heads[r->nheads++] = d;
    if (r->k->textures && lang_texture_line(d->name)) { /* lang/textures.c reads it */
        const SchRow *row = sch_find(t, d->name, NULL);
        if (r->seen && row && r->seen->line) r->seen->line(r->seen->ctx, row, -1, d);
        return;
    }
    int level;
    const SchRow *row = sch_find(t, d->name, &level);
    bool in_group = row && row->group && r->k->group.dir && !r->seen; /* stored in the open element */
    if (!row || (in_group && !r->elem)) { /* a group's row outside a group: unknown to the block */
        char hint[480];
        sch_suggest(t, d->name, hint, sizeof hint);
        bad(r, (SchProblem){.what = SCH_BAD_UNKNOWN, .d = d, .name = d->name, .hint = hint, .in_group = r->elem != NULL});
        return;
    }
    if (in_group) base = r->elem;
    if (row->levels && level > 3) {
        bad(r, (SchProblem){.what = SCH_BAD_LEVEL, .d = d, .row = row, .name = d->name});
        return;
    }
    int i = row_index(r, row);
    if (i >= MAX_ROWS) return;
    if (r->given[i] && !r->k->again) {
        bad(r, (SchProblem){.what = SCH_BAD_TWICE, .d = d, .row = row, .name = d->name, .line = r->given[i]->line});
        return;
    }
    r->given[i] = d;
    if (r->seen) {
        if (r->seen->line) r->seen->line(r->seen->ctx, row, level, d);
        return;
    }
    const SchSlot *s = slot_of(r, row);
    if (is_lod(row)) r->errors += lang_lod_check(r->p, d, r->diag); /* every kind's words (lang/lod.c) */
    else if (is_kind(s)) r->errors += r->k->line(r, row, d, base);
    else read_value(r, d, row, level, base);
}

/* ---- --set ---- */

static bool is_param(const SylProgram *p, const char *name) {
    for (int i = 0; i < p->nparams; i++)
        if (!strcmp(p->params[i].name, name)) return true;
    return false;
}

static int elem_count(const SchLineRead *r, const void *base) {
    return base ? *(const int *)((const char *)base + r->k->group.count_off) : r->nheads;
}
static void *elem_at(const SchLineRead *r, void *base, int i) {
    return (char *)base + r->k->group.off + (size_t)i * r->k->group.size;
}
static const char *elem_name(const SchLineRead *r, void *base, int i) {
    return base ? (const char *)elem_at(r, base, i) + r->k->group.name_off : r->heads[i]->args[0].text;
}

static void set_one(SchLineRead *r, const char *typed, const char *name, double v, void *base) {
    const SchTable *t = r->k->t;
    int level, only = -1; /* ELEM.NAME: the element's index; -1: every element */
    const char *dot = r->k->group.dir ? strchr(name, '.') : NULL;
    if (dot) {
        int n = elem_count(r, base);
        for (int i = 0; i < n; i++) {
            const char *e = elem_name(r, base, i);
            if (strlen(e) == (size_t)(dot - name) && !strncmp(e, name, (size_t)(dot - name))) only = i;
        }
        if (only < 0) {
            if (r->seen) return;
            const char *names[64];
            char prefix[96], near[380], hint[400] = "";
            for (int i = 0; i < n && i < 64; i++) names[i] = elem_name(r, base, i);
            snprintf(prefix, sizeof prefix, "%.*s", (int)(dot - name), name);
            if (closest_list(prefix, names, n < 64 ? n : 64, near, sizeof near))
                snprintf(hint, sizeof hint, " (did you mean %s?)", near);
            bad(r, (SchProblem){.what = SCH_BAD_SET_ELEMENT, .name = prefix, .typed = typed, .hint = hint, .x = v});
            return;
        }
        name = dot + 1;
    }
    const SchRow *row = sch_find(t, name, &level);
    if (!row && r->p->sibling) return; /* meant for another model of the file */
    if (r->seen) {
        if (row && r->seen->value && (!dot || row->group)) r->seen->value(r->seen->ctx, row, row->group ? only : level, &v, 1, NULL);
        return;
    }
    SchProblem pr = {.row = row, .name = name, .typed = typed, .x = v};
    if (row && is_lod(row)) {
        r->errors += lang_lod_set_check(r->p, v, typed, r->diag); /* as every kind's */
        return;
    }
    char hint[480];
    sch_suggest(t, name, hint, sizeof hint);
    pr.hint = hint;
    if (!row) {
        pr.what = SCH_BAD_SET_UNKNOWN;
        bad(r, pr);
        return;
    }
    if (row->levels && (level < 0 || level > 3)) {
        pr.what = level < 0 ? SCH_BAD_SET_LEVELS : SCH_BAD_SET_LEVEL;
        bad(r, pr);
        return;
    }
    const SchSlot *s = slot_of(r, row);
    if (row->type != SCH_NUMBER && row->type != SCH_INTEGER && row->type != SCH_BOOLEAN) {
        pr.what = SCH_BAD_SET_NOT_NUMBER;
        bad(r, pr);
        return;
    }
    char why[160];
    bool ok = row->type == SCH_BOOLEAN ? v == 0 || v == 1 : sch_value_ok(row, v, why, sizeof why);
    if (!ok && row->type == SCH_BOOLEAN) snprintf(why, sizeof why, "takes true or false (or 1 or 0), not %g", v);
    if (!ok) {
        pr.what = SCH_BAD_SET_RANGE, pr.why = why;
        bad(r, pr);
        return;
    }
    if (dot && !row->group) {
        pr.what = SCH_BAD_SET_NOT_GROUP;
        bad(r, pr);
        return;
    }
    if (row_index(r, row) < MAX_ROWS) r->set[row_index(r, row)] = true;
    if (row->group && r->k->group.dir) { /* in every element, or in the one named */
        for (int i = 0; i < elem_count(r, base); i++)
            if (only < 0 || only == i) take(r, row, elem_at(r, base, i), -1, v);
        return;
    }
    if (is_kind(s)) r->errors += r->k->set(r, row, typed, v, base);
    else take(r, row, base, row->levels ? level : -1, v);
}

static int read_block(SchLineRead *r, void *base, int *set_errors) {
    const SylProgram *p = r->p;
    int n = 0;
    const SylDirective *ds = syl_program_directives(p, &n);
    for (int i = 0; i < n && !r->stopped; i++) read_line(r, &ds[i], base);
    *set_errors = 0;
    if (r->stopped) return r->errors;
    if (!r->seen && r->k->lines_done) r->errors += r->k->lines_done(r, base);
    int before = r->errors;
    for (int i = 0; i < p->noverrides && !(r->k->set_if_clean && before && !r->seen); i++) { /* in the order given: the last one wins */
        const char *name = p->set_local ? p->set_local[i] : NULL;
        if (name && !is_param(p, name)) set_one(r, p->overrides[i].name, name, p->overrides[i].value, base);
    }
    *set_errors = r->set_errors = r->errors - before;
    if (!r->seen && r->k->done) r->errors += r->k->done(r, base);
    return r->errors;
}

int sch_read_lines(const SylProgram *p, const SchLines *k, void *base, FILE *diag, int *set_errors) {
    SchLineRead r = {.p = p, .k = k, .diag = diag, .lenient = k->lenient && k->lenient(p)};
    return read_block(&r, base, set_errors);
}

int sch_read_lines_to(const SylProgram *p, const SchLines *k, void *base, const SylSink *sink, int *set_errors) {
    SchLineRead r = {.p = p, .k = k, .sink = sink, .lenient = k->lenient && k->lenient(p)};
    return read_block(&r, base, set_errors);
}

int sch_see_lines(const SylProgram *p, const SchTable *t, const SchSeen *seen) {
    SchLines k = {.t = t, .textures = true, .again = true};
    for (int i = 0; i < t->n && !k.group.dir; i++) k.group.dir = t->rows[i].group; /* its head's name */
    SchLineRead r = {.p = p, .k = &k, .seen = seen};
    int set_errors;
    return read_block(&r, NULL, &set_errors);
}
