/* The schema's reader of keyed lines (SCH_KEYED, a grow block's shape):
 *
 *   DIRECTIVE [MODE [N]] [VALUE] [~SYMBOL(x)] [KEY VALUE]...
 *
 * The table's rows say it all: a row DIRECTIVE is a bare value (years 18) or, as an enum, the
 * directive's modes (with the mode implied by keys alone, one that must be written, a mode
 * word a whole number follows, a line that may repeat); a row DIRECTIVE.KEY is a key (of one
 * mode only when it has `when`). Values are stored into the caller's struct through its slots
 * (schema.h); --set reaches a key as DIRECTIVE.KEY, by its name alone, a bare value by its
 * directive's name and a repeated line's key as DIRECTIVE.N.KEY. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "lang/program.h"
#include "lang/schema.h"
#include "lang/textures.h"
#include "util/closest.h"

enum { MAX_DIRS = 32, MAX_NAMES = 256 };

/* A directive of the table: its name, and its head row (its modes or its value) if any. */
typedef struct Dir {
    char name[32];
    const SchRow *head;
    const SchGroup *group; /* a repeated directive's elements in base; NULL: not stored */
} Dir;

typedef struct Reader {
    const SylProgram *p;
    const SchKeyed *k;
    FILE *diag;
    const SchSeen *seen; /* describe's: told each value; errors are counted, not reported */
    int errors;
    Dir dirs[MAX_DIRS];
    int ndirs;
    int count[MAX_DIRS]; /* lines of each repeated directive read so far */
    int elem;            /* the element of the repeated line being read, -1: none */
} Reader;

#define ERR(r, line, col, ...)                                                                                   \
    ((r)->seen ? (void)0 : syl_program_report_error((r)->p, (r)->diag, (line), (col), __VA_ARGS__), (r)->errors++)

/* row took x (n numbers) or word: describe's, if it asked. */
static void see(const Reader *r, const SchRow *row, const double *x, int n, const char *word) {
    if (r->seen && r->seen->value) r->seen->value(r->seen->ctx, row, row->group ? r->elem : -1, x, n, word);
}

static const SchTable *table(const Reader *r) { return r->k->t; }
/* "n" before a noun that begins with a vowel ("an organ line"). */
static const char *an(const char *noun) { return noun && strchr("aeiou", noun[0]) ? "n" : ""; }
static bool is_mode_row(const SchRow *row) { return row && row->type == SCH_ENUM && !strchr(row->name, '.'); }

/* The directive's part of a row name: "buds" of "buds.angle" and of "buds". */
static size_t dir_len(const char *name) {
    const char *dot = strchr(name, '.');
    return dot ? (size_t)(dot - name) : strlen(name);
}

/* The table's directives, in the order of their first row (texture lines are not its). */
static void list_dirs(Reader *r) {
    const SchTable *t = table(r);
    for (int i = 0; i < t->n; i++) {
        const SchRow *row = &t->rows[i];
        if (lang_texture_line(row->name)) continue;
        size_t len = dir_len(row->name);
        int d = 0;
        while (d < r->ndirs && !(strlen(r->dirs[d].name) == len && !strncmp(r->dirs[d].name, row->name, len))) d++;
        if (d == r->ndirs) {
            if (r->ndirs == MAX_DIRS || len >= sizeof r->dirs[0].name) continue;
            snprintf(r->dirs[d].name, sizeof r->dirs[d].name, "%.*s", (int)len, row->name);
            r->ndirs++;
        }
        if (!strchr(row->name, '.')) r->dirs[d].head = row;
    }
    for (int d = 0; d < r->ndirs; d++)
        for (int g = 0; g < r->k->ngroups; g++)
            if (!strcmp(r->k->groups[g].dir, r->dirs[d].name)) r->dirs[d].group = &r->k->groups[g];
}

static const char *key_of(const SchRow *row) {
    const char *dot = strchr(row->name, '.');
    return dot ? dot + 1 : row->name;
}

static const char *kind_name(SylDirArgKind k) {
    switch (k) {
    case SYL_DARG_WORD: return "a word";
    case SYL_DARG_NUMBER: return "a number";
    case SYL_DARG_STRING: return "a string";
    case SYL_DARG_SYMBOL: return "a symbol";
    default: return "a tuple";
    }
}

