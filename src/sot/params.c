/* The directives of a `grow` block: one table (params.def, which the schema's sch_grow and
 * `sylva describe` read too) says what each accepts, with ranges and defaults; reading fills
 * GrowParams over the defaults and reports every wrong line. docs/growth.md is the user's
 * side of this table — keep the two in step.
 *
 *   DIRECTIVE [MODE [COUNT]] [VALUE] [KEY VALUE]...
 *
 * A value is a number, a one-element tuple `(expr)` (which may use a `param`, so --set can
 * change it), a tuple (x, y, z), a word or on/off. */
#include "sot/params.h"
#include "sot/reader.h"
#include "sot/shoot_rule.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "lang/program.h"
#include "lang/schema.h"
#include "lang/textures.h"
#include "util/closest.h"
#include "sylva/grow.h"
#include "sylva/lod.h"
#include "sylva/skeleton.h"

/* V_SEED: a whole number in a uint64_t; V_NAME: a model's name, into a char[64] */
typedef enum { V_NUM, V_INT, V_SEED, V_BOOL, V_VEC3, V_WORD, V_NAME } VType;

typedef struct Key {
    const char *name;
    VType type;         /* its range is the schema's row (key_row) */
    size_t off;         /* into GrowParams, or OrganSpec for `organ` */
    const char *words;  /* V_WORD: the words "a|b", the index of the one written stored */
} Key;

typedef struct Mode {
    const char *word;
    int value;
    bool count;         /* an integer follows the word (whorled N) */
    const Key *keys;    /* keys of this mode only; NULL: none */
} Mode;

typedef struct Directive {
    const char *name;
    bool repeat;        /* may appear more than once (organ) */
    bool mode_required; /* unless implied: */
    int implied;        /* the mode's index in modes when none is written (-1: none) */
    size_t mode_off;    /* where the mode's value goes */
    const Mode *modes;
    const Key *value;   /* a bare value right after the name (years 18) */
    const Key *keys;    /* keys of every mode */
} Directive;

#define G(f) offsetof(GrowParams, f)
#define O(f) offsetof(OrganSpec, f)
#define END {0}

enum { NO_MODE = (size_t)-1 };

/* the lists of params.def, as the reader's structures */
#define GROW_VALUE(var, nm, ty, l, h, f, d, u, mean) static const Key var = {nm, V_##ty, G(f), NULL};
#define GROW_KEYS(list) static const Key list##_keys[] = {
#define GROW_KEY(base, f, dir, nm, ty, l, h, d, w, u, mean) {nm, V_##ty, base(f), w},
#define GROW_KEYS_END END};
#define GROW_MODES(list, dir, dw, w, grp, mean) static const Mode list##_modes[] = {
#define GROW_MODE(word, value, count, keys) {word, value, count, keys},
#define GROW_MODES_END {0}};
#include "sot/params.def"
static const Directive directives[] = {
#define GROW_DIRECTIVE(nm, rep, req, implied, off, modes, value, keys) {nm, rep, req, implied, off, modes, value, keys},
#include "sot/params.def"
};
enum { NDIRECTIVES = sizeof directives / sizeof *directives };

/* A default of params.def into its field (a mode's word, a direction and a name are set below). */
#define DEF_NUM(lv, d, w) lv = (float)(d);
#define DEF_INT(lv, d, w) lv = (int)(d);
#define DEF_SEED(lv, d, w) lv = (uint64_t)(d);
#define DEF_BOOL(lv, d, w) lv = (d) != 0;
#define DEF_WORD(lv, d, w) lv = (uint8_t)sch_word_index(w, d);
#define DEF_VEC3(lv, d, w)
#define DEF_NAME(lv, d, w)

