/* The files a model names (a terrain, an envelope, an obstacle): where they are, and whether
 * they can be read. */
#include <errno.h>
#include <libgen.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lang/program.h"

char *syl_program_file_path(const SylProgram *p, const char *file) {
    if (file[0] == '/') return strdup(file);
    char *prog = strdup(syl_program_path(p));
    if (!prog) return NULL;
    const char *dir = dirname(prog);
    size_t n = strlen(dir) + strlen(file) + 2;
    char *out = malloc(n);
    if (out && !strcmp(dir, ".")) snprintf(out, n, "%s", file); /* messages name it as written */
    else if (out) snprintf(out, n, "%s/%s", dir, file);
    free(prog);
    return out;
}

int syl_program_check_file(const SylProgram *p, FILE *diag, const char *what, const char *file, int line, int col) {
    char *path = syl_program_file_path(p, file);
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
        syl_program_error(p, diag, line, col, "the %s file \"%s\" cannot be read (looked for %s%s%s): %s", what, file,
                          whole ? dir : "", whole ? "/" : "", whole ? base : path, strerror(err));
        free(copy);
        free(d);
    }
    free(path);
    return !f;
}