/* The list "a, b or c" of names. */
static void list_words(char *buf, size_t size, const char *const *names, size_t n) {
    buf[0] = 0;
    size_t used = 0;
    for (size_t i = 0; i < n; i++) {
        int k = snprintf(buf + used, size - used, "%s%s", i == 0 ? "" : i + 1 == n ? " or " : ", ", names[i]);
        if (k < 0 || (size_t)k >= size - used) break;
        used += (size_t)k;
    }
}

/* "a|b|c" into names (pointing into tmp); returns how many. */
static size_t split_words(const char *words, const char **names, size_t max, char *tmp, size_t size) {
    size_t n = 0;
    snprintf(tmp, size, "%s", words ? words : "");
    for (char *w = tmp; w && *w && n < max; n++) {
        names[n] = w;
        w = strchr(w, '|');
        if (w) *w++ = 0;
    }
    return n;
}

static const SchSlot *slot_of(const Reader *r, const SchRow *row) {
    int i = (int)(row - table(r)->rows);
    return i < r->k->nslots ? &r->k->slots[i] : NULL;
}

/* An enum's word index as stored (its value), and back. */
static int word_value(const SchSlot *s, int word) { return s && s->values ? s->values[word] : word; }

/* base NULL: nothing is stored (describe's reading). */
static void store(const SchSlot *s, void *base, double v) { sch_slot_store(s, base, -1, v); }

static int stored_int(const SchSlot *s, const void *base) {
    const char *at = (const char *)base + s->off;
    return s->store == SCH_AT_U8 ? *(const uint8_t *)at : *(const int *)at;
}

/* ---- defaults ---- */

static void row_default(const SchKeyed *k, int i, void *base) {
    const SchRow *row = &k->t->rows[i];
    const SchSlot *s = &k->slots[i];
    if (row->type == SCH_ENUM) {
        int w = row->def_text ? sch_word_index(row->words, row->def_text) : -1;
        if (w >= 0) store(s, base, word_value(s, w));
    } else if (row->type != SCH_VECTOR && row->type != SCH_STRING && !isnan(row->def[0]))
        store(s, base, row->def[0]);
}

void sch_keyed_defaults(const SchKeyed *k, void *base) {
    for (int i = 0; i < k->nslots && i < k->t->n; i++)
        if (!k->t->rows[i].group) row_default(k, i, base);
}

void sch_keyed_group_defaults(const SchKeyed *k, const SchGroup *g, void *elem) {
    memset(elem, 0, g->size);
    size_t len = strlen(g->dir);
    for (int i = 0; i < k->nslots && i < k->t->n; i++) {
        const SchRow *row = &k->t->rows[i];
        if (row->group && dir_len(row->name) == len && !strncmp(row->name, g->dir, len)) row_default(k, i, elem);
    }
}

/* ---- a line ---- */

/* The key row KEY of directive dir in mode (NULL: none written); NULL when it has none. */
static const SchRow *find_key(const Reader *r, const char *dir, const char *mode, const char *key) {
    char name[96];
    snprintf(name, sizeof name, "%s.%s", dir, key);
    const SchTable *t = table(r);
    for (int i = 0; i < t->n; i++)
        if (!strcmp(t->rows[i].name, name) && (!t->rows[i].when || (mode && !strcmp(t->rows[i].when, mode))))
            return &t->rows[i];
    return NULL;
}

/* The keys of dir readable in mode: the mode's own first, then every mode's. */
static size_t key_names(const Reader *r, const char *dir, const char *mode, const char **names, size_t max) {
    const SchTable *t = table(r);
    size_t n = 0, len = strlen(dir);
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < t->n && n < max; i++) {
            const SchRow *row = &t->rows[i];
            if (strncmp(row->name, dir, len) || row->name[len] != '.') continue;
            if (pass == 0 ? row->when && mode && !strcmp(row->when, mode) : !row->when) names[n++] = key_of(row);
        }
    return n;
}

