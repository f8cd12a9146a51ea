/* The files a model names: where they are (relative to the model's folder), whether the model
 * may read them (util/pathpolicy.h), and whether another file is recognisably a model. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "lang/arbaro.h"
#include "lang/pafco_cfg.h"
#include "lang/parse_state.h"
#include "lang/program.h"
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
    const char *prog = p->src.path, *slash = strrchr(prog, '/');
    size_t dir = name[0] == '/' || !slash || !strcmp(prog, "-") ? 0 : (size_t)(slash - prog + 1);
    if (dir == 2 && prog[0] == '.') dir = 0; /* "./model.syl" */
    *path = malloc(dir + strlen(name) + 1);
    if (!*path) return SYL_ELIMIT;
    memcpy(*path, prog, dir); /* "dir/name"; as written when the model is in the working folder */
    strcpy(*path + dir, name);
    if (pathpolicy_allows(*path, p->roots, p->nroots)) return SYL_OK;
    free(*path);
    *path = NULL;
    errno = EACCES;
    return SYL_EIO;
}

/* a line that opens a block of the language: `lsystem Name {`, `scene {` ... */
static bool opens_block(const char *b, const char *e) {
    static const char *const kw[] = {"lsystem", "grow", "scene", "weber", "strands", "ecosystem"};
    while (b < e && (*b == ' ' || *b == '\t')) b++;
    for (size_t k = 0; k < sizeof kw / sizeof *kw; k++) {
        size_t n = strlen(kw[k]);
        if ((size_t)(e - b) > n && !memcmp(b, kw[k], n) && (b[n] == ' ' || b[n] == '\t' || b[n] == '{'))
            return true;
    }
    return false;
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
