/* Reading directive lines of scene blocks (and grow's checks across directives, after the
 * schema's keyed reader, lang/schema_keyed.c, has read its lines): errors go through the program's
 * diagnostics, and are counted so that a whole block is checked before failing. */
#ifndef SOT_READER_H
#define SOT_READER_H
#include <stdbool.h>
#include <stdio.h>

#include "lang/schema.h"
#include "sylva/sylva.h"

typedef struct Reader {
    const SylProgram *p;
    FILE *diag;
    int errors;
} Reader;

#define ERR(r, line, col, ...) (syl_program_report_error((r)->p, (r)->diag, (line), (col), __VA_ARGS__), (r)->errors++)

/* A number, written as such or as a one-value tuple `(expr)`: the schema's reading of one. */
static inline bool reader_number(const SylDirArg *a, double *out) { return sch_number(a, out); }

#endif
