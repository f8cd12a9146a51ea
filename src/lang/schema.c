/* The one reader of the directive tables (schema.h): names, did-you-mean, values, ranges and
 * --set, the same for every kind of block. */
#include "lang/schema.h"
#include "util/diag.h"

#include <stdlib.h>
#include <string.h>

#include "lang/program.h"
#include "util/closest.h"

const char *sch_type_name(SchType t) {
    static const char *const names[] = {
#define X(t, s) s,
        SCH_TYPES(X)
#undef X
    };
    return (unsigned)t < sizeof names / sizeof *names ? names[t] : "?";
}

/* Whether name is one of the words "a|b|c". */
static bool in_words(const char *words, const char *name) {
    size_t n = strlen(name);
    for (const char *w = words; w && *w;) {
        const char *end = strchr(w, '|');
        size_t len = end ? (size_t)(end - w) : strlen(w);
        if (len == n && !strncmp(w, name, n)) return true;
        w = end ? end + 1 : NULL;
    }
    return false;
}

int sch_word_index(const char *words, const char *word) {
    size_t n = strlen(word);
    int i = 0;
    for (const char *w = words; w && *w; i++) {
        const char *end = strchr(w, '|');
        size_t len = end ? (size_t)(end - w) : strlen(w);
        if (len == n && !strncmp(w, word, n)) return i;
        w = end ? end + 1 : NULL;
    }
    return -1;
}

const SchRow *sch_find(const SchTable *t, const char *name, int *level) {
    if (level) *level = -1;
    for (int i = 0; i < t->n; i++)
        if (!strcmp(t->rows[i].name, name) || in_words(t->rows[i].aliases, name)) return &t->rows[i];
    if (name[0] >= '0' && name[0] <= '9' && name[1])
        for (int i = 0; i < t->n; i++)
            if (t->rows[i].levels && !strcmp(t->rows[i].name, name + 1)) {
                if (level) *level = name[0] - '0';
                return &t->rows[i];
            }
    return NULL;
}

/* Split "a|b|c" into names (pointing into buf). */
static int split_words(const char *words, const char **names, int max, char *buf, size_t size) {
    snprintf(buf, size, "%s", words ? words : "");
    int n = 0;
    for (char *w = buf; *w && n < max;) {
        char *end = strchr(w, '|');
        names[n++] = w;
        if (!end) break;
        *end = 0;
        w = end + 1;
    }
    return n;
}

void sch_suggest(const SchTable *t, const char *typed, char *buf, size_t size) {
    /* 1DownAngel is compared with 1DownAngle, 1Rotate, ...; DownAngel with every name */
    enum { MAX = 160 };
    char pre[MAX][40];
    const char *names[MAX];
    int n = 0;
    char digit = typed[0] >= '0' && typed[0] <= '9' && typed[1] ? typed[0] : 0;
    for (int i = 0; i < t->n && n < MAX; i++) {
        if (digit && t->rows[i].levels) {
            snprintf(pre[n], sizeof pre[n], "%c%s", digit, t->rows[i].name);
            names[n] = pre[n];
        } else
            names[n] = t->rows[i].name;
        n++;
    }
    char list[400];
    if (closest_list(typed, names, n, list, sizeof list) > 0) snprintf(buf, size, " (did you mean %s?)", list);
    else buf[0] = 0;
}

void sch_suggest_word(const char *words, const char *typed, char *buf, size_t size) {
    const char *names[64];
    char tmp[512], list[400];
    int n = split_words(words, names, 64, tmp, sizeof tmp);
    if (closest_list(typed, names, n, list, sizeof list) > 0) snprintf(buf, size, " (did you mean %s?)", list);
    else buf[0] = 0;
}

bool sch_number(const SylDirArg *a, double *x) {
    if (a->kind == SYL_DARG_NUMBER) return *x = a->num, true;
    if (a->kind == SYL_DARG_TUPLE && a->nvalues == 1) return *x = a->values[0], true;
    return false;
}

/* A bound: an integer row's whole (9007199254740991, not 9.0072e+15), else %g. */
static void bound_text(const SchRow *r, double x, char *buf, size_t size) {
    if (isinf(x)) snprintf(buf, size, "%sinf", x < 0 ? "-" : "");
    else if (r->type == SCH_INTEGER && x == floor(x) && fabs(x) < 1e17) snprintf(buf, size, "%.0f", x);
    else snprintf(buf, size, "%g", x);
}

void sch_range_text(const SchRow *r, char *buf, size_t size) {
    char lo[32], hi[32];
    bound_text(r, r->lo, lo, sizeof lo);
    bound_text(r, r->hi, hi, sizeof hi);
    snprintf(buf, size, "%s%s, %s%s", r->lo_open || isinf(r->lo) ? "(" : "[", lo, hi,
             r->hi_open || isinf(r->hi) ? ")" : "]");
}

