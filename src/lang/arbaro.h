/* Arbaro's XML species files (and Helios's WeberPennTreeLibrary.xml), read with libxml2 into
 * the syntax tree a `weber` block makes (docs/arbaro.md). */
#ifndef SYL_ARBARO_H
#define SYL_ARBARO_H
#include <stdbool.h>

#include "lang/ast.h"

/* The root element of a grow preset file (docs/growth.md#presets). */
#define SYL_GROW_PRESET_ROOT "grow-presets"

/* Larger files are refused before libxml2 sees them. */
#define ARBARO_MAX_BYTES (16u << 20)

/* Whether the text is XML: its first characters, blanks skipped, are `<?xml`, `<!--`,
 * `<arbaro`, `<helios` or `<grow-presets`. */
bool syl_arbaro_detect(const Source *src);

/* One weber model per <species> (per <WeberPennTree> of a Helios file; a grow model per
 * <species> of a grow preset file), its directives the parameters at their XML lines. Malformed XML is reported at libxml2's line and column.
 * Returns the number of errors. */
int syl_arbaro_parse(const Source *src, Arena *arena, Diag *diag, FileAst *ast);

#endif