void grow_params_default(GrowParams *g) {
    memset(g, 0, sizeof *g);
#define ON_G(ty, f, d, w) DEF_##ty(g->f, d, w)
#define ON_O(ty, f, d, w)
#define GROW_VALUE(var, nm, ty, l, h, f, d, u, mean) ON_G(ty, f, d, NULL)
#define GROW_KEY(base, f, dir, nm, ty, l, h, d, w, u, mean) ON_##base(ty, f, d, w)
#include "sot/params.def"
#undef ON_G
#undef ON_O
    g->phyllotaxis = PHYL_ALTERNATE;
    g->laterals = 1;
    g->light = LIGHT_SHADOW;
    g->sun[1] = 1;
    g->space = SPACEM_OFF;
    g->alloc = ALLOC_BH;
    g->shoot = SHOOT_RELATIVE;
}

static void organ_default(OrganSpec *o) {
    memset(o, 0, sizeof *o);
    o->kind = SYL_KIND_LEAF;
#define ON_G(ty, f, d, w)
#define ON_O(ty, f, d, w) DEF_##ty(o->f, d, w)
#define GROW_KEY(base, f, dir, nm, ty, l, h, d, w, u, mean) ON_##base(ty, f, d, w)
#include "sot/params.def"
#undef ON_G
#undef ON_O
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

/* A number: a literal or a one-element tuple. */
/* The list "a, b or c" of a table's names. */
static void list_words(char *buf, size_t size, const char *const *names, size_t stride, size_t n) {
    buf[0] = 0;
    size_t used = 0;
    for (size_t i = 0; i < n; i++) {
        const char *w = *(const char *const *)((const char *)names + i * stride);
        int k = snprintf(buf + used, size - used, "%s%s", i == 0 ? "" : i + 1 == n ? " or " : ", ", w);
        if (k < 0 || (size_t)k >= size - used) break;
        used += (size_t)k;
    }
}

/* The schema's row of key k of directive dir (lang/schema_tables.c makes it of the same line
 * of params.def): a key's is DIRECTIVE.KEY (buds.angle), a bare value's its name (years). Its
 * range is the one the schema checks, for a line's value and for --set alike. */
static const SchRow *key_row(const char *dir, const Key *k) {
    char name[96];
    snprintf(name, sizeof name, "%s.%s", dir, k->name);
    const SchRow *row = sch_find(&sch_grow, name, NULL);
    return row ? row : sch_find(&sch_grow, k->name, NULL);
}

/* Store the value of key k from args[i] (and on); returns how many args it took, 0 on error. */
static int take_value(Reader *r, const SylDirective *d, const Key *k, const SylDirArg *args, int i, void *base) {
    if (i >= d->nargs) {
        const SylDirArg *last = i > 0 ? &args[i - 1] : NULL;
        ERR(r, last ? last->line : d->line, last ? last->col : d->col, "'%s' needs a value after it", k->name);
        return 0;
    }
    const SylDirArg *a = &args[i];
    char *field = (char *)base + k->off;
    double v;
    switch (k->type) {
    case V_NUM:
    case V_INT:
    case V_SEED:
        if (!reader_number(a, &v)) {
            ERR(r, a->line, a->col, "'%s' expects a number, not %s", k->name, kind_name(a->kind));
            return 0;
        }
        char why[160];
        if (k == &k_lod && !sch_value_ok(key_row(d->name, k), v, why, sizeof why)) {
            r->errors += lang_lod_check(r->p, d, r->diag); /* one message for every kind's `lod` */
            return 0;
        }
        if (!sch_value_ok(key_row(d->name, k), v, why, sizeof why)) {
            ERR(r, a->line, a->col, "%s %s", k->name, why);
            return 0;
        }
        if (k->type == V_NUM) *(float *)field = (float)v;
        else if (k->type == V_SEED) *(uint64_t *)field = (uint64_t)v;
        else *(int *)field = (int)v;
        return 1;
    case V_BOOL:
        if (a->kind == SYL_DARG_WORD && (!strcmp(a->text, "on") || !strcmp(a->text, "yes"))) *(bool *)field = true;
        else if (a->kind == SYL_DARG_WORD && (!strcmp(a->text, "off") || !strcmp(a->text, "no"))) *(bool *)field = false;
        else if (reader_number(a, &v) && (v == 0 || v == 1)) *(bool *)field = v == 1;
        else {
            ERR(r, a->line, a->col, "'%s' expects on or off", k->name);
            return 0;
        }
        return 1;
    case V_VEC3:
        if (a->kind != SYL_DARG_TUPLE || a->nvalues != 3) {
            ERR(r, a->line, a->col, "'%s' expects a direction (x, y, z)", k->name);
            return 0;
        }
        for (int j = 0; j < 3; j++) {
            if (!isfinite(a->values[j])) {
                ERR(r, a->line, a->col, "'%s': (x, y, z) must be finite", k->name);
                return 0;
            }
            ((float *)field)[j] = (float)a->values[j];
        }
        return 1;
    case V_NAME:
        if (a->kind != SYL_DARG_WORD || strlen(a->text) >= 64) {
            ERR(r, a->line, a->col, "'%s' expects the name of an lsystem of this file", k->name);
            return 0;
        }
        strcpy(field, a->text);
        return 1;
    case V_WORD: {
        int j = a->kind == SYL_DARG_WORD ? sch_word_index(k->words, a->text) : -1;
        if (j >= 0) {
            *(uint8_t *)field = (uint8_t)j;
            return 1;
        }
        const char *names[16];
        char tmp[256], list[256];
        size_t n = 0;
        snprintf(tmp, sizeof tmp, "%s", k->words);
        for (char *w = tmp; w && n < 16; n++) { /* "a|b" into names */
            names[n] = w;
            w = strchr(w, '|');
            if (w) *w++ = 0;
        }
        list_words(list, sizeof list, names, sizeof *names, n);
        ERR(r, a->line, a->col, "'%s' expects %s", k->name, list);
    }
        return 0;
    }
    return 0;
}

static const Key *find_key(const Key *keys, const char *name) {
    for (size_t i = 0; keys && keys[i].name; i++)
        if (!strcmp(keys[i].name, name)) return &keys[i];
    return NULL;
}

/* Side effects of a mode: buds per node and the usual divergence. */
static void apply_mode(GrowParams *g, const Directive *dir, const Mode *m, int count) {
    if (dir->modes == buds_modes) {
        g->laterals = m->value == PHYL_ALTERNATE ? 1 : m->value == PHYL_OPPOSITE ? 2 : count;
        g->divergence = m->value == PHYL_ALTERNATE ? 137.5f : m->value == PHYL_OPPOSITE ? 90.0f : 180.0f / (float)count;
    }
    if (dir->modes == shed_modes) g->shed_threshold = 0, g->bare_trunk = 0;
}

static void read_directive(Reader *r, const Directive *dir, const SylDirective *d, GrowParams *g) {
    void *base = g;
    if (dir->modes == organ_modes) {
        if (g->norgans == MAX_ORGANS) {
            ERR(r, d->line, d->col, "at most %d organ lines", MAX_ORGANS);
            return;
        }
        organ_default(&g->organs[g->norgans]);
        base = &g->organs[g->norgans++];
    }
    const SylDirArg *args = d->args;
    int i = 0;
    const Mode *mode = NULL;
    if (dir->modes) {
        if (i < d->nargs && args[i].kind == SYL_DARG_WORD)
            for (int m = 0; dir->modes[m].word; m++)
                if (!strcmp(args[i].text, dir->modes[m].word)) mode = &dir->modes[m];
        size_t nm = 0;
        while (dir->modes[nm].word) nm++;
        char list[256];
        list_words(list, sizeof list, &dir->modes[0].word, sizeof *dir->modes, nm);
        if (!mode && dir->implied >= 0 && i < d->nargs) { /* keys only: the implied mode */
            mode = &dir->modes[dir->implied];
            i--; /* nothing was read */
        }
        if (!mode && dir->mode_required) {
            if (i < d->nargs && args[i].kind == SYL_DARG_WORD)
                ERR(r, args[i].line, args[i].col, "'%s' expects %s first, not '%s'", d->name, list, args[i].text);
            else if (i < d->nargs)
                ERR(r, args[i].line, args[i].col, "'%s' expects %s first, not %s", d->name, list, kind_name(args[i].kind));
            else ERR(r, d->line, d->col, "'%s' expects %s after it", d->name, list);
            return;
        }
        if (mode) {
            i++;
            int count = 0;
            if (mode->count) {
                double v;
                if (i >= d->nargs || !reader_number(&args[i], &v) || v != floor(v) || v < 1 || v > 32) {
                    const SylDirArg *at = i < d->nargs ? &args[i] : &args[i - 1];
                    ERR(r, at->line, at->col, "'%s' expects a whole number of buds from 1 to 32 after it", mode->word);
                    return;
                }
                count = (int)v;
                i++;
            }
            if (dir->mode_off != NO_MODE) {
                if (dir->modes == organ_modes) *(uint8_t *)((char *)base + dir->mode_off) = (uint8_t)mode->value;
                else *(int *)((char *)base + dir->mode_off) = mode->value;
            }
            apply_mode(g, dir, mode, count);
        }
    }
    if (dir->value) {
        if (!take_value(r, d, dir->value, args, i < d->nargs ? i : d->nargs, base)) return;
        i++;
    }
    for (; i < d->nargs; i++) {
        const SylDirArg *a = &args[i];
        if (dir->modes == organ_modes && a->kind == SYL_DARG_SYMBOL) { /* ~leaf(0.06): kind and size */
            OrganSpec *o = base;
            const char *s = a->text[0] == '~' ? a->text + 1 : a->text;
            if (!strcmp(s, "leaf")) o->kind = SYL_KIND_LEAF;
            else if (!strcmp(s, "petal") || !strcmp(s, "flower")) o->kind = SYL_KIND_FLOWER;
            else if (!strcmp(s, "needle")) o->kind = SYL_KIND_NEEDLE;
            else {
                ERR(r, a->line, a->col, "'%s' is not an organ: use ~leaf, ~flower or ~needle", a->text);
                return;
            }
            if (a->nvalues >= 1) {
                if (!(a->values[0] > 0) || !isfinite(a->values[0])) {
                    ERR(r, a->line, a->col, "the size of '%s' must be above 0", a->text);
                    return;
                }
                o->size = (float)a->values[0];
            }
            continue;
        }
        if (a->kind != SYL_DARG_WORD) {
            ERR(r, a->line, a->col, "expected a key of '%s' here, not %s", d->name, kind_name(a->kind));
            return;
        }
        const Key *k = find_key(dir->keys, a->text);
        if (!k && mode) k = find_key(mode->keys, a->text);
        if (!k) {
            /* name the keys that would have been right */
            const Key *all[2] = {mode ? mode->keys : NULL, dir->keys};
            const char *names[64];
            size_t n = 0;
            for (int t = 0; t < 2; t++)
                for (size_t j = 0; all[t] && all[t][j].name && n < 64; j++) names[n++] = all[t][j].name;
            char list[512];
            list_words(list, sizeof list, names, sizeof *names, n);
            /* did you mean: a key, or a mode word where the mode goes (`buds alternat`) */
            size_t nn = n;
            for (int m = 0; !mode && i == 0 && dir->modes && dir->modes[m].word && nn < 64; m++)
                names[nn++] = dir->modes[m].word;
            char near[160];
            if (closest_list(a->text, names, (int)nn, near, sizeof near)) {
                ERR(r, a->line, a->col, "unknown key '%s' of '%s' (did you mean %s?)", a->text, d->name, near);
                return;
            }
            bool other_mode = false;
            for (int m = 0; dir->modes && dir->modes[m].word; m++)
                if (find_key(dir->modes[m].keys, a->text)) other_mode = true;
            if (other_mode && mode)
                ERR(r, a->line, a->col, "'%s' is not a key of '%s %s' (keys: %s)", a->text, d->name, mode->word,
                    n ? list : "none");
            else if (n) ERR(r, a->line, a->col, "unknown key '%s' of '%s' (keys: %s)", a->text, d->name, list);
            else ERR(r, a->line, a->col, "'%s%s%s' takes no keys", d->name, mode ? " " : "", mode ? mode->word : "");
            return;
        }
        int took = take_value(r, d, k, args, i + 1, base);
        if (!took) return;
        i += took;
    }
}

/* ---- --set: a directive's number by its key ("lambda"), or as DIRECTIVE.KEY ("buds.angle");
 * a bare value by the directive's name ("years"); an organ line's as organ.N.KEY. Words,
 * directions and names are not reached. ---- */

typedef struct SetKey {
    const Directive *dir;
    const Mode *mode; /* the key belongs to this mode only; NULL: to every mode */
    const Key *key;
} SetKey;

/* Every key --set reaches, under both its names; returns how many (at most max). */
static int set_keys(SetKey *out, int max) {
    int n = 0;
    for (int d = 0; d < NDIRECTIVES; d++) {
        const Directive *dir = &directives[d];
        if (dir->repeat) continue;
        if (dir->value && n < max) out[n++] = (SetKey){dir, NULL, dir->value};
        for (int k = 0; dir->keys && dir->keys[k].name && n < max; k++) out[n++] = (SetKey){dir, NULL, &dir->keys[k]};
        for (int m = 0; dir->modes && dir->modes[m].word; m++)
            for (int k = 0; dir->modes[m].keys && dir->modes[m].keys[k].name && n < max; k++)
                out[n++] = (SetKey){dir, &dir->modes[m], &dir->modes[m].keys[k]};
    }
    return n;
}

static bool settable(const Key *k) { return k->type == V_NUM || k->type == V_INT || k->type == V_SEED || k->type == V_BOOL; }

static bool is_param(const SylProgram *p, const char *name) {
    for (int i = 0; i < p->nparams; i++)
        if (!strcmp(p->params[i].name, name)) return true;
    return false;
}

/* A number v of key k into base (GrowParams or OrganSpec), within the key's range. */
static void store_number(Reader *r, const char *typed, const char *dir, const Key *k, void *base, double v) {
    char *field = (char *)base + k->off;
    if (k->type == V_BOOL) {
        if (v != 0 && v != 1) {
            ERR(r, 0, 0, "--set %s: '%s' is 1 (on) or 0 (off)", typed, k->name);
            return;
        }
        *(bool *)field = v == 1;
        return;
    }
    char why[160];
    if (k == &k_lod) {
        int e = lang_lod_set_check(r->p, v, typed, r->diag); /* as every kind's */
        r->errors += e;
        if (e) return;
    }
    if (!sch_value_ok(key_row(dir, k), v, why, sizeof why)) { /* as sch_set_check says it */
        ERR(r, 0, 0, "--set %s: '%s' %s", typed, k->name, why);
        return;
    }
    if (k->type == V_NUM) *(float *)field = (float)v;
    else if (k->type == V_SEED) *(uint64_t *)field = (uint64_t)v;
    else *(int *)field = (int)v;
}

static void set_organ(Reader *r, GrowParams *g, const char *typed, const char *name, double v);

static void set_one(Reader *r, GrowParams *g, const char *typed, const char *name, double v) {
    if (!strncmp(name, "organ.", 6)) {
        set_organ(r, g, typed, name, v);
        return;
    }
    SetKey all[128], *hit = NULL;
    int n = set_keys(all, 128), hits = 1;
    char dotted[128];
    for (int i = 0; i < n && !hit; i++) { /* DIRECTIVE.KEY (buds.angle), or a bare value (years) */
        snprintf(dotted, sizeof dotted, "%s.%s", all[i].dir->name, all[i].key->name);
        if (!strcmp(name, dotted) || (all[i].dir->value == all[i].key && !strcmp(name, all[i].key->name)))
            hit = &all[i];
    }
    if (!hit) { /* a key by its name alone (lambda): one directive's, or ambiguous */
        hits = 0;
        for (int i = 0; i < n; i++)
            if (!strcmp(name, all[i].key->name)) hit = hit ? hit : &all[i], hits++;
    }
    if (!hit || !settable(hit->key)) {
        if (r->p->sibling) return; /* a name of the model it was set for */
        const char *names[256];
        int k = 0;
        for (int i = 0; i < r->p->nparams && k < 100; i++) names[k++] = r->p->params[i].name;
        char buf[128][64];
        for (int i = 0; i < n && k < 250; i++) {
            if (!settable(all[i].key)) continue;
            names[k++] = all[i].key->name;
            snprintf(buf[i], sizeof buf[i], "%s.%s", all[i].dir->name, all[i].key->name);
            names[k++] = buf[i];
        }
        char near[256];
        int found = closest_list(name, names, k, near, sizeof near);
        if (hit || sch_find(&sch_grow, name, NULL)) /* a word, a direction, a mode (buds) */
            ERR(r, 0, 0, "--set %s: '%s' is not a number (write it in the block)", typed, name);
        else
            ERR(r, 0, 0, "--set %s: grow block '%s' has no parameter '%s'%s%s%s", typed, /* sch_set_check's words */
                syl_program_name(r->p), name, found ? " (did you mean " : "", found ? near : "", found ? "?)" : "");
        return;
    }
    if (hits > 1) { /* none today: kept so that a new key cannot make a name mean two things */
        ERR(r, 0, 0, "--set %s: '%s' is a key of several directives: name one, as %s.%s", typed, name, hit->dir->name,
            name);
        return;
    }
    const Key *k = hit->key;
    if (hit->mode && hit->dir->mode_off != NO_MODE && *(int *)((char *)g + hit->dir->mode_off) != hit->mode->value) {
        if (r->p->sibling) return; /* meant for a model of that mode */
        const char *now = "?";
        for (int m = 0; hit->dir->modes[m].word; m++)
            if (*(int *)((char *)g + hit->dir->mode_off) == hit->dir->modes[m].value) now = hit->dir->modes[m].word;
        ERR(r, 0, 0, "--set %s: '%s' is a key of '%s %s', and this block has '%s %s'", typed, k->name,
            hit->dir->name, hit->mode->word, hit->dir->name, now);
        return;
    }
    store_number(r, typed, hit->dir->name, k, g, v);
}

/* organ.N.KEY: the N-th organ line's size, count, angle, age or chance. */
static void set_organ(Reader *r, GrowParams *g, const char *typed, const char *name, double v) {
    char *end = NULL;
    long n = strtol(name + 6, &end, 10);
    if (end == name + 6 || *end != '.') {
        ERR(r, 0, 0, "--set %s: write organ.N.KEY, N the organ line from 1 (organ.1.size)", typed);
        return;
    }
    if (n < 1 || n > g->norgans) {
        if (r->p->sibling) return;
        ERR(r, 0, 0, "--set %s: grow block '%s' has %d organ line%s", typed, syl_program_name(r->p), g->norgans,
            g->norgans == 1 ? "" : "s");
        return;
    }
    const Key *k = find_key(organ_keys, end + 1);
    if (!k || k->type == V_WORD) {
        ERR(r, 0, 0, "--set %s: an organ line has no number '%s' (size, count, angle, age, chance)", typed, end + 1);
        return;
    }
    store_number(r, typed, "organ", k, &g->organs[n - 1], v);
}

/* In the order given, so that the last one wins; a param takes its own (lang/overrides.c). */
static void apply_sets(Reader *r, GrowParams *g) {
    const SylProgram *p = r->p;
    for (int i = 0; i < p->noverrides; i++) {
        const char *name = p->set_local ? p->set_local[i] : NULL;
        if (name && !is_param(p, name)) set_one(r, g, p->overrides[i].name, name, p->overrides[i].value);
    }
}

/* The shoot rule's model compiles, is an lsystem and rewrites `shoot`. */
static void check_rule(Reader *r, const SylDirective *dirs, int n, GrowParams *g) {
    int line = 0, col = 0;
    for (int i = 0; i < n; i++)
        if (!strcmp(dirs[i].name, "shoot"))
            for (int j = 0; j < dirs[i].nargs; j++)
                if (dirs[i].args[j].kind == SYL_DARG_WORD && !strcmp(dirs[i].args[j].text, g->rule))
                    line = dirs[i].args[j].line, col = dirs[i].args[j].col;
    int status = 0;
    SylProgram *q = syl_compile_model(r->p, g->rule, NULL, &status);
    const char *why = shoot_rule_check(q);
    size_t len = 0;
    const char *text = syl_program_source(r->p, &len);
    const char *names[256];
    char buf[8192];
    int nm = q ? 0 : syl_list_models(syl_program_path(r->p), text, len, names, 256, buf, sizeof buf);
    bool exists = false;
    for (int i = 0; i < nm; i++) exists |= !strcmp(names[i], g->rule);
    if (!q && !exists) ERR(r, line, col, "the shoot rule '%s' is not a model of this file", g->rule);
    else if (!q) ERR(r, line, col, "the shoot rule '%s' does not compile (see `sylva check %s:%s`)", g->rule,
                     syl_program_path(r->p), g->rule);
    else if (why) ERR(r, line, col, "the shoot rule '%s' %s", g->rule, why);
    syl_program_free(q);
}

/* Checks across directives, once all are read. */
static void check_whole(Reader *r, const SylDirective *dirs, int n, GrowParams *g) {
    if (g->space != SPACEM_OFF && g->perception <= g->occupancy) {
        int line = 0, col = 0;
        for (int i = 0; i < n; i++)
            if (!strcmp(dirs[i].name, "space")) line = dirs[i].line, col = dirs[i].col;
        ERR(r, line, col, "'space': perception (%g) must reach beyond occupancy (%g)", g->perception, g->occupancy);
    }
    if (g->alloc == ALLOC_PRIORITY && g->wmin > g->wmax) {
        int line = 0, col = 0;
        for (int i = 0; i < n; i++)
            if (!strcmp(dirs[i].name, "allocate")) line = dirs[i].line, col = dirs[i].col;
        ERR(r, line, col, "'allocate priority': wmin (%g) must not exceed wmax (%g)", g->wmin, g->wmax);
    }
    float s = sqrtf(g->sun[0] * g->sun[0] + g->sun[1] * g->sun[1] + g->sun[2] * g->sun[2]);
    if (!(s > 0) || g->sun[1] <= 0) {
        int line = 0, col = 0;
        for (int i = 0; i < n; i++)
            if (!strcmp(dirs[i].name, "light")) line = dirs[i].line, col = dirs[i].col;
        ERR(r, line, col, "'light': the sun must be above the horizon (y > 0)");
    } else
        for (int k = 0; k < 3; k++) g->sun[k] /= s;
    const double deg = 3.14159265358979323846 / 180;
    g->tropism_sin = (float)sin(g->tropism_angle * deg);
    g->tropism_cos = (float)cos(g->tropism_angle * deg);
    g->jitter_cos = g->jitter > 0 ? (float)cos(g->jitter * deg) : 1;
    g->branch_sin = (float)sin(g->branch_angle * deg);
    g->branch_cos = (float)cos(g->branch_angle * deg);
    if (g->voxel <= 0) g->voxel = g->internode;
    if (g->foliage <= 0) g->foliage = 0.4f * g->internode;
    if (g->rule[0]) check_rule(r, dirs, n, g);
}

static int read_all(const SylProgram *p, GrowParams *g, FILE *diag, int *set_errors) {
    grow_params_default(g);
    g->from = p;
    g->seed = syl_program_seed(p) ? syl_program_seed(p) : 1;
    sch_count_read(p);
    Reader r = {.p = p, .diag = diag};
    int n = 0;
    const SylDirective *dirs = syl_program_directives(p, &n);
    int first[NDIRECTIVES];
    for (int k = 0; k < NDIRECTIVES; k++) first[k] = -1;
    for (int i = 0; i < n; i++) {
        const SylDirective *d = &dirs[i];
        if (lang_texture_line(d->name)) continue; /* lang/textures.c reads it */
        int k = 0;
        while (k < NDIRECTIVES && strcmp(directives[k].name, d->name)) k++;
        if (k == NDIRECTIVES) {
            const char *names[NDIRECTIVES];
            for (int j = 0; j < NDIRECTIVES; j++) names[j] = directives[j].name;
            char list[512], near[160];
            list_words(list, sizeof list, names, sizeof *names, NDIRECTIVES);
            if (closest_list(d->name, names, NDIRECTIVES, near, sizeof near))
                ERR(&r, d->line, d->col, "unknown directive '%s' in a grow block (did you mean %s?)", d->name, near);
            else
                ERR(&r, d->line, d->col, "unknown directive '%s' in a grow block (known: %s)", d->name, list);
            continue;
        }
        if (first[k] >= 0 && !directives[k].repeat) {
            ERR(&r, d->line, d->col, "'%s' is given twice (first at line %d)", d->name, dirs[first[k]].line);
            continue;
        }
        if (first[k] < 0) first[k] = i;
        if (directives[k].modes == shed_modes && d->nargs == 0) continue;
        if (!d->nargs && (directives[k].value || directives[k].mode_required)) {
            if (directives[k].value)
                ERR(&r, d->line, d->col, "'%s' needs a value", d->name);
            else read_directive(&r, &directives[k], d, g);
            continue;
        }
        read_directive(&r, &directives[k], d, g);
    }
    int before = r.errors;
    apply_sets(&r, g);
    *set_errors = r.errors - before;
    check_whole(&r, dirs, n, g);
    return r.errors;
}

int grow_params_read(const SylProgram *p, GrowParams *g, FILE *diag) {
    if (sch_kept(p, g, sizeof *g)) return 0;
    int set_errors;
    return read_all(p, g, diag, &set_errors);
}

/* What is statically sure to grow nothing: no year (shoots need light and room, which only
 * growing tells). */
static void warn_grows_nothing(const SylProgram *p, const GrowParams *g, FILE *diag) {
    if (g->years) return;
    int n = 0, line = 0, col = 0;
    const SylDirective *dirs = syl_program_directives(p, &n);
    for (int i = 0; i < n; i++)
        if (!strcmp(dirs[i].name, "years")) line = dirs[i].line, col = dirs[i].col;
    const char *set = "";
    for (int i = 0; i < p->noverrides; i++)
        if (p->set_local[i] && !strcmp(p->set_local[i], "years")) line = col = 0, set = " by --set";
    program_warning(p, diag, line, col, "grow block '%s' grows nothing: years is 0%s (the tree is its root)",
                    syl_program_name(p), set);
}

int sot_check_grow(const SylProgram *p, FILE *diag) {
    GrowParams g;
    int set_errors, errors = read_all(p, &g, diag, &set_errors);
    if (!errors) warn_grows_nothing(p, &g, diag);
    if (!errors) sch_keep(p, &g, sizeof g); /* the growth takes it: read once */
    return errors && errors == set_errors ? -errors : errors; /* only the command line's */
}
