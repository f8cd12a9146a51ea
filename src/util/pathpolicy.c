/* Which files a model may name (util/pathpolicy.h). */
#include "util/pathpolicy.h"

#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

char *pathpolicy_root(const char *dir) { return realpath(dir && *dir ? dir : ".", NULL); }

char *pathpolicy_model_root(const char *model_path) {
    if (!model_path || !strcmp(model_path, "-")) return pathpolicy_root(".");
    const char *slash = strrchr(model_path, '/');
    if (!slash) return pathpolicy_root(".");
    if (slash == model_path) return pathpolicy_root("/");
    char *dir = strndup(model_path, (size_t)(slash - model_path));
    char *root = dir ? pathpolicy_root(dir) : NULL;
    free(dir);
    return root;
}

static bool within(const char *real, const char *root) {
    size_t n = strlen(root);
    if (n == 1 && root[0] == '/') return true;
    return !strncmp(real, root, n) && (real[n] == 0 || real[n] == '/');
}

bool pathpolicy_allows(const char *path, const char *const *roots, int nroots) {
    char *real = realpath(path, NULL);
    if (!real) {
        /* not there (yet): the nearest folder above that is decides, and the rest must not
         * climb out of it again */
        char *up = strdup(path);
        if (!up) return false;
        for (;;) {
            char *slash = strrchr(up, '/');
            const char *rest = slash ? path + (slash - up) : path;
            if (strstr(rest, "/..") || !strncmp(rest, "..", 2)) break;
            if (!slash) {
                real = realpath(".", NULL);
                break;
            }
            if (slash == up) slash[1] = 0;
            else *slash = 0;
            if ((real = realpath(up, NULL)) || slash == up) break;
        }
        free(up);
        if (!real) return false;
    }
    bool ok = false;
    for (int i = 0; i < nroots && !ok; i++) ok = roots[i] && within(real, roots[i]);
    free(real);
    return ok;
}
