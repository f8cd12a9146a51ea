/* Blender's Sapling add-on's presets (a Python dictionary literal of its parameters), read
 * into the syntax tree a `weber` block makes (docs/arbaro.md#sapling). */
#ifndef SYL_SAPLING_H
#define SYL_SAPLING_H
#include <stdbool.h>

#include "lang/ast.h"

/* Whether the text is a Sapling preset: blanks and # comments skipped, `{` and a quoted key,
 * with a 'branches' key somewhere. */
bool syl_sapling_detect(const Source *src);

/* One weber model, named after the file, its directives Sapling's parameters mapped to
 * Sylva's at their lines. Returns the number of errors. */
int syl_sapling_parse(const Source *src, Arena *arena, Diag *diag, FileAst *ast);

#endif
