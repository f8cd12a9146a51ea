/* A weber block's parameters as Arbaro XML (libxml2's xmlTextWriter does the escaping) or as a
 * .syl block. Both print each value as the shortest decimal that reads back to the same double,
 * so that reading what is written gives the same parameters, and writing again the same bytes. */
#include <ctype.h>
#include <stdlib.h>
#include <string.h>


#include "lang/kinds.h"
#include "util/number.h"
#include "util/paramxml.h"
#include "lang/textures.h"
#include "weber/xml.h"

/* Arbaro's order (its writer's, as in its species files): the globals, then per level. */
static const char *const arbaro_globals[] = {
    "Shape",       "Levels",       "Scale",        "ScaleV",      "BaseSize",    "Ratio",         "RatioPower",
    "Flare",       "Lobes",        "LobeDepth",    "Smooth",      "Leaves",      "LeafShape",     "LeafScale",
    "LeafScaleX",  "LeafQuality",  "LeafStemLen",  "LeafDistrib", "LeafBend",    "AttractionUp",  "PruneRatio",
    "PrunePowerLow", "PrunePowerHigh", "PruneWidth", "PruneWidthPeak", "0Scale", "0ScaleV",      "0BaseSplits"};
static const char *const arbaro_levels[] = {"DownAngle", "DownAngleV", "Rotate",    "RotateV",    "Branches",
                                            "BranchDist", "Length",    "LengthV",   "Taper",      "SegSplits",
                                            "SplitAngle", "SplitAngleV", "CurveRes", "Curve",     "CurveBack",
                                            "CurveV"};

static const WeberParamInfo *info(const char *name, bool per_level) {
    for (int i = 0; i < weber_param_count; i++)
        if (weber_param_table[i].per_level == per_level && !strcmp(weber_param_table[i].name, name))
            return &weber_param_table[i];
    return NULL;
}

static const double *slot(const WeberParams *w, const WeberParamInfo *pi) {
    return (const double *)((const char *)w + pi->offset);
}

/* The shortest %.Ng that strtod reads back as v; whole numbers without an exponent (60, not
 * 6e+01: %g turns to one only for them or for tiny values). */
static void number(char *buf, size_t n, double v) { number_write(buf, n, v); }

static const char *leaf_shape(const WeberParams *w, char *buf, size_t n) {
    switch (w->leaf_kind) {
    case WEBER_LEAF_SQUARE: return "square";
    case WEBER_LEAF_SPHERE: return "sphere";
    case WEBER_LEAF_PALM: return "palm";
    default:
        if (w->leaf_tris == 6) return "0"; /* Arbaro's default spelling of the disc */
        snprintf(buf, n, "disc%d", w->leaf_tris);
        return buf;
    }
}

/* A global's value as text (LeafShape is a word). */
static const char *global_text(const WeberParams *w, const WeberParamInfo *pi, char *buf, size_t n) {
    if (pi->type == WP_LEAFSHAPE) return leaf_shape(w, buf, n);
    number(buf, n, slot(w, pi)[0]);
    return buf;
}

/* ---- XML ---- */

int weber_write_xml(const WeberParams *w, const char *species, const SylProgram *tex, FILE *out) {
    ParamXml *x = paramxml_begin("arbaro", species);
    if (!x) return SYL_ELIMIT;
    paramxml_comment(x, " general params ");
    char v[64];
    for (size_t i = 0; i < sizeof arbaro_globals / sizeof *arbaro_globals; i++) {
        const WeberParamInfo *pi = info(arbaro_globals[i], false);
        if (pi) paramxml_param(x, pi->name, global_text(w, pi, v, sizeof v));
    }
    /* Sylva's own: an Arbaro file means convention arbaro, no seed, no envelope, no lod, ZScale 1 0 */
    const WeberParamInfo *zs = info("ZScale", false), *zv = info("ZScaleV", false);
    if (zs && slot(w, zs)[0] != zs->def[0]) paramxml_param(x, "ZScale", global_text(w, zs, v, sizeof v));
    if (zv && slot(w, zv)[0] != zv->def[0]) paramxml_param(x, "ZScaleV", global_text(w, zv, v, sizeof v));
    if (w->convention == WEBER_PAPER) paramxml_param(x, "convention", "paper");
    if (w->has_seed) {
        snprintf(v, sizeof v, "%llu", (unsigned long long)w->seed);
        paramxml_param(x, "Seed", v);
    }
    if (w->envelope) paramxml_param(x, "envelope", w->envelope);
    if (w->lod) {
        snprintf(v, sizeof v, "%d", w->lod);
        paramxml_param(x, "lod", v);
    }
    for (int l = 0; l < 4; l++) {
        char comment[32], name[64];
        snprintf(comment, sizeof comment, " level %d ", l);
        paramxml_comment(x, comment);
        for (size_t i = 0; i < sizeof arbaro_levels / sizeof *arbaro_levels; i++) {
            const WeberParamInfo *pi = info(arbaro_levels[i], true);
            if (!pi) continue;
            snprintf(name, sizeof name, "%d%s", l, pi->name);
            number(v, sizeof v, slot(w, pi)[l]);
            paramxml_param(x, name, v);
        }
    }
    if (tex) lang_textures_xml(tex, x);
    return paramxml_end(x, out);
}