/* Store the value of row (key name kname) from args[i]; returns how many args it took, 0 on error. */
static int take_value(Reader *r, const SylDirective *d, const SchRow *row, const SylDirArg *args, int i, void *base) {
    const char *kname = key_of(row);
    if (i >= d->nargs) {
        const SylDirArg *last = i > 0 ? &args[i - 1] : NULL;
        ERR(r, last ? last->line : d->line, last ? last->col : d->col, "'%s' needs a value after it", kname);
        return 0;
    }
    const SylDirArg *a = &args[i];
    const SchSlot *s = slot_of(r, row);
    double v;
    switch (row->type) {
    case SCH_BOOLEAN:
        if (a->kind == SYL_DARG_WORD && (!strcmp(a->text, "on") || !strcmp(a->text, "yes"))) v = 1;
        else if (a->kind == SYL_DARG_WORD && (!strcmp(a->text, "off") || !strcmp(a->text, "no"))) v = 0;
        else if (!sch_number(a, &v) || (v != 0 && v != 1)) {
            ERR(r, a->line, a->col, "'%s' expects on or off", kname);
            return 0;
        }
        store(s, base, v);
        see(r, row, &v, 1, NULL);
        return 1;
    case SCH_VECTOR:
        if (a->kind != SYL_DARG_TUPLE || a->nvalues != 3) {
            ERR(r, a->line, a->col, "'%s' expects a direction (x, y, z)", kname);
            return 0;
        }
        for (int j = 0; j < 3; j++)
            if (!isfinite(a->values[j])) {
                ERR(r, a->line, a->col, "'%s': (x, y, z) must be finite", kname);
                return 0;
            }
        if (s && s->store == SCH_AT_F32X3 && base)
            for (int j = 0; j < 3; j++) ((float *)((char *)base + s->off))[j] = (float)a->values[j];
        see(r, row, (const double[3]){a->values[0], a->values[1], a->values[2]}, 3, NULL);
        return 1;
    case SCH_STRING:
        if (a->kind != SYL_DARG_WORD || (s && strlen(a->text) >= s->size)) {
            ERR(r, a->line, a->col, "'%s' expects a name shorter than %zu characters: %s", kname, s ? s->size : 0,
                row->doc);
            return 0;
        }
        if (s && s->store == SCH_AT_TEXT && base) snprintf((char *)base + s->off, s->size, "%s", a->text);
        see(r, row, NULL, 0, a->text);
        return 1;
    case SCH_ENUM: {
        int j = a->kind == SYL_DARG_WORD ? sch_word_index(row->words, a->text) : -1;
        if (j >= 0) {
            store(s, base, word_value(s, j));
            see(r, row, NULL, 0, a->text);
            return 1;
        }
        const char *names[16];
        char tmp[256], list[256];
        list_words(list, sizeof list, names, split_words(row->words, names, 16, tmp, sizeof tmp));
        ERR(r, a->line, a->col, "'%s' expects %s", kname, list);
        return 0;
    }
    default: /* a number or a whole number */
        if (!sch_number(a, &v)) {
            ERR(r, a->line, a->col, "'%s' expects a number, not %s", kname, kind_name(a->kind));
            return 0;
        }
        char why[160];
        if (!sch_value_ok(row, v, why, sizeof why)) {
            if (!strcmp(row->name, "lod") && !r->seen) r->errors += lang_lod_check(r->p, d, r->diag); /* every kind's words */
            else ERR(r, a->line, a->col, "%s %s", kname, why);
            return 0;
        }
        store(s, base, v);
        see(r, row, &v, 1, NULL);
        return 1;
    }
}

/* ~leaf(0.06) on a repeated line: its mode (by the head's symbols) and symbol_key's value. */
static bool take_symbol(Reader *r, const Dir *dir, const SylDirArg *a, void *base) {
    const SchRow *head = dir->head;
    const char *s = a->text[0] == '~' ? a->text + 1 : a->text;
    const char *names[16];
    char tmp[256];
    size_t n = split_words(head->symbols, names, 16, tmp, sizeof tmp);
    int word = -1;
    const char *wtext = NULL;
    for (size_t i = 0; i < n && word < 0; i++) {
        const char *eq = strchr(names[i], '=');
        if (eq && (size_t)(eq - names[i]) == strlen(s) && !strncmp(names[i], s, strlen(s)))
            word = sch_word_index(head->words, wtext = eq + 1);
    }
    if (word < 0) {
        const char *modes[16];
        char mtmp[256], tilde[16][40], list[256];
        size_t nm = split_words(head->words, modes, 16, mtmp, sizeof mtmp);
        for (size_t i = 0; i < nm; i++) snprintf(tilde[i], sizeof tilde[i], "~%s", modes[i]), modes[i] = tilde[i];
        list_words(list, sizeof list, modes, nm);
        const char *what = head->group ? head->group : head->name;
        ERR(r, a->line, a->col, "'%s' is not a symbol of a%s %s: use %s", a->text, an(what), what, list);
        return false;
    }
    store(slot_of(r, head), base, word_value(slot_of(r, head), word));
    see(r, head, NULL, 0, wtext);
    if (a->nvalues >= 1) {
        if (!(a->values[0] > 0) || !isfinite(a->values[0])) {
            ERR(r, a->line, a->col, "the size of '%s' must be above 0", a->text);
            return false;
        }
        const SchRow *key = find_key(r, dir->name, NULL, head->symbol_key);
        if (key) store(slot_of(r, key), base, a->values[0]), see(r, key, &a->values[0], 1, NULL);
    }
    return true;
}

