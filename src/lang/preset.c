/* A grow block as a preset file (docs/growth.md#presets): each directive as it stands after
 * compiling (params, expressions and a --set of a param worked out), as XML that
 * lang/arbaro.c reads back (<grow-presets>, util/paramxml.h), or as a
 * grow block. The mapping follows no list of its own: a directive's name and its words go
 * across as they are, and the grow reader checks them on the way back. */
#include <stdlib.h>
#include <string.h>

#include "lang/arbaro.h"
#include "lang/kinds.h"
#include "lang/preset.h"
#include "lang/textures.h"
#include "sylva/grow.h"
#include "util/number.h"
#include "util/paramxml.h"
#include "lang/program.h"

/* One argument as the XML reader takes it back: a number in the fewest digits that read back
 * exactly (an expression's value too), a word, a tuple (x,y,z) or a symbol ~leaf(0.06), without blanks. false: a string,
 * which no grow directive takes. */
static bool arg_text(const SylDirArg *a, char *buf, size_t n) {
    char num[40];
    switch (a->kind) {
    case SYL_DARG_NUMBER: number_write(buf, n, a->num); return true;
    case SYL_DARG_WORD: snprintf(buf, n, "%s", a->text); return true;
    case SYL_DARG_TUPLE:
        if (a->nvalues == 1) { /* (expr): its value */
            number_write(buf, n, a->values[0]);
            return true;
        }
        /* fall through */
    case SYL_DARG_SYMBOL: {
        size_t k = (size_t)snprintf(buf, n, "%s", a->kind == SYL_DARG_SYMBOL ? a->text : "");
        if (a->kind == SYL_DARG_SYMBOL && !a->nvalues) return true;
        for (int i = 0; i < a->nvalues && k < n; i++) {
            number_write(num, sizeof num, a->values[i]);
            k += (size_t)snprintf(buf + k, n - k, "%s%s", i ? "," : "(", num);
        }
        if (k < n) snprintf(buf + k, n - k, ")");
        return true;
    }
    case SYL_DARG_STRING: return false;
    }
    return false;
}

/* A directive's words, space-separated (malloc'ed; NULL: out of memory, or *bad the argument
 * that cannot be written). */
static char *line_text(const SylDirective *d, const SylDirArg **bad) {
    size_t size = 1;
    for (int i = 0; i < d->nargs; i++) size += 48 + (d->args[i].text ? strlen(d->args[i].text) : 0) + 24 * (size_t)d->args[i].nvalues;
    char *s = malloc(size);
    if (!s) return NULL;
    size_t k = 0;
    s[0] = 0;
    for (int i = 0; i < d->nargs; i++) {
        if (!arg_text(&d->args[i], s + k + (i > 0), size - k - (i > 0))) {
            *bad = &d->args[i];
            free(s);
            return NULL;
        }
        if (i) s[k] = ' ';
        k += strlen(s + k);
    }
    return s;
}

/* Every directive can be written: 0, or SYL_EUSAGE with an error at the one that cannot. */
static int writable(const SylProgram *p, FILE *diag) {
    int n;
    const SylDirective *ds = syl_program_directives(p, &n);
    if (syl_program_kind(p) != SYL_MODEL_GROW) {
        program_say(p, diag, DIAG_ERROR, NULL, "'%s' is a %s block: a preset holds a grow block", syl_program_name(p),
                          syl_model_kind_name(syl_program_kind(p)));
        return SYL_EUSAGE;
    }
    for (int i = 0; i < n; i++) {
        const SylDirective *d = &ds[i];
        if (lang_texture_line(d->name)) continue; /* written by lang_textures_xml / _syl */
        for (int j = 0; j < d->nargs; j++)
            if (!strcmp(d->name, "shoot") && d->args[j].kind == SYL_DARG_WORD && !strcmp(d->args[j].text, "rule")) {
                syl_directive_report_error(p, diag, d, &d->args[j],
                                           "a shoot rule names an lsystem of the file: a preset holds the grow block alone");
                return SYL_EUSAGE;
            } else if (d->args[j].kind == SYL_DARG_STRING) {
                syl_directive_report_error(p, diag, d, &d->args[j], "a preset holds numbers and words, not a string");
                return SYL_EUSAGE;
            }
    }
    return SYL_OK;
}

int syl_grow_write_preset(const SylProgram *p, FILE *out, FILE *diag) {
    int st = writable(p, diag);
    if (st) return st;
    ParamXml *x = paramxml_begin(SYL_GROW_PRESET_ROOT, syl_program_name(p));
    if (!x) return SYL_ELIMIT;
    int n;
    const SylDirective *ds = syl_program_directives(p, &n);
    for (int i = 0; i < n && !st; i++) {
        if (lang_texture_line(ds[i].name)) continue;
        const SylDirArg *bad = NULL;
        char *value = line_text(&ds[i], &bad);
        if (!value) st = SYL_ELIMIT;
        else paramxml_param(x, ds[i].name, value);
        free(value);
    }
    lang_textures_xml(p, x);
    int written = paramxml_end(x, st ? NULL : out);
    return st ? st : written;
}

int syl_grow_write_syl(const SylProgram *p, const char *note, FILE *out, FILE *diag) {
    int st = writable(p, diag);
    if (st) return st;
    if (note) fprintf(out, "# %s\n", note);
    fprintf(out, "grow %s {\n", syl_program_name(p));
    int n;
    const SylDirective *ds = syl_program_directives(p, &n);
    for (int i = 0; i < n; i++) {
        if (lang_texture_line(ds[i].name)) continue;
        const SylDirArg *bad = NULL;
        char *value = line_text(&ds[i], &bad);
        if (!value) return SYL_ELIMIT;
        fprintf(out, "  %s%s%s\n", ds[i].name, *value ? " " : "", value);
        free(value);
    }
    lang_textures_syl(p, out);
    fprintf(out, "}\n");
    return ferror(out) ? SYL_EIO : SYL_OK;
}

int lang_grow_convert(const SylProgram *p, unsigned format, const char *note, FILE *out, FILE *diag) {
    int st = lang_textures_read(p, diag);
    if (st) return st;
    return format == KC_XML ? syl_grow_write_preset(p, out, diag) : syl_grow_write_syl(p, note, out, diag);
}