/* ---- .syl ---- */

static bool is_name(const char *s) {
    if (!isalpha((unsigned char)s[0]) && s[0] != '_') return false;
    for (; *s; s++)
        if (!isalnum((unsigned char)*s) && *s != '_') return false;
    return true;
}

int weber_write_syl(const WeberParams *w, const char *species, const SylProgram *tex, const char *note, FILE *out) {
    char name[256], v[64];
    size_t n = 0;
    for (const char *s = species; *s && n + 2 < sizeof name; s++)
        name[n++] = isalnum((unsigned char)*s) || *s == '_' ? *s : '_';
    name[n] = 0;
    if (!n || isdigit((unsigned char)name[0])) {
        memmove(name + 1, name, n + 1 < sizeof name - 1 ? n + 1 : sizeof name - 2);
        name[0] = '_';
    }
    if (note) fprintf(out, "# %s\n", note);
    fprintf(out, "weber %s {\n", name);
    if (!is_name(species) || strcmp(name, species)) {
        fputs("  Species \"", out);
        for (const char *s = species; *s; s++) fputc(*s == '"' || *s == '\n' ? '_' : *s, out);
        fputs("\"\n", out);
    }
    fprintf(out, "  convention %s\n", w->convention == WEBER_PAPER ? "paper" : "arbaro");
    if (w->has_seed) fprintf(out, "  Seed %llu\n", (unsigned long long)w->seed);
    if (w->envelope) fprintf(out, "  envelope \"%s\"\n", w->envelope);
    if (w->lod) fprintf(out, "  lod %d\n", w->lod);
    for (int i = 0; i < weber_param_count; i++) {
        const WeberParamInfo *pi = &weber_param_table[i];
        if (pi->per_level) continue;
        /* a tree not by Sapling's law written as before SaplingTaperCrown was read */
        if (pi->offset == offsetof(WeberParams, SaplingTaperCrown) && !w->SaplingLaw && w->SaplingTaperCrown == 0) continue;
        fprintf(out, "  %-14s %s\n", pi->name, global_text(w, pi, v, sizeof v));
    }
    for (int i = 0; i < weber_param_count; i++) {
        const WeberParamInfo *pi = &weber_param_table[i];
        if (!pi->per_level) continue;
        fprintf(out, "  %-14s", pi->name);
        for (int l = 0; l < 4; l++) {
            number(v, sizeof v, slot(w, pi)[l]);
            fprintf(out, " %s", v);
        }
        fputc('\n', out);
    }
    if (tex) lang_textures_syl(tex, out);
    fputs("}\n", out);
    return ferror(out) ? SYL_EIO : SYL_OK;
}

/* The species' name: a `Species "…"` line (kept by a .syl written from XML), else the model's. */
static const char *species_name(const SylProgram *p) {
    int n;
    const SylDirective *ds = syl_program_directives(p, &n);
    const char *name = syl_program_name(p);
    for (int i = 0; i < n; i++)
        if (!strcmp(ds[i].name, "Species") && ds[i].nargs == 1 &&
            (ds[i].args[0].kind == SYL_DARG_STRING || ds[i].args[0].kind == SYL_DARG_WORD))
            name = ds[i].args[0].text;
    return name;
}

int weber_convert(const SylProgram *p, unsigned format, const char *note, FILE *out, FILE *diag) {
    int st = lang_textures_read(p, diag); /* the texture lines are written as they stand: checked first, as sylva check does */
    if (st) return st;
    WeberParams w;
    if (weber_params_read(p, &w, diag)) return SYL_EMODEL;
    return format == KC_XML ? weber_write_xml(&w, species_name(p), p, out)
                            : weber_write_syl(&w, species_name(p), p, note, out);
}