/* The mode a line begins with (or implies): its index among head's words, -1 none, -2 an
 * error (reported); *i is past it and its count. */
static int read_mode(Reader *r, const SchRow *head, const SylDirective *d, void *base, int *i) {
    const SylDirArg *args = d->args;
    int mode = d->nargs > 0 && args[0].kind == SYL_DARG_WORD ? sch_word_index(head->words, args[0].text) : -1;
    if (mode >= 0) *i = 1;
    else if (head->implied && d->nargs > 0) mode = sch_word_index(head->words, head->implied); /* keys only */
    if (mode < 0 && head->required) {
        const char *words[32];
        char tmp[256], list[256];
        list_words(list, sizeof list, words, split_words(head->words, words, 32, tmp, sizeof tmp));
        if (d->nargs > 0 && args[0].kind == SYL_DARG_WORD)
            ERR(r, args[0].line, args[0].col, "'%s' expects %s first, not '%s'", d->name, list, args[0].text);
        else if (d->nargs > 0)
            ERR(r, args[0].line, args[0].col, "'%s' expects %s first, not %s", d->name, list, kind_name(args[0].kind));
        else ERR(r, d->line, d->col, "'%s' expects %s after it", d->name, list);
        return -2;
    }
    if (mode < 0) return -1;
    int count = 0;
    if (head->counted && mode == sch_word_index(head->words, head->counted)) { /* whorled 3 */
        double v;
        if (*i >= d->nargs || !sch_number(&args[*i], &v) || v != floor(v) || v < head->count_lo || v > head->count_hi) {
            const SylDirArg *at = *i < d->nargs ? &args[*i] : &args[*i - 1];
            ERR(r, at->line, at->col, "'%s' expects a whole number of %s from %d to %d after it", head->counted,
                head->count_of ? head->count_of : "things", head->count_lo, head->count_hi);
            return -2;
        }
        count = (int)v;
        (*i)++;
    }
    store(slot_of(r, head), base, word_value(slot_of(r, head), mode));
    if (r->k->mode_read && base) r->k->mode_read(base, head, mode, count);
    if (r->seen) {
        const char *words[32];
        char tmp[256];
        if ((size_t)mode < split_words(head->words, words, 32, tmp, sizeof tmp)) see(r, head, NULL, 0, words[mode]);
    }
    return mode;
}

/* A word that is no key of dir in mode (mword; NULL: none written), at argument i: the keys
 * that would have been right, or a near one. */
static void unknown_key(Reader *r, const Dir *dir, const SylDirective *d, const SylDirArg *a, const char *mword,
                        bool mode_place) {
    const char *names[64];
    size_t n = key_names(r, dir->name, mword, names, 64);
    char list[512], mtmp[256];
    list_words(list, sizeof list, names, n);
    /* did you mean: a key, or a mode word where the mode goes (`buds alternat`) */
    size_t nn = n;
    if (mode_place && is_mode_row(dir->head)) nn += split_words(dir->head->words, names + n, 64 - n, mtmp, sizeof mtmp);
    char near[160];
    if (closest_list(a->text, names, (int)nn, near, sizeof near)) {
        ERR(r, a->line, a->col, "unknown key '%s' of '%s' (did you mean %s?)", a->text, d->name, near);
        return;
    }
    bool other_mode = false;
    size_t len = strlen(dir->name);
    for (int j = 0; j < table(r)->n; j++) {
        const SchRow *row = &table(r)->rows[j];
        if (row->when && !strncmp(row->name, dir->name, len) && row->name[len] == '.' &&
            !strcmp(row->name + len + 1, a->text))
            other_mode = true;
    }
    if (other_mode && mword)
        ERR(r, a->line, a->col, "'%s' is not a key of '%s %s' (keys: %s)", a->text, d->name, mword, n ? list : "none");
    else if (n) ERR(r, a->line, a->col, "unknown key '%s' of '%s' (keys: %s)", a->text, d->name, list);
    else ERR(r, a->line, a->col, "'%s%s%s' takes no keys", d->name, mword ? " " : "", mword ? mword : "");
}

