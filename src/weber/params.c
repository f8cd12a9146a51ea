/* Reading a `weber` block: the schema's reader of NAME VALUE lines (lang/schema_lines.c) with
 * params.def's rows (a per-level one as `1DownAngle 60` or `DownAngle 0 60 45 45`). What is
 * weber's own is here: where each value is kept, LeafShape's words, the messages' words, and
 * the checks once the lines are read. A `from "species.xml"` splice is the compiler's
 * (lang/splice.c): its lines come first, the block's own after them, the last one winning. */
#include "weber/params.h"

#include <stddef.h>
#include <string.h>

#include "lang/program.h"
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


/* Where each row is kept in WeberParams (params.def's order, the schema's): a number, a number
 * per level, Sylva's lines; LeafShape is read here (SCH_AT_KIND: a number or a word). */
#define WP_OFF_INT(f) offsetof(WeberParams, f)
#define WP_OFF_U64(f) offsetof(WeberParams, f)
#define WP_OFF_LINE(f) offsetof(WeberParams, f)
#define WP_OFF_NONE(f) 0
static const SchSlot slots[] = {
#define WP_G(f, nm, ty, ...) {.store = (int)(ty) == SCH_ENUM ? SCH_AT_KIND : SCH_AT_F64, .off = offsetof(WeberParams, f)},
#define WP_L(f, ...) {.store = SCH_AT_F64, .off = offsetof(WeberParams, f)},
#define WP_X(at, f, ...) {.store = SCH_AT_##at, .off = WP_OFF_##at(f)},
#include "params.def"
#undef WP_G
#undef WP_L
};

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

/* LeafShape: a number (the disc) or one of the words. */
static int leaf_line(SchLineRead *r, const SchRow *row, const SylDirective *d, void *base) {
    WeberParams *w = base;
    if (d->nargs != 1) {
        sch_lines_error(r, d, d->nargs > 1 ? &d->args[1] : NULL, "%s takes one value", d->name);
        return 0;
    }
    const SylDirArg *a = &d->args[0];
    double unused;
    if (sch_number(a, &unused)) return leaf_shape("0", w), 0;
    bool word = a->kind == SYL_DARG_WORD || a->kind == SYL_DARG_STRING;
    if (word && leaf_shape(a->text, w)) return 0;
    char near[200] = "";
    if (word) sch_suggest_word(row->words, a->text, near, sizeof near);
    if (!near[0] && word && (!strcmp(a->text, "oval") || closest_near(a->text, "oval"))) /* docs/weberpenn.md's name of disc */
        snprintf(near, sizeof near, " (did you mean 'disc', the oval?)");
    sch_lines_error(r, d, a, "LeafShape must be 0, disc, disc1 .. disc9, square, sphere or palm%s", near);
    return 0;
}

/* The words of weber's messages (the reader's own where none). */
static void say(SchProblem *pr, char *buf, size_t size) {
    const char *row = pr->row ? pr->row->name : "";
    switch (pr->what) {
    case SCH_BAD_UNKNOWN:
        snprintf(buf, size, "unknown weber parameter '%s'%s", pr->name, pr->hint[0] ? pr->hint : " (docs/weberpenn.md lists them)");
        break;
    case SCH_BAD_NUMBER:
    case SCH_BAD_RANGE:
        if (!strcmp(row, "Seed")) snprintf(buf, size, "Seed takes a whole number >= 0");
        break;
    case SCH_BAD_WORD: snprintf(buf, size, "convention is 'arbaro' or 'paper'%s", pr->hint); break;
    case SCH_BAD_FILE: snprintf(buf, size, "envelope takes a file name in quotes (a closed .obj mesh)"); break;
    default: break;
    }
}

static void took(void *base, const SchRow *row) {
    if (!strcmp(row->name, "Seed")) ((WeberParams *)base)->has_seed = true;
}

/* After the lines: the envelope's name, `lod`, and Arbaro's refusal to split without an angle
 * to split by (at the line that last gave each level's SegSplits). */
static int lines_done(SchLineRead *r, void *base) {
    WeberParams *w = base;
    const SylProgram *p = sch_lines_program(r);
    if (w->envelope_at) w->envelope = w->envelope_at->args[0].text;
    w->lod = (int)lang_directive_lod(p);
    int n = 0, errors = 0;
    const SylDirective *ds = syl_program_directives(p, &n), *splits_at[4] = {0};
    const SchRow *splits = sch_find(&sch_weber, "SegSplits", NULL);
    for (int i = 0; i < n; i++) {
        int level;
        if (sch_find(&sch_weber, ds[i].name, &level) != splits || level > 3) continue;
        for (int k = 0; k < ds[i].nargs && k < (level >= 0 ? 1 : 4); k++) splits_at[level >= 0 ? level : k] = &ds[i];
    }
    for (int l = 0; l < 4 && l < (int)w->Levels; l++)
        if (w->SegSplits[l] > 0 && w->SplitAngle[l] == 0 && splits_at[l]) {
            syl_directive_report_error(p, sch_lines_diag(r), splits_at[l], NULL, "%dSegSplits %g needs a %dSplitAngle above 0",
                                       l, w->SegSplits[l], l);
            errors++;
        }
    return errors;
}

static const SchLines weber_lines = {
    .t = &sch_weber,
    .slots = slots,
    .nslots = (int)(sizeof slots / sizeof *slots),
    .textures = true,
    .again = true, /* a `from` splice's lines, then the block's own */
    .say = say,
    .line = leaf_line,
    .took = took,
    .lines_done = lines_done,
};

void weber_params_default(WeberParams *w) {
    memset(w, 0, sizeof *w);
    sch_lines_defaults(&weber_lines, w);
    w->leaf_kind = WEBER_LEAF_DISC;
    w->leaf_tris = 6;
}

static int read_all(const SylProgram *p, void *params, FILE *diag, int *set_errors) {
    weber_params_default(params);
    sch_count_read(p);
    return sch_read_lines(p, &weber_lines, params, diag, set_errors);
}

int weber_params_check(const SylProgram *p, FILE *diag) {
    WeberParams w;
    return sch_check_once(p, &w, sizeof w, read_all, diag);
}

int weber_params_read(const SylProgram *p, WeberParams *w, FILE *diag) {
    return sch_read_once(p, w, sizeof *w, read_all, diag);
}
