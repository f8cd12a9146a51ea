/* Reading a `weber` block's directives against the parameter table (params.def). */
#include "weber/params.h"

#include <stdlib.h>
#include <string.h>

#include "lang/program.h"
#include "lang/textures.h"
#include "util/closest.h"

#define WP_G(f, nm, ty, lo, hi, lop, hop, d, unit, mean) \
    {nm, false, ty, lo, hi, lop, hop, {d, d, d, d}, offsetof(WeberParams, f), mean},
#define WP_L(f, nm, ty, lo, hi, lop, hop, d0, d1, d2, d3, unit, mean) \
    {nm, true, ty, lo, hi, lop, hop, {d0, d1, d2, d3}, offsetof(WeberParams, f), mean},
const WeberParamInfo weber_param_table[] = {
#include "params.def"
};
#undef WP_G
#undef WP_L
const int weber_param_count = (int)(sizeof weber_param_table / sizeof weber_param_table[0]);


static double *slot(WeberParams *w, const WeberParamInfo *pi) { return (double *)((char *)w + pi->offset); }

void weber_params_default(WeberParams *w) {
    memset(w, 0, sizeof *w);
    for (int i = 0; i < weber_param_count; i++) {
        const WeberParamInfo *pi = &weber_param_table[i];
        double *v = slot(w, pi);
        if (pi->per_level)
            for (int l = 0; l < 4; l++) v[l] = pi->def[l];
        else
            v[0] = pi->def[0];
    }
    w->leaf_kind = WEBER_LEAF_DISC;
    w->leaf_tris = 6;
    w->convention = WEBER_ARBARO;
    w->seed = 13;
}

static const WeberParamInfo *find(const char *name, bool per_level) {
    for (int i = 0; i < weber_param_count; i++)
        if (weber_param_table[i].per_level == per_level && !strcmp(weber_param_table[i].name, name))
            return &weber_param_table[i];
    return NULL;
}

/* The leaf shape words Arbaro's mesher knows (any number is its "0", the disc). */
static bool leaf_shape(const char *s, WeberParams *w) {
    if (!strcmp(s, "disc") || !strcmp(s, "0")) { w->leaf_kind = WEBER_LEAF_DISC; w->leaf_tris = 6; return true; }
    if (!strncmp(s, "disc", 4) && s[4] >= '1' && s[4] <= '9' && !s[5]) {
        w->leaf_kind = WEBER_LEAF_DISC;
        w->leaf_tris = s[4] - '0';
        return true;
    }
    if (!strcmp(s, "square")) { w->leaf_kind = WEBER_LEAF_SQUARE; w->leaf_tris = 2; return true; }
    if (!strcmp(s, "sphere")) { w->leaf_kind = WEBER_LEAF_SPHERE; w->leaf_tris = 20; return true; }
    if (!strcmp(s, "palm")) { w->leaf_kind = WEBER_LEAF_PALM; w->leaf_tris = 6; return true; }
    return false;
}

#define number_of sch_number

/* One value of parameter pi; stores it at *v. Returns the errors (0 or 1). */
static int read_value(const SylProgram *p, FILE *diag, const SylDirective *d, const SylDirArg *a,
                      const WeberParamInfo *pi, const char *shown, WeberParams *w, double *v) {
    if (pi->type == WP_LEAFSHAPE) {
        double unused;
        if (number_of(a, &unused)) { leaf_shape("0", w); return 0; }
        if ((a->kind == SYL_DARG_WORD || a->kind == SYL_DARG_STRING) && leaf_shape(a->text, w)) return 0;
        char near[200] = "";
        bool word = a->kind == SYL_DARG_WORD || a->kind == SYL_DARG_STRING;
        if (word) sch_suggest_word(sch_find(&sch_weber, "LeafShape", NULL)->words, a->text, near, sizeof near);
        if (!near[0] && word && (!strcmp(a->text, "oval") || closest_near(a->text, "oval"))) /* docs/weberpenn.md's name of disc */
            snprintf(near, sizeof near, " (did you mean 'disc', the oval?)");
        syl_directive_error(p, diag, d, a, "LeafShape must be 0, disc, disc1 .. disc9, square, sphere or palm%s", near);
        return 1;
    }
    double x;
    if (!number_of(a, &x)) {
        syl_directive_error(p, diag, d, a, "%s takes a number", shown);
        return 1;
    }
    char why[160];
    if (!sch_value_ok(&sch_weber.rows[pi - weber_param_table], x, why, sizeof why)) { /* the same row of params.def */
        syl_directive_error(p, diag, d, a, "%s %s", shown, why);
        return 1;
    }
    *v = x;
    return 0;
}

