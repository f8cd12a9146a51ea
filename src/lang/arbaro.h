/* Arbaro's XML species files (and Helios's WeberPennTreeLibrary.xml), read with libxml2 into
 * the syntax tree a `weber` block makes (docs/arbaro.md). */
#ifndef SYL_ARBARO_H
#define SYL_ARBARO_H
#include <stdbool.h>

#include "lang/ast.h"

/* Larger files are refused before libxml2 sees them. */
#define ARBARO_MAX_BYTES (16u << 20)

/* Whether the text is XML: its first characters, blanks skipped, are `<?xml`, `<!--`,
 * `<arbaro` or `<helios`. */
bool syl_arbaro_detect(const Source *src);

/* One weber model per <species> (per <WeberPennTree> of a Helios file), its directives the
 * parameters at their XML lines. Malformed XML is reported at libxml2's line and column.
 * Returns the number of errors. */
int syl_arbaro_parse(const Source *src, Arena *arena, Diag *diag, FileAst *ast);

#endif
