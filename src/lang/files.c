/* The files a model names: where they are (relative to the model's folder), whether the model
 * may read them (util/pathpolicy.h), and whether another file is recognisably a model. */
#include <errno.h>
#include <libgen.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lang/arbaro.h"
#include "lang/kinds.h"
#include "lang/pafco_cfg.h"
#include "lang/parse_state.h"
#include "lang/program.h"
#include "util/file.h"
#include "util/pathpolicy.h"

const char syl_file_refused[] =
    "outside the folders this model may read (its own folder and below; --allow-path DIR allows another)";

void lang_program_roots(SylProgram *p, const SylCompileOptions *opt) {
    p->roots = arena_alloc(&p->arena, sizeof *p->roots * (size_t)(1 + (opt->nallow_paths > 0 ? opt->nallow_paths : 0)));
    p->nroots = 0;
    char *own = pathpolicy_model_root(p->src.path);
    for (int i = -1; i < opt->nallow_paths; i++) {
        char *r = i < 0 ? own : opt->allow_paths[i] ? pathpolicy_root(opt->allow_paths[i]) : NULL;
        if (r) p->roots[p->nroots++] = arena_strndup(&p->arena, r, strlen(r));
        free(r);
    }
}

int syl_program_file(const SylProgram *p, const char *name, char **path) {
    if (!(*path = file_beside(p->src.path, name))) return SYL_ELIMIT;
    if (pathpolicy_allows(*path, p->roots, p->nroots)) return SYL_OK;
    free(*path);
    *path = NULL;
    errno = EACCES;
    return SYL_EIO;
}

int lang_check_file(const SylProgram *p, FILE *diag, const char *what, const char *file, int line, int col) {
    char *path = file_beside(p->src.path, file);
    if (!path) return 0;
    char *colon = strrchr(path, ':'); /* "file.syl:Model" */
    if (colon && colon > path && colon[1] && (!strrchr(path, '/') || colon > strrchr(path, '/'))) *colon = 0;
    errno = 0;
    FILE *f = fopen(path, "rb");
    if (f && fgetc(f) == EOF && ferror(f)) {
        fclose(f);
        f = NULL;
    }
    int err = errno;
    if (f) fclose(f);
    else { /* where it was looked for, from the root: the model's folder, not the shell's */
        char dir[PATH_MAX], *copy = strdup(path);
        const char *base = copy ? basename(copy) : path;
        char *d = copy ? strdup(path) : NULL;
        bool whole = d && realpath(dirname(d), dir);
        syl_program_report_error(p, diag, line, col, "the %s file \"%s\" cannot be read (looked for %s%s%s): %s", what, file,
                                 whole ? dir : "", whole ? "/" : "", whole ? base : path, strerror(err));
        free(copy);
        free(d);
    }
    free(path);
    return !f;
}

/* a line that opens a block of the language: `lsystem Name {`, `scene {` ... (a kind's keyword,
 * lang/kinds.def) */
static bool opens_block(const char *b, const char *e) {
    while (b < e && (*b == ' ' || *b == '\t')) b++;
    size_t n = 0;
    while (b + n < e && ((b[n] >= 'a' && b[n] <= 'z') || (b[n] >= 'A' && b[n] <= 'Z'))) n++;
    return b + n < e && (b[n] == ' ' || b[n] == '\t' || b[n] == '{') && lang_kind_of_keyword(b, n) >= 0;
}

int syl_text_is_model(const char *text, size_t len) {
    Source src = {.path = "", .text = text, .len = len};
    Diag quiet = {0};
    if (syl_arbaro_detect(&src) || syl_picek_detect(&src) || syl_foreign_file(&src, &quiet) ||
        lang_pafco_cfg_detect(text, len))
        return 1;
    for (const char *p = text, *end = text + len; p < end;) {
        const char *nl = memchr(p, '\n', (size_t)(end - p)), *e = nl ? nl : end;
        if (opens_block(p, e)) return 1;
        p = e + 1;
    }
    return 0;
}