static int unknown(const SylProgram *p, FILE *diag, const SylDirective *d) {
    char near[480];
    sch_suggest(&sch_weber, d->name, near, sizeof near);
    syl_directive_error(p, diag, d, NULL, "unknown weber parameter '%s'%s", d->name,
                        near[0] ? near : " (docs/weberpenn.md lists them)");
    return 1;
}

static int read_all(const SylProgram *p, WeberParams *w, FILE *diag);

static int read_extra(const SylProgram *p, FILE *diag, const SylDirective *d, WeberParams *w) {
    if (!strcmp(d->name, "lod")) return lang_lod_check(p, d, diag); /* sylva mesh reads it (lang/lod.c) */
    const SylDirArg *a = d->nargs ? &d->args[0] : NULL;
    if (d->nargs != 1) {
        syl_directive_error(p, diag, d, d->nargs > 1 ? &d->args[1] : NULL, "%s takes one value", d->name);
        return 1;
    }
    if (!strcmp(d->name, "convention")) {
        const char *words = sch_find(&sch_weber, "convention", NULL)->words; /* WEBER_ARBARO, WEBER_PAPER */
        int k = a->kind == SYL_DARG_WORD ? sch_word_index(words, a->text) : -1;
        if (k >= 0) w->convention = k;
        else {
            char near[200] = "";
            if (a->kind == SYL_DARG_WORD) sch_suggest_word(words, a->text, near, sizeof near);
            syl_directive_error(p, diag, d, a, "convention is 'arbaro' or 'paper'%s", near);
            return 1;
        }
    } else if (!strcmp(d->name, "Seed")) {
        double x;
        if (!number_of(a, &x) || x < 0 || x != floor(x) || x > 9.0e15) {
            syl_directive_error(p, diag, d, a, "Seed takes a whole number >= 0");
            return 1;
        }
        w->has_seed = true;
        w->seed = (uint64_t)x;
    } else if (!strcmp(d->name, "envelope")) {
        if (a->kind != SYL_DARG_STRING) {
            syl_directive_error(p, diag, d, a, "envelope takes a file name in quotes (a closed .obj mesh)");
            return 1;
        }
        w->envelope = a->text;
        w->envelope_at = d;
    } /* Species: a name, as in Arbaro's files; nothing reads it */
    return 0;
}

/* --set lod=N: Sylva's `lod` line, checked here as the block's own would be. */
static int lod_sets(const SylProgram *p, FILE *diag) {
    int errors = 0;
    bool param = false;
    for (int i = 0; i < p->nparams; i++) param |= !strcmp(p->params[i].name, "lod");
    for (int i = 0; i < p->noverrides && !param; i++)
        if (p->set_local && p->set_local[i] && !strcmp(p->set_local[i], "lod"))
            errors += lang_lod_set_check(p, p->overrides[i].value, p->overrides[i].name, diag);
    return errors;
}

static bool is_param(const SylProgram *p, const char *name) {
    for (int i = 0; i < p->nparams; i++)
        if (!strcmp(p->params[i].name, name)) return true;
    return false;
}

/* --set NAME=VALUE over the block's lines, in the order given (the last one wins): any
 * number of the table (`Levels`, `Scale`, `1DownAngle`), checked by the schema's reader
 * (lang/schema.c) for its name and range; `lod` as lod_sets checks it. A param takes its
 * own value (lang/overrides.c). */