static void read_line(Reader *r, const Dir *dir, const SylDirective *d, void *base) {
    const SchRow *head = dir->head;
    const SylDirArg *args = d->args;
    int i = 0, mode = -1; /* mode: the word's index among head's words */
    if (is_mode_row(head)) {
        if ((mode = read_mode(r, head, d, base, &i)) == -2) return;
    } else if (head) { /* a bare value */
        if (!take_value(r, d, head, args, i < d->nargs ? i : d->nargs, base)) return;
        i++;
    }
    const char *mwords[32];
    char mtmp[256];
    const char *mword = NULL;
    if (mode >= 0 && (size_t)mode < split_words(head->words, mwords, 32, mtmp, sizeof mtmp)) mword = mwords[mode];
    for (; i < d->nargs; i++) {
        const SylDirArg *a = &args[i];
        if (head && head->symbols && a->kind == SYL_DARG_SYMBOL) {
            if (!take_symbol(r, dir, a, base)) return;
            continue;
        }
        if (a->kind != SYL_DARG_WORD) {
            ERR(r, a->line, a->col, "expected a key of '%s' here, not %s", d->name, kind_name(a->kind));
            return;
        }
        const SchRow *key = find_key(r, dir->name, mword, a->text);
        if (!key) {
            unknown_key(r, dir, d, a, mword, mode < 0 && i == 0);
            return;
        }
        int took = take_value(r, d, key, args, i + 1, base);
        if (!took) return;
        i += took;
    }
}

static void read_lines(Reader *r, void *base) {
    int n = 0;
    const SylDirective *ds = syl_program_directives(r->p, &n);
    int first[MAX_DIRS];
    for (int k = 0; k < r->ndirs; k++) first[k] = -1;
    const char *names[MAX_DIRS];
    for (int k = 0; k < r->ndirs; k++) names[k] = r->dirs[k].name;
    for (int i = 0; i < n; i++) {
        const SylDirective *d = &ds[i];
        if (lang_texture_line(d->name)) continue; /* lang/textures.c reads it */
        int k = 0;
        while (k < r->ndirs && strcmp(r->dirs[k].name, d->name)) k++;
        if (k == r->ndirs) {
            char list[512], near[160];
            list_words(list, sizeof list, names, (size_t)r->ndirs);
            if (closest_list(d->name, names, r->ndirs, near, sizeof near))
                ERR(r, d->line, d->col, "unknown directive '%s' in a %s block (did you mean %s?)", d->name,
                    table(r)->kind, near);
            else
                ERR(r, d->line, d->col, "unknown directive '%s' in a %s block (known: %s)", d->name, table(r)->kind,
                    list);
            continue;
        }
        const Dir *dir = &r->dirs[k];
        bool repeats = dir->head && dir->head->repeat;
        if (first[k] >= 0 && !repeats) {
            ERR(r, d->line, d->col, "'%s' is given twice (first at line %d)", d->name, ds[first[k]].line);
            continue;
        }
        if (first[k] < 0) first[k] = i;
        bool value = dir->head && !is_mode_row(dir->head);
        if (!d->nargs && value) {
            ERR(r, d->line, d->col, "'%s' needs a value", d->name);
            continue;
        }
        void *at = base;
        if (repeats) { /* each line its own element of its group */
            int *count = &r->count[k];
            if (*count == dir->head->repeat) {
                ERR(r, d->line, d->col, "at most %d %ss", dir->head->repeat,
                    dir->head->group ? dir->head->group : dir->name);
                continue;
            }
            const SchGroup *g = base ? dir->group : NULL;
            at = g ? (char *)base + g->off + (size_t)*count * g->size : NULL;
            if (g) sch_keyed_group_defaults(r->k, g, at), *(int *)((char *)base + g->count_off) = *count + 1;
            r->elem = (*count)++;
            if (r->seen && r->seen->element) r->seen->element(r->seen->ctx, dir->head, r->elem);
        }
        read_line(r, dir, d, at);
        r->elem = -1;
    }
}

