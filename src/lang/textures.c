/* The texture lines of any kind of plant: `bark "F.png" [tile U V]` and `leaf_texture "F.png"...`
 * (lang/textures.def), their image files read under the model's path rule
 * (syl_program_file) and checked to be whole PNGs. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lang/program.h"
#include "lang/textures.h"
#include "util/file.h"
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
        syl_directive_error(p, diag, d, a, "'%s' takes file names in quotes (\"bark.png\")", d->name);
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
        syl_directive_error(p, diag, d, a, "more than %d texture images in one model", SYL_IMAGES_MAX);
        return SYL_EMODEL;
    }
    if (strlen(a->text) >= sizeof im->img[0].name) {
        syl_directive_error(p, diag, d, a, "a texture's file name is at most %d bytes",
                            (int)sizeof im->img[0].name - 1);
        return SYL_EMODEL;
    }
    char *path = NULL;
    int st = syl_program_file(p, a->text, &path);
    if (st == SYL_ELIMIT) return st;
    if (st) {
        syl_directive_error(p, diag, d, a, "cannot read the texture \"%s\": %s", a->text, syl_file_refused);
        return SYL_EIO;
    }
    size_t len = 0;
    char *bytes = file_read_named(path, &len, NULL);
    int err = errno;
    free(path);
    if (!bytes) {
        syl_directive_error(p, diag, d, a, "cannot read the texture \"%s\": %s", a->text, file_strerror(err));
        return err == ENOMEM ? SYL_ELIMIT : SYL_EIO;
    }
    SylImage *g = &im->img[im->n];
    char why[160];
    bool alpha = false;
    if (!pngin_decode((const uint8_t *)bytes, len, &g->width, &g->height, &alpha, NULL, why, sizeof why)) {
        syl_directive_error(p, diag, d, a, "the texture \"%s\" is %s", a->text, why);
        free(bytes);
        return SYL_EMODEL;
    }
    snprintf(g->name, sizeof g->name, "%s", a->text);
    g->png = (uint8_t *)bytes, g->len = len, g->alpha = alpha;
    *idx = ++im->n;
    return SYL_OK;
}

static bool tile_value(const SylDirArg *a, float *v) {
    double x = a->kind == SYL_DARG_NUMBER ? a->num : a->kind == SYL_DARG_TUPLE && a->nvalues == 1 ? a->values[0] : NAN;
    *v = (float)x;
    return isfinite(x) && x >= 0.01 && x <= 1000;
}

int lang_textures(const SylProgram *p, SylTextureSpec *spec, FILE *diag) {
    memset(spec, 0, sizeof *spec);
    int n = 0, errors = 0, st = SYL_OK;
    const SylDirective *dirs = syl_program_directives(p, &n);
    const SylDirective *bark = NULL, *leaves = NULL;
    for (int i = 0; i < n && st != SYL_ELIMIT; i++) {
        const SylDirective *d = &dirs[i];
        bool is_bark = !strcmp(d->name, "bark");
        if (!is_bark && strcmp(d->name, "leaf_texture")) continue;
        const SylDirective **seen = is_bark ? &bark : &leaves;
        if (*seen) {
            syl_directive_error(p, diag, d, NULL, "'%s' is given twice (first at line %d)", d->name, (*seen)->line);
            errors++;
            continue;
        }
        *seen = d;
        int files = is_bark ? 1 : d->nargs;
        if (d->nargs == 0 || (is_bark && d->nargs != 1 && d->nargs != 4)) {
            syl_directive_error(p, diag, d, NULL,
                                is_bark ? "'bark' takes a file name and optionally `tile U V`: bark \"oak.png\" tile 2 3"
                                        : "'leaf_texture' takes one or more file names: leaf_texture \"maple.png\"");
            errors++;
            continue;
        }
        if (is_bark && d->nargs == 4) {
            if (strcmp(d->args[1].text, "tile") || d->args[1].kind != SYL_DARG_WORD) {
                syl_directive_error(p, diag, d, &d->args[1], "expected `tile U V` after the bark's file");
                errors++;
                continue;
            }
            bool ok = true;
            for (int k = 0; k < 2 && ok; k++)
                if (!(ok = tile_value(&d->args[2 + k], &spec->tile[k]))) {
                    syl_directive_error(p, diag, d, &d->args[2 + k], "a tile count is a number from 0.01 to 1000");
                    errors++;
                }
            if (!ok) continue;
        }
        for (int k = 0; k < files && st != SYL_ELIMIT; k++) {
            int idx = 0;
            st = lang_texture_image(p, d, &d->args[k], spec, &idx, diag);
            if (st) {
                errors++;
                continue;
            }
            if (is_bark) spec->bark = idx;
            else spec->leaf[spec->nleaf++] = (uint8_t)idx;
        }
    }
    if (st == SYL_ELIMIT && diag) fprintf(diag, "sylva: error: out of memory reading textures\n");
    if (errors || st) lang_textures_free(spec);
    return st == SYL_ELIMIT ? -1 : errors;
}

int lang_textures_check(const SylProgram *p, FILE *diag) {
    SylTextureSpec spec;
    int errors = lang_textures(p, &spec, diag);
    lang_textures_free(&spec);
    return errors < 0 ? 1 : errors;
}