static int table_sets(const SylProgram *p, WeberParams *w, FILE *diag) {
    int errors = 0;
    for (int i = 0; i < p->noverrides; i++) {
        const char *name = p->set_local ? p->set_local[i] : NULL;
        if (!name || is_param(p, name) || !strcmp(name, "lod")) continue;
        const SchRow *row;
        int level;
        if (p->sibling && !sch_find(&sch_weber, name, &level)) continue; /* meant for another model */
        if (sch_set_check(p, diag, &sch_weber, p->overrides[i].name, name, p->overrides[i].value, &row, &level)) {
            errors++;
            continue;
        }
        double v = p->overrides[i].value;
        const WeberParamInfo *pi = find(row->name, row->levels > 0);
        if (pi) slot(w, pi)[pi->per_level ? level : 0] = v;
        else if (!strcmp(row->name, "Seed")) w->has_seed = true, w->seed = (uint64_t)v;
    }
    return errors;
}

int weber_params_check(const SylProgram *p, FILE *diag) {
    WeberParams w;
    int errors = read_all(p, &w, diag), set_errors = lod_sets(p, diag) + table_sets(p, &w, diag);
    if (!errors && !set_errors) sch_keep(p, &w, sizeof w); /* the build takes it: read once */
    return !errors && set_errors ? -set_errors : errors + set_errors; /* negative: only the command line's */
}

int weber_params_read(const SylProgram *p, WeberParams *w, FILE *diag) {
    if (sch_kept(p, w, sizeof *w)) return 0;
    return read_all(p, w, diag) + lod_sets(p, diag) + table_sets(p, w, diag);
}

static int read_all(const SylProgram *p, WeberParams *w, FILE *diag) {
    weber_params_default(w);
    sch_count_read(p);
    int n = 0, errors = 0;
    const SylDirective *ds = syl_program_directives(p, &n);
    const SylDirective *splits_at[4] = {0}, *levels_at = NULL;
    for (int i = 0; i < n; i++) {
        const SylDirective *d = &ds[i];
        if (lang_texture_line(d->name)) continue; /* lang/textures.c reads it */
        const WeberParamInfo *pi = find(d->name, false);
        const SchRow *row = pi ? NULL : sch_find(&sch_weber, d->name, NULL);
        if (row && !row->levels) { errors += read_extra(p, diag, d, w); continue; } /* convention, Seed, ... */
        int level = -1; /* a single level (digit prefix); -1: a list from level 0 */
        if (!pi) pi = find(d->name, true);
        if (!pi && d->name[0] >= '0' && d->name[0] <= '9' && (pi = find(d->name + 1, true)) != NULL) {
            level = d->name[0] - '0';
            if (level > 3) {
                syl_directive_error(p, diag, d, NULL, "levels above 3 reuse level 3's parameters: write 3%s",
                                    d->name + 1);
                errors++;
                continue;
            }
        }
        if (!pi) { errors += unknown(p, diag, d); continue; }
        int most = pi->per_level && level < 0 ? 4 : 1;
        if (d->nargs < 1 || d->nargs > most) {
            if (most == 4)
                syl_directive_error(p, diag, d, d->nargs ? &d->args[4] : NULL,
                                    "%s takes 1 to 4 values, for levels 0 to 3", d->name);
            else
                syl_directive_error(p, diag, d, d->nargs ? &d->args[1] : NULL, "%s takes one value", d->name);
            errors++;
            continue;
        }
        double *v = slot(w, pi);
        for (int k = 0; k < d->nargs; k++) {
            int l = level >= 0 ? level : k;
            char shown[64];
            if (pi->per_level) snprintf(shown, sizeof shown, "%d%s", l, pi->name);
            else snprintf(shown, sizeof shown, "%s", pi->name);
            errors += read_value(p, diag, d, &d->args[k], pi, shown, w, pi->per_level ? &v[l] : &v[0]);
            if (pi->per_level && !strcmp(pi->name, "SegSplits")) splits_at[l] = d;
        }
        if (!strcmp(pi->name, "Levels")) levels_at = d;
    }
    (void)levels_at;
    w->lod = (int)lang_directive_lod(p);
    /* Arbaro refuses splitting without an angle to split by. */
    for (int l = 0; l < 4 && l < (int)w->Levels; l++)
        if (w->SegSplits[l] > 0 && w->SplitAngle[l] == 0 && splits_at[l]) {
            syl_directive_error(p, diag, splits_at[l], NULL, "%dSegSplits %g needs a %dSplitAngle above 0", l,
                                w->SegSplits[l], l);
            errors++;
        }
    return errors;
}