bool sch_value_ok(const SchRow *r, double x, char *why, size_t size) {
    if (isnan(x) || x < r->lo || x > r->hi || (r->lo_open && x == r->lo) || (r->hi_open && x == r->hi)) {
        char range[80];
        sch_range_text(r, range, sizeof range);
        snprintf(why, size, "must be in %s, not %g", range, x);
        return false;
    }
    if (r->type == SCH_INTEGER && x != floor(x)) {
        char range[80];
        sch_range_text(r, range, sizeof range);
        snprintf(why, size, "takes a whole number in %s, not %g", range, x);
        return false;
    }
    return true;
}

int sch_set_check_to(const SylProgram *p, const SylSink *sink, const SchTable *t, const char *typed, const char *name,
                  double value, const SchRow **row, int *level) {
    const SchRow *r = sch_find(t, name, level);
    if (!r) {
        char hint[480];
        sch_suggest(t, name, hint, sizeof hint);
        program_error_to(p, sink, 0, 0, "--set %s: %s block '%s' has no parameter '%s'%s", typed, t->kind,
                          syl_program_name(p), name, hint);
        return 1;
    }
    if (r->levels && *level < 0) {
        program_error_to(p, sink, 0, 0, "--set %s: '%s' is per level: write 0%s to 3%s", typed, name, r->name,
                          r->name);
        return 1;
    }
    if (r->levels && *level > 3) {
        program_error_to(p, sink, 0, 0, "--set %s: levels above 3 reuse level 3's parameters: write 3%s", typed,
                          r->name);
        return 1;
    }
    if (r->type != SCH_NUMBER && r->type != SCH_INTEGER) {
        program_error_to(p, sink, 0, 0, "--set %s: '%s' is not a number (write it in the block)", typed, name);
        return 1;
    }
    char why[160];
    if (!sch_value_ok(r, value, why, sizeof why)) {
        program_error_to(p, sink, 0, 0, "--set %s: '%s' %s", typed, name, why);
        return 1;
    }
    *row = r;
    return 0;
}

int sch_set_check(const SylProgram *p, FILE *diag, const SchTable *t, const char *typed, const char *name,
                  double value, const SchRow **row, int *level) {
    return sch_set_check_to(p, diag_sink(&(SylSink){0}, diag, NULL), t, typed, name, value, row, level);
}

void sch_count_read(const SylProgram *p) {
    if (!p->read_cache) return;
    p->read_cache->reads++;
    if (p->read_cache->also) (*p->read_cache->also)++;
}

int sch_reads(const SylProgram *p) { return p->read_cache ? p->read_cache->reads : 0; }
int sch_lod_scans(const SylProgram *p) { return p->read_cache ? p->read_cache->lod_scans : 0; }

void sch_count_into(const SylProgram *q, const SylProgram *p) {
    if (q->read_cache && p->read_cache) q->read_cache->also = &p->read_cache->reads;
}

void sch_keep(const SylProgram *p, const void *v, size_t size) {
    SchCache *c = p->read_cache;
    if (!c || c->value) return;
    c->value = malloc(size);
    if (!c->value) return; /* then the build reads the block again */
    memcpy(c->value, v, size);
    c->size = size;
}

bool sch_kept(const SylProgram *p, void *out, size_t size) {
    const SchCache *c = p->read_cache;
    if (!c || !c->value || c->size != size) return false;
    memcpy(out, c->value, size);
    return true;
}

int sch_read_once(const SylProgram *p, void *params, size_t size, SchRead read, FILE *diag) {
    if (sch_kept(p, params, size)) return 0;
    int set_errors;
    return read(p, params, diag, &set_errors);
}

int sch_check_once(const SylProgram *p, void *params, size_t size, SchRead read, FILE *diag) {
    int set_errors, errors = read(p, params, diag, &set_errors);
    if (!errors) sch_keep(p, params, size); /* the build takes it: read once */
    return errors && errors == set_errors ? -errors : errors;
}

void sch_slot_store(const SchSlot *s, void *base, int level, double v) {
    if (!s || !base) return;
    char *at = (char *)base + s->off;
    switch (s->store) {
    case SCH_AT_F32: *(float *)at = (float)v; break;
    case SCH_AT_F64: ((double *)at)[level > 0 ? level : 0] = v; break;
    case SCH_AT_INT: *(int *)at = (int)v; break;
    case SCH_AT_I64: *(int64_t *)at = (int64_t)v; break;
    case SCH_AT_U64: *(uint64_t *)at = (uint64_t)v; break;
    case SCH_AT_BOOL: *(bool *)at = v != 0; break;
    case SCH_AT_U8: *(uint8_t *)at = (uint8_t)v; break;
    default: break;
    }
}
