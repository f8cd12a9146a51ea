/* Which files a model may name: its own folder and below, and the folders the user allowed
 * (--allow-path). Every reader of a model-named path asks this one function first, with the
 * path as the real path (symlinks and `..` resolved) decides, not as written. */
#ifndef SYL_PATHPOLICY_H
#define SYL_PATHPOLICY_H
#include <stdbool.h>

/* The real path of a folder (malloc'd), or NULL when it cannot be resolved; "" or "." is the
 * working folder. */
char *pathpolicy_root(const char *dir);
/* The folder a model file stands in, resolved (malloc'd): "-" (standard input) and a bare
 * name stand in the working folder. NULL when it cannot be resolved. */
char *pathpolicy_model_root(const char *model_path);
/* Whether path lies within one of roots (each a real path from pathpolicy_root). A path that
 * does not exist is judged by the nearest folder above it that does, and refused when what is
 * left of it climbs with `..`. */
bool pathpolicy_allows(const char *path, const char *const *roots, int nroots);

#endif
