/* For the unit tests of the keyed reader (src/lang/schema_keyed.c) with made-up tables: the
 * lines given, as a grow block (a kind that keeps its lines), compiled and read by the table. */
#ifndef SYL_TEST_KEYED_H
#define SYL_TEST_KEYED_H

#include "unit.h"

#include "lang/program.h"
#include "lang/schema.h"

static inline SylProgram *keyed_compile(const char *file, const char *lines, const SylOverride *sets, int nsets) {
    char text[1024];
    snprintf(text, sizeof text, "grow G {\n%s}\n", lines);
    SylCompileOptions o = {.overrides = sets, .noverrides = nsets};
    int st;
    SylProgram *p = syl_compile(file, text, strlen(text), &o, &st);
    assert_non_null(p);
    return p;
}

/* Reads into dst (size bytes, cleared, then the table's defaults); the errors' text into *diag. */
static inline int keyed_read(const char *file, const SchKeyed *k, const char *lines, const SylOverride *sets,
                             int nsets, void *dst, size_t size, char **diag) {
    SylProgram *p = keyed_compile(file, lines, sets, nsets);
    size_t len = 0;
    FILE *f = open_memstream(diag, &len);
    memset(dst, 0, size);
    sch_keyed_defaults(k, dst);
    int set_errors, errors = sch_read_keyed(p, k, dst, f, &set_errors);
    fclose(f);
    syl_program_free(p);
    return errors;
}

#endif
