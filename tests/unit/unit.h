/* Helpers shared by the cmocka unit tests. */
#ifndef SYL_UNIT_H
#define SYL_UNIT_H
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sylva/sylva.h"

/* Compile model text; diagnostics go to a buffer the test can read (free with free()). */
static inline SylProgram *unit_compile(const char *text, char **diag, int *status) {
    size_t len = 0;
    char *buf = NULL;
    FILE *mem = open_memstream(&buf, &len);
    SylCompileOptions opt = {.diag = mem, .lint = 1};
    int st;
    SylProgram *p = syl_compile("test.syl", text, strlen(text), &opt, &st);
    fclose(mem);
    if (status) *status = st;
    if (diag) *diag = buf;
    else free(buf);
    return p;
}

/* Derive with n steps (n < 0: the model's) and return the canonical string (free it). */
static inline char *unit_derive(const char *text, int n, int threads) {
    SylProgram *p = unit_compile(text, NULL, NULL);
    if (!p) return NULL;
    SylDeriveOptions opt = {.steps = n, .threads = threads};
    SylString *s = NULL;
    char *out = NULL;
    size_t len = 0;
    if (syl_derive(p, &opt, &s) == SYL_OK) {
        FILE *mem = open_memstream(&out, &len);
        syl_string_write(p, s, mem);
        fclose(mem);
    }
    syl_string_free(s);
    syl_program_free(p);
    return out;
}

#define assert_derives(text, n, expected)                 \
    do {                                                  \
        char *got_ = unit_derive((text), (n), 1);         \
        assert_non_null(got_);                            \
        assert_string_equal(got_, (expected));            \
        free(got_);                                       \
    } while (0)

#endif
