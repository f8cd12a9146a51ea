/* PROVISIONAL (branch `view`, issue 30): syl_describe_json (sylva/describe.h) covering what is
 * cheap to know here — an L-system's settings, a model's `param`s, and the one-number lines of
 * a grow, weber, strands or ecosystem block (without their ranges or meanings, which their
 * engines' tables hold: the `schema` branch's version brings them and replaces this file). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lang/program.h"
#include "sylva/describe.h"
#include "util/json.h"

typedef struct Setting {
    const char *name, *type, *unit, *doc;
    double min, max; /* NAN: unbounded */
} Setting;

/* The settings of an lsystem block that --set takes (lang/settings.c checks the same ranges). */
static const Setting settings[] = {
    {"derive", "integer", "", "derivation steps", 0, 1e6},
    {"angle", "number", "deg", "turn angle of + and -", 0, 360},
    {"step", "number", "", "length of F", 0, NAN},
    {"width", "number", "", "line width at the start", 0, NAN},
    {"widthfactor", "number", "", "width change of !", 0, NAN},
    {"seed", "integer", "", "seed of the stochastic rules", 0, 9007199254740991.0},
};

static void num(FILE *out, double x) {
    if (isnan(x) || x > 1e300 || x < -1e300) fputs("null", out);
    else fprintf(out, "%.17g", x);
}

static void param(FILE *out, bool first, const char *name, const char *type, double min, double max, double def,
                  double value, const char *unit, const char *doc) {
    fputs(first ? "{\"name\":" : ",{\"name\":", out);
    json_string_file(out, name);
    fprintf(out, ",\"type\":\"%s\",\"min\":", type);
    num(out, min);
    fputs(",\"max\":", out);
    num(out, max);
    fputs(",\"default\":", out);
    num(out, def);
    fputs(",\"value\":", out);
    num(out, value);
    fputs(",\"unit\":", out);
    json_string_file(out, unit);
    fputs(",\"doc\":", out);
    json_string_file(out, doc);
    fputs(",\"values\":null,\"aliases\":[]}", out);
}

/* The line of `KIND NAME` in the source (1 when not found). */
static int model_line(const SylProgram *p, const char *kind) {
    size_t nl = strlen(p->name), kl = strlen(kind);
    int line = 1;
    for (const char *s = p->src.text, *e = s + p->src.len; s && s < e && *s; s++) {
        if (*s == '\n') line++;
        if ((s == p->src.text || s[-1] == '\n' || s[-1] == ' ') && !strncmp(s, kind, kl) && s[kl] == ' ') {
            const char *n = s + kl;
            while (*n == ' ') n++;
            if (!strncmp(n, p->name, nl) && !(n[nl] == '_' || (n[nl] >= '0' && n[nl] <= '9') ||
                                              ((n[nl] | 32) >= 'a' && (n[nl] | 32) <= 'z')))
                return line;
        }
    }
    return 1;
}

static void model(const SylProgram *p, FILE *out, bool first) {
    /* the block's keyword: "weber" of "weber block" */
    char kind[32];
    snprintf(kind, sizeof kind, "%s", syl_model_kind_name(p->kind));
    kind[strcspn(kind, " ")] = 0;
    fputs(first ? "{\"name\":" : ",{\"name\":", out);
    json_string_file(out, p->name ? p->name : "");
    fputs(",\"kind\":", out);
    json_string_file(out, kind);
    fprintf(out, ",\"line\":%d,\"params\":[", model_line(p, kind));
    bool any = false;
    for (int i = 0; i < p->nparams; i++, any = true)
        param(out, !any, p->params[i].name, "number", NAN, NAN, p->params[i].value, p->params[i].value, "", "a param of the model");
    if (p->kind == SYL_MODEL_LSYSTEM) {
        for (size_t i = 0; i < sizeof settings / sizeof *settings; i++, any = true) {
            const Setting *s = &settings[i];
            double v = !strcmp(s->name, "seed") ? (double)syl_program_seed(p) : syl_program_setting(p, s->name);
            param(out, !any, s->name, s->type, s->min, s->max, v, v, s->unit, s->doc);
        }
    } else {
        for (int i = 0; i < p->ndirectives; i++) {
            const SylDirective *d = &p->directives[i];
            if (d->nargs != 1 || d->args[0].kind != SYL_DARG_NUMBER) continue;
            param(out, !any, d->name, "number", NAN, NAN, d->args[0].num, d->args[0].num, "", "");
            any = true;
        }
    }
    fputs("]}", out);
}

int syl_describe_json(const SylProgram *p, FILE *out) {
    fputs("{\"file\":", out);
    json_string_file(out, p->src.path ? p->src.path : "");
    fputs(",\"models\":[", out);
    const char *names[256];
    char buf[8192];
    int n = syl_list_models(p->src.path, p->src.text, p->src.len, names, 256, buf, sizeof buf);
    bool first = true;
    for (int i = 0; i < n; i++) {
        if (p->name && !strcmp(names[i], p->name)) {
            model(p, out, first);
            first = false;
            continue;
        }
        int status;
        SylProgram *q = syl_compile_model(p, names[i], NULL, &status);
        if (!q) continue;
        model(q, out, first);
        first = false;
        syl_program_free(q);
    }
    if (first && p->name) model(p, out, true);
    fputs("]}\n", out);
    return fflush(out) || ferror(out) ? SYL_EIO : SYL_OK;
}