/* ---- --set ---- */

static bool settable(const SchRow *row) {
    return row->type == SCH_NUMBER || row->type == SCH_INTEGER || row->type == SCH_BOOLEAN;
}

static bool is_param(const SylProgram *p, const char *name) {
    for (int i = 0; i < p->nparams; i++)
        if (!strcmp(p->params[i].name, name)) return true;
    return false;
}

/* A number v of row (key name kname) into base, within the row's range. */
static void set_number(Reader *r, const char *typed, const SchRow *row, void *base, double v) {
    const char *kname = key_of(row);
    if (row->type == SCH_BOOLEAN) {
        if (v != 0 && v != 1) {
            ERR(r, 0, 0, "--set %s: '%s' is 1 (on) or 0 (off)", typed, kname);
            return;
        }
        store(slot_of(r, row), base, v);
        see(r, row, &v, 1, NULL);
        return;
    }
    if (!strcmp(row->name, "lod") && !r->seen) {
        int e = lang_lod_set_check(r->p, v, typed, r->diag); /* as every kind's */
        r->errors += e;
        if (e) return;
    }
    char why[160];
    if (!sch_value_ok(row, v, why, sizeof why)) { /* as sch_set_check says it */
        ERR(r, 0, 0, "--set %s: '%s' %s", typed, kname, why);
        return;
    }
    store(slot_of(r, row), base, v);
    see(r, row, &v, 1, NULL);
}

/* DIRECTIVE.N.KEY: the N-th repeated line's number (organ.2.size). */
static void set_group(Reader *r, const Dir *dir, void *base, const char *typed, const char *name, double v) {
    const SchRow *head = dir->head;
    const char *group = head->group ? head->group : head->name;
    const SchTable *t = table(r);
    const char *first = NULL, *names[32];
    size_t nn = 0, len = strlen(dir->name) + 1;
    for (int i = 0; i < t->n; i++)
        if (t->rows[i].group && !strncmp(t->rows[i].name, dir->name, len - 1) && t->rows[i].name[len - 1] == '.' &&
            settable(&t->rows[i]) && nn < 32) {
            names[nn++] = key_of(&t->rows[i]);
            if (!first) first = key_of(&t->rows[i]);
        }
    char *end = NULL;
    long n = strtol(name + len, &end, 10);
    if (end == name + len || *end != '.') {
        ERR(r, 0, 0, "--set %s: write %s.N.KEY, N the %s from 1 (%s.1.%s)", typed, dir->name, group, dir->name,
            first ? first : "KEY");
        return;
    }
    int count = r->count[dir - r->dirs];
    if (n < 1 || n > count) {
        if (r->p->sibling) return;
        ERR(r, 0, 0, "--set %s: %s block '%s' has %d %s%s", typed, t->kind, syl_program_name(r->p), count, group,
            count == 1 ? "" : "s");
        return;
    }
    const SchRow *key = find_key(r, dir->name, NULL, end + 1);
    if (!key || !settable(key)) {
        char list[256] = "";
        size_t used = 0;
        for (size_t i = 0; i < nn && used < sizeof list; i++)
            used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", names[i]);
        ERR(r, 0, 0, "--set %s: a%s %s has no number '%s' (%s)", typed, an(group), group, end + 1, list);
        return;
    }
    const SchGroup *g = base ? dir->group : NULL;
    r->elem = (int)n - 1;
    set_number(r, typed, key, g ? (char *)base + g->off + (size_t)(n - 1) * g->size : NULL, v);
    r->elem = -1;
}

/* The head row of row's directive (its modes), or NULL. */
static const SchRow *head_of(const Reader *r, const SchRow *row) {
    size_t len = dir_len(row->name);
    for (int d = 0; d < r->ndirs; d++)
        if (strlen(r->dirs[d].name) == len && !strncmp(r->dirs[d].name, row->name, len)) return r->dirs[d].head;
    return NULL;
}

