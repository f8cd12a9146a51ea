/* The model's settings (derive, angle, step, ..., colour): their table of ranges, checked and stored. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lang/compiler.h"
#include "lang/parse_state.h"
#include "lang/schema.h"
#include "lang/textures.h"
#include "sylva/lod.h"

typedef struct SettingDef {
    const char *name;
    int block; /* -1: the model's level; else only in decompose/interpret blocks */
    double min, max;
    bool integer;
    int nargs;       /* values it takes */
    bool repeatable; /* colour: once per index */
} SettingDef;

static const SettingDef settings[] = {
#define SETTING(nm, ty, blk, na, rep, lo, hi, d, words, unit, doc) {nm, blk, lo, hi, ty == SCH_INTEGER, na, rep},
#include "settings.def"
#undef SETTING
#define TEXTURE_LINE(nm, ty, doc) {nm, -1, 0, 0, false, 1, false},
#include "lang/textures.def"
};

static bool in_range(Compiler *c, const SettingDef *def, double v, SylLoc loc, const char *typed);
static void store(Compiler *c, const SettingDef *def, int block, double v);

/* `direction forward|backward [when EXPR]`, EXPR over `step` and the model's values. */
static void direction(Compiler *c, Stmt *s) {
    SylProgram *p = c->p;
    const Expr *w = s->args.v[0];
    bool fwd = w->kind == EX_NAME && !strcmp(w->name, "forward"),
         back = w->kind == EX_NAME && !strcmp(w->name, "backward");
    if (!fwd && !back) {
        diag_error(c->d, w->loc, "'direction' is forward or backward (optionally followed by `when EXPR`)");
        return;
    }
    p->backward = back;
    if (!s->value) return;
    const char *names[1] = {"step"};
    Scope scope = {.names = names, .n = 1};
    p->direction_when = cc_expr(c, s->value, &scope, NULL);
}

const char *syl_setting_name(int i) {
    return i >= 0 && i < (int)(sizeof settings / sizeof *settings) ? settings[i].name : NULL;
}

void cc_setting(Compiler *c, Stmt *s, SylLoc *seen) {
    SylProgram *p = c->p;
    int i = 0, n = (int)(sizeof settings / sizeof *settings);
    while (i < n && strcmp(settings[i].name, s->name)) i++;
    if (i == n) return; /* the lexer only makes SETTING of known names */
    const SettingDef *def = &settings[i];
    if ((def->block < 0) != (s->block == BLOCK_PRODUCE)) {
        diag_error(c->d, s->loc, def->block < 0 ? "'%s' belongs to the model, not to a block"
                                                : "'%s' belongs in a decompose or interpret block",
                   s->name);
        return;
    }
    if (s->args.n != def->nargs) {
        if (def->nargs == 1) diag_error(c->d, s->loc, "'%s' takes one value", s->name);
        else diag_error(c->d, s->loc, "'%s' takes %d values separated by commas", s->name, def->nargs);
        return;
    }
    int slot = def->block < 0 ? i : i + s->block; /* maxdepth per block */
    if (!def->repeatable) {
        if (seen[slot].first_line) {
            diag_error(c->d, s->loc, "'%s' is set twice (first at line %d)", s->name, seen[slot].first_line);
            return;
        }
        seen[slot] = s->loc;
    }
    if (lang_texture_line(s->name)) { /* with its file in quotes it is a directive (grammar/parser.y) */
        diag_error(c->d, s->loc, "'%s' takes a file name in quotes: %s \"F.png\"", s->name, s->name);
        return;
    }
    if (!strcmp(s->name, "direction")) {
        direction(c, s);
        return;
    }
    if (s->value) { /* the grammar takes `when` after any setting word */
        diag_error(c->d, s->value->loc, "only 'direction' takes `when`");
        return;
    }
    double v[4];
    for (int k = 0; k < def->nargs; k++)
        if (!cc_const(c, s->args.v[k], &v[k])) return;
    if (!strcmp(s->name, "colour")) {
        if (v[0] != floor(v[0]) || v[0] < 0 || v[0] > 255) {
            diag_error(c->d, s->args.v[0]->loc, "a colour index is a whole number from 0 to 255");
            return;
        }
        for (int k = 1; k < 4; k++)
            if (v[k] < 0 || v[k] > 1) {
                diag_error(c->d, s->args.v[k]->loc, "colour components go from 0 to 1");
                return;
            }
        int idx = (int)v[0];
        for (int k = 0; k < 3; k++) p->colours[idx][k] = (float)v[k + 1];
        p->colour_set[idx] = true;
        return;
    }
    if (!strcmp(s->name, "tropism")) {
        for (int k = 0; k < 4; k++) p->tropism[k] = v[k];
        return;
    }
    if (!in_range(c, def, v[0], s->args.v[0]->loc, NULL)) return;
    store(c, def, s->block, v[0]);
}

