/* The texture lines of any kind of plant: `bark "F.png" [tile U V]` and `leaf_texture "F.png"...`
 * (lang/textures.def), their image files read under the model's path rule
 * (syl_program_file) and checked to be whole PNGs. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lang/kinds.h"
#include "lang/program.h"
#include "lang/schema.h"
#include "lang/textures.h"
#include "util/file.h"
#include "util/number.h"
#include "util/pngin.h"

bool lang_texture_line(const char *name) {
#define TEXTURE_LINE(nm, ty, mean) if (!strcmp(name, nm)) return true;
#include "lang/textures.def"
    return false;
}

void lang_textures_free(SylTextureSpec *spec) {
    SylImages *im = spec->images;
    if (im)
        for (int i = 0; i < im->n; i++) free(im->img[i].png);
    free(im);
    memset(spec, 0, sizeof *spec);
}

int lang_texture_image(const SylProgram *p, const SylDirective *d, const SylDirArg *a, SylTextureSpec *spec,
                       int *idx, FILE *diag) {
    if (a->kind != SYL_DARG_STRING && a->kind != SYL_DARG_WORD) {
        syl_directive_report_error(p, diag, d, a, "'%s' takes file names in quotes (\"bark.png\")", d->name);
        return SYL_EMODEL;
    }
    if (!spec->images && !(spec->images = calloc(1, sizeof *spec->images))) return SYL_ELIMIT;
    SylImages *im = spec->images;
    im->refs = 1;
    for (int i = 0; i < im->n; i++)
        if (!strcmp(im->img[i].name, a->text)) {
            *idx = i + 1;
            return SYL_OK;
        }
    if (im->n >= SYL_IMAGES_MAX) {
        syl_directive_report_error(p, diag, d, a, "more than %d texture images in one model", SYL_IMAGES_MAX);
        return SYL_EMODEL;
    }
    if (strlen(a->text) >= sizeof im->img[0].name) {
        syl_directive_report_error(p, diag, d, a, "a texture's file name is at most %d bytes",
                                   (int)sizeof im->img[0].name - 1);
        return SYL_EMODEL;
    }
    char *path = NULL;
    int st = syl_program_file(p, a->text, &path);
    if (st == SYL_ELIMIT) return st;
    if (st) {
        syl_directive_report_error(p, diag, d, a, "cannot read the texture \"%s\": %s", a->text, syl_file_refused);
        return SYL_EIO;
    }
    size_t len = 0;
    char *bytes = file_read_named(path, &len, NULL);
    int err = errno;
    free(path);
    if (!bytes) {
        syl_directive_report_error(p, diag, d, a, "cannot read the texture \"%s\": %s", a->text, file_strerror(err));
        return err == ENOMEM ? SYL_ELIMIT : SYL_EIO;
    }
    SylImage *g = &im->img[im->n];
    char why[160];
    bool alpha = false;
    if (!pngin_decode((const uint8_t *)bytes, len, &g->width, &g->height, &alpha, NULL, why, sizeof why)) {
        syl_directive_report_error(p, diag, d, a, "the texture \"%s\" is %s", a->text, why);
        free(bytes);
        return SYL_EMODEL;
    }
    snprintf(g->name, sizeof g->name, "%s", a->text);
    g->png = (uint8_t *)bytes, g->len = len, g->alpha = alpha;
    *idx = ++im->n;
    return SYL_OK;
}

/* Whether row r is named name, by its name or an alias ("a|b"). */
static bool row_named(const SchRow *r, const char *name) {
    if (!strcmp(r->name, name)) return true;
    size_t n = strlen(name);
    for (const char *a = r->aliases; a && *a;) {
        size_t k = strcspn(a, "|");
        if (k == n && !strncmp(a, name, n)) return true;
        a += k + (a[k] == '|');
    }
    return false;
}

/* The texture line a directive is: 1 the bark, 2 the leaves, 0 neither; by its row of the
 * kind's table, so a kind's own names for them (Pafčo's K_SUBOR, TEX_SUBORY, whose aliases
 * are bark and leaf_texture) are the same lines. */
static int line_role(const SylProgram *p, const char *name) {
    const SchTable *t = lang_kind_schema(syl_program_kind(p));
    const SchRow *r = t ? sch_find(t, name, NULL) : NULL;
    return !r ? 0 : row_named(r, "bark") ? 1 : row_named(r, "leaf_texture") ? 2 : 0;
}

static bool tile_value(const SylDirArg *a, float *v) {
    double x = a->kind == SYL_DARG_NUMBER ? a->num : a->kind == SYL_DARG_TUPLE && a->nvalues == 1 ? a->values[0] : NAN;
    *v = (float)x;
    return isfinite(x) && x >= 0.01 && x <= 1000;
}

/* The worse of two statuses: out of memory, then a file that cannot be read, then the model. */
static int worse(int a, int b) {
    static const int rank[] = {[SYL_OK] = 0, [SYL_EMODEL] = 1, [SYL_EUSAGE] = 1, [SYL_EIO] = 2, [SYL_ELIMIT] = 3};
    return rank[b] > rank[a] ? b : a;
}

