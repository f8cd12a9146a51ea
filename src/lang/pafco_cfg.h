/* Pafčo's parameter files (Pafčo 2007, §4.6): `PARAMETER=value`, one a line, in any order,
 * read into the syntax tree a `pafco` block makes (docs/pafco.md#the-file-format). Recognised
 * by their content, whatever the extension. */
#ifndef SYL_PAFCO_CFG_H
#define SYL_PAFCO_CFG_H
#include <stdbool.h>
#include <stddef.h>

#include "lang/ast.h"

/* Whether text is a Pafčo file: its first line that is not blank or a # comment is
 * `NAME=…` with NAME in capitals, digits and _, and some line names one of the 42
 * parameters. */
bool lang_pafco_cfg_detect(const char *text, size_t len);

/* One pafco model, named after the file, a directive a line (values: numbers, words,
 * file names) at its line and column. Returns the number of errors. */
int lang_pafco_cfg_parse(const Source *src, Arena *arena, Diag *diag, FileAst *ast);

#endif