static void set_one(Reader *r, void *base, const char *typed, const char *name, double v) {
    const SchTable *t = table(r);
    for (int d = 0; d < r->ndirs; d++) { /* a repeated line's: DIRECTIVE.N.KEY */
        const Dir *rep = &r->dirs[d];
        size_t len = strlen(rep->name);
        if (rep->head && rep->head->repeat && !strncmp(name, rep->name, len) && name[len] == '.') {
            set_group(r, rep, base, typed, name, v);
            return;
        }
    }
    /* a key as DIRECTIVE.KEY (buds.angle) or a bare value (years); then a key by its name alone */
    const SchRow *hit = NULL;
    int hits = 1;
    for (int i = 0; i < t->n && !hit; i++) {
        const SchRow *row = &t->rows[i];
        if (!row->group && !lang_texture_line(row->name) && !is_mode_row(row) && !strcmp(row->name, name)) hit = row;
    }
    if (!hit) {
        hits = 0;
        for (int i = 0; i < t->n; i++) {
            const SchRow *row = &t->rows[i];
            if (!row->group && strchr(row->name, '.') && !strcmp(key_of(row), name)) hit = hit ? hit : row, hits++;
        }
    }
    if (!hit || !settable(hit)) {
        if (r->p->sibling) return; /* a name of the model it was set for */
        const char *names[MAX_NAMES];
        int k = 0;
        for (int i = 0; i < r->p->nparams && k < 100; i++) names[k++] = r->p->params[i].name;
        for (int i = 0; i < t->n && k < MAX_NAMES - 1; i++) {
            const SchRow *row = &t->rows[i];
            if (row->group || !settable(row)) continue;
            names[k++] = key_of(row);
            if (strchr(row->name, '.')) names[k++] = row->name;
        }
        char near[256];
        int found = closest_list(name, names, k, near, sizeof near);
        if (hit || sch_find(t, name, NULL)) /* a word, a direction, a mode (buds) */
            ERR(r, 0, 0, "--set %s: '%s' is not a number (write it in the block)", typed, name);
        else
            ERR(r, 0, 0, "--set %s: %s block '%s' has no parameter '%s'%s%s%s", typed, t->kind, /* sch_set_check's */
                syl_program_name(r->p), name, found ? " (did you mean " : "", found ? near : "", found ? "?)" : "");
        return;
    }
    if (hits > 1) { /* none today: kept so that a new key cannot make a name mean two things */
        ERR(r, 0, 0, "--set %s: '%s' is a key of several directives: name one, as %s", typed, name, hit->name);
        return;
    }
    const SchRow *head = head_of(r, hit);
    const SchSlot *hs = head ? slot_of(r, head) : NULL;
    if (hit->when && hs && hs->store != SCH_AT_NONE && base) {
        int now = stored_int(hs, base), want = sch_word_index(head->words, hit->when);
        if (now != word_value(hs, want)) {
            if (r->p->sibling) return; /* meant for a model of that mode */
            const char *words[32], *nowword = "?";
            char tmp[256];
            size_t nw = split_words(head->words, words, 32, tmp, sizeof tmp);
            for (size_t w = 0; w < nw; w++)
                if (word_value(hs, (int)w) == now) nowword = words[w];
            size_t len = dir_len(hit->name);
            ERR(r, 0, 0, "--set %s: '%s' is a key of '%.*s %s', and this block has '%.*s %s'", typed, key_of(hit),
                (int)len, hit->name, hit->when, (int)len, hit->name, nowword);
            return;
        }
    }
    set_number(r, typed, hit, base, v);
}

static int read_block(Reader *r, void *base, int *set_errors) {
    r->elem = -1;
    list_dirs(r);
    read_lines(r, base);
    int before = r->errors;
    const SylProgram *p = r->p;
    for (int i = 0; i < p->noverrides; i++) { /* in the order given: the last one wins */
        const char *name = p->set_local ? p->set_local[i] : NULL;
        if (name && !is_param(p, name)) set_one(r, base, p->overrides[i].name, name, p->overrides[i].value);
    }
    *set_errors = r->errors - before;
    return r->errors;
}

int sch_read_keyed(const SylProgram *p, const SchKeyed *k, void *base, FILE *diag, int *set_errors) {
    Reader r = {.p = p, .k = k, .diag = diag};
    return read_block(&r, base, set_errors);
}

int sch_see_keyed(const SylProgram *p, const SchTable *t, const SchSeen *seen) {
    SchKeyed k = {.t = t};
    Reader r = {.p = p, .k = &k, .seen = seen};
    int set_errors;
    return read_block(&r, NULL, &set_errors);
}