int lang_textures(const SylProgram *p, SylTextureSpec *spec, FILE *diag) {
    memset(spec, 0, sizeof *spec);
    int n = 0, worst = SYL_OK, st = SYL_OK;
    const SylDirective *dirs = syl_program_directives(p, &n);
    const SylDirective *bark = NULL, *leaves = NULL;
    for (int i = 0; i < n && st != SYL_ELIMIT; i++) {
        const SylDirective *d = &dirs[i];
        int role = line_role(p, d->name);
        bool is_bark = role == 1;
        if (!role) continue;
        const SylDirective **seen = is_bark ? &bark : &leaves;
        if (*seen) {
            syl_directive_report_error(p, diag, d, NULL, "'%s' is given twice (first at line %d, as '%s')", d->name,
                                       (*seen)->line, (*seen)->name);
            worst = worse(worst, SYL_EMODEL);
            continue;
        }
        *seen = d;
        int files = is_bark ? 1 : d->nargs;
        if (d->nargs == 0 || (is_bark && d->nargs != 1 && d->nargs != 4)) {
            syl_directive_report_error(p, diag, d, NULL,
                                       is_bark ? "'%s' takes a file name and optionally `tile U V`: bark \"oak.png\" tile 2 3"
                                               : "'%s' takes one or more file names: leaf_texture \"maple.png\"",
                                       d->name);
            worst = worse(worst, SYL_EMODEL);
            continue;
        }
        if (is_bark && d->nargs == 4) {
            if (strcmp(d->args[1].text, "tile") || d->args[1].kind != SYL_DARG_WORD) {
                syl_directive_report_error(p, diag, d, &d->args[1], "expected `tile U V` after the bark's file");
                worst = worse(worst, SYL_EMODEL);
                continue;
            }
            bool ok = true;
            for (int k = 0; k < 2 && ok; k++)
                if (!(ok = tile_value(&d->args[2 + k], &spec->tile[k]))) {
                    syl_directive_report_error(p, diag, d, &d->args[2 + k], "a tile count is a number from 0.01 to 1000");
                    worst = worse(worst, SYL_EMODEL);
                }
            if (!ok) continue;
        }
        for (int k = 0; k < files && st != SYL_ELIMIT; k++) {
            int idx = 0;
            st = lang_texture_image(p, d, &d->args[k], spec, &idx, diag);
            if (st) {
                worst = worse(worst, st);
                continue;
            }
            if (is_bark) spec->bark = idx;
            else spec->leaf[spec->nleaf++] = (uint8_t)idx;
        }
    }
    if (st == SYL_ELIMIT) program_say(p, diag, DIAG_ERROR, NULL, "out of memory reading textures");
    if (worst) lang_textures_free(spec);
    return worst;
}

int lang_textures_check(const SylProgram *p, FILE *diag) {
    SylTextureSpec spec;
    int st = lang_textures(p, &spec, diag);
    lang_textures_free(&spec);
    return st != SYL_OK;
}

static const char *file_text(const SylDirArg *a) { return a->text ? a->text : ""; }

/* A tile count as written: the fewest digits that read back exactly. */
static void tile_text(const SylDirArg *a, char *buf, size_t n) {
    number_write(buf, n, a->kind == SYL_DARG_TUPLE && a->nvalues == 1 ? a->values[0] : a->num);
}

/* p's texture lines into x (XML) or else out (.syl). */
static void write_lines(const SylProgram *p, ParamXml *x, FILE *out) {
    int n = 0;
    const SylDirective *ds = syl_program_directives(p, &n);
    for (int i = 0; i < n; i++) {
        const SylDirective *d = &ds[i];
        int role = line_role(p, d->name);
        if (!role) continue;
        char u[40], v[40], tile[84] = "";
        if (role == 1 && d->nargs == 4) {
            tile_text(&d->args[2], u, sizeof u), tile_text(&d->args[3], v, sizeof v);
            snprintf(tile, sizeof tile, "%s %s", u, v);
        }
        int files = role == 1 && d->nargs ? 1 : d->nargs;
        if (x && role == 1) {
            const char *attrs[] = {"file", files ? file_text(&d->args[0]) : "", "tile", *tile ? tile : NULL};
            paramxml_element(x, "bark", attrs, 2);
        } else if (x)
            for (int k = 0; k < files; k++) paramxml_element(x, "leaf_texture", (const char *[]){"file", file_text(&d->args[k])}, 1);
        else {
            fputs(role == 1 ? "  bark" : "  leaf_texture", out);
            for (int k = 0; k < files; k++) fprintf(out, " \"%s\"", file_text(&d->args[k]));
            fprintf(out, "%s%s\n", *tile ? " tile " : "", tile);
        }
    }
}

void lang_textures_xml(const SylProgram *p, ParamXml *x) { write_lines(p, x, NULL); }

void lang_textures_syl(const SylProgram *p, FILE *out) { write_lines(p, NULL, out); }