/* A value of def within its range, or an error at loc (typed: the --set that gave it). */
static bool in_range(Compiler *c, const SettingDef *def, double v, SylLoc loc, const char *typed) {
    char set[128] = "";
    if (typed) snprintf(set, sizeof set, "--set %s=%.15g: ", typed, v);
    if (v < def->min || v > def->max) {
        diag_error(c->d, loc, "%s'%s' %.15g is out of range (%s %.17g)", set, def->name, v,
                   v > def->max ? "at most" : "at least", v > def->max ? def->max : def->min);
        return false;
    }
    if (def->integer && v != floor(v)) {
        diag_error(c->d, loc, "%s'%s' must be a whole number from %.15g to %.17g", set, def->name, def->min,
                   def->max);
        return false;
    }
    return true;
}

static void store(Compiler *c, const SettingDef *def, int block, double v) {
    SylProgram *p = c->p;
    const char *name = def->name;
    if (!strcmp(name, "derive")) p->derive = (int)v;
    else if (!strcmp(name, "angle")) p->angle = v;
    else if (!strcmp(name, "step")) p->step = v;
    else if (!strcmp(name, "width")) p->width = v;
    else if (!strcmp(name, "seed")) p->seed = (uint64_t)v;
    else if (!strcmp(name, "widthfactor")) p->widthfactor = v;
    else if (!strcmp(name, "lod")) p->lod = (int)v;
    else p->tables[block == BLOCK_DECOMPOSE ? TABLE_DECOMPOSE : TABLE_INTERPRET].maxdepth = (int)v;
}

/* --set reaches a setting of one value by its name, a tropism component as tropism.1 to
 * tropism.4 (x, y, z, elasticity: the order of the line) and a block's maxdepth as
 * decompose.maxdepth or interpret.maxdepth, a colour's component as colour.I.r, .g or .b. */
static const char *const set_names[] = {"derive", "angle", "step", "width", "seed", "widthfactor", "lod",
                                        "tropism.1", "tropism.2", "tropism.3", "tropism.4",
                                        "decompose.maxdepth", "interpret.maxdepth"};
enum { NSET_NAMES = sizeof set_names / sizeof *set_names };

int cc_setting_names(const char **out, int max) {
    int n = 0;
    for (; n < NSET_NAMES && n < max; n++) out[n] = set_names[n];
    return n;
}

/* colour.I.r (or .g, .b): one component of a colour the model sets; the others stay. A
 * colour the model leaves to the palette has no line to change: say so. */
static int colour_override(Compiler *c, const char *name, double v, const char *typed) {
    SylProgram *p = c->p;
    char comp = 0, *end;
    long idx = strtol(name + 7, &end, 10);
    if (end == name + 7 || *end != '.' || !end[1] || end[2] || !strchr("rgb", end[1])) {
        diag_error(c->d, (SylLoc){0}, "--set %s: a colour's component is colour.I.r, colour.I.g or colour.I.b", typed);
        return 0;
    }
    comp = end[1];
    if (idx < 0 || idx > 255) {
        diag_error(c->d, (SylLoc){0}, "--set %s: a colour index is a whole number from 0 to 255", typed);
        return 0;
    }
    if (!p->colour_set[idx]) {
        diag_error(c->d, (SylLoc){0}, "--set %s: model '%s' sets no colour %ld (write `colour %ld, R, G, B` in it)",
                   typed, p->name, idx, idx);
        return 0;
    }
    if (v < 0 || v > 1) {
        diag_error(c->d, (SylLoc){0}, "--set %s=%.15g: colour components go from 0 to 1", typed, v);
        return 0;
    }
    p->colours[idx][comp == 'r' ? 0 : comp == 'g' ? 1 : 2] = (float)v;
    return 1;
}

int cc_setting_override(Compiler *c, const char *name, double v, const char *typed) {
    int n = (int)(sizeof settings / sizeof *settings), i = 0;
    if (!strncmp(name, "colour.", 7)) return colour_override(c, name, v, typed);
    if (!strncmp(name, "tropism.", 8) && name[8] >= '1' && name[8] <= '4' && !name[9]) {
        while (strcmp(settings[i].name, "tropism")) i++;
        if (!in_range(c, &settings[i], v, (SylLoc){0}, typed)) return 0;
        c->p->tropism[name[8] - '1'] = v;
        return 1;
    }
    int block = BLOCK_PRODUCE;
    if (!strcmp(name, "decompose.maxdepth")) block = BLOCK_DECOMPOSE, name = "maxdepth";
    else if (!strcmp(name, "interpret.maxdepth")) block = BLOCK_INTERPRET, name = "maxdepth";
    while (i < n && strcmp(settings[i].name, name)) i++;
    if (i == n || settings[i].nargs != 1 || (settings[i].block >= 0) != (block != BLOCK_PRODUCE)) return -1;
    if (!in_range(c, &settings[i], v, (SylLoc){0}, typed)) return 0;
    store(c, &settings[i], block, v);
    return 1;
}
