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

#include "sylva/grow.h"
#include "sylva/sylva.h"

/* Compile model text; diagnostics go to a buffer the test can read (free with free()). */
static inline SylProgram *unit_compile(const char *text, char **diag, int *status) {
    size_t len = 0;
    char *buf = NULL;
    FILE *mem = open_memstream(diag ? diag : &buf, &len); /* straight into *diag: gcc's
                                                             dangling-pointer check is happier */
    SylCompileOptions opt = {.diag = mem, .lint = 1, .validate = syl_validate};
    int st;
    SylProgram *p = syl_compile("test.syl", text, strlen(text), &opt, &st);
    fclose(mem);
    if (status) *status = st;
    free(buf);
    return p;
}

/* Write text to the file dir/name (a fixture of a test's own folder). */
static inline void unit_write_file(const char *dir, const char *name, const char *text) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

/* Remove the files names[0..n) of dir (a test's own folder), then the folder (remove(3) takes
 * both): the folder's result, 0 when it is gone. */
static inline int unit_remove_files(const char *dir, const char *const *names, size_t n) {
    for (size_t i = 0; i < n; i++) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        remove(path);
    }
    return remove(dir);
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

/* A derivation kept for inspection. diag holds the compiler's and the engine's messages
 * (never NULL); p and s are NULL when compiling or deriving failed. */
typedef struct UnitRun {
    SylProgram *p;
    SylString *s;
    int status;
    char *diag;
} UnitRun;

/* Compile (lint on) and derive with opt (its diag is replaced). */
static inline UnitRun unit_run(const char *text, SylDeriveOptions opt) {
    UnitRun r = {0};
    size_t len = 0;
    FILE *mem = open_memstream(&r.diag, &len);
    SylCompileOptions copt = {.diag = mem, .lint = 1, .validate = syl_validate};
    r.p = syl_compile("test.syl", text, strlen(text), &copt, &r.status);
    if (r.p) {
        opt.diag = mem;
        r.status = syl_derive(r.p, &opt, &r.s);
    }
    fclose(mem);
    return r;
}

static inline void unit_run_free(UnitRun *r) {
    syl_string_free(r->s);
    syl_program_free(r->p);
    free(r->diag);
    *r = (UnitRun){0};
}

/* The canonical form of a run's string (free it). */
static inline char *unit_string(const UnitRun *r) {
    char *out = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&out, &len);
    if (r->p && r->s) syl_string_write(r->p, r->s, mem);
    fclose(mem);
    return out;
}

/* Parameter k of module i of a run's string; fails the test if there is none. */
static inline double unit_param(const UnitRun *r, size_t i, int k) {
    int np = 0;
    const double *par = NULL;
    if (!r->s || i >= syl_string_length(r->s)) fail_msg("no module %zu in the string", i);
    syl_string_module(r->s, i, &np, &par);
    if (k >= np) fail_msg("module %zu has %d parameters, not %d", i, np, k + 1);
    return par[k];
}

/* How many modules of the string are named name. */
static inline uint64_t unit_count(const UnitRun *r, const char *name) {
    int sym = syl_program_symbol_find(r->p, name);
    if (sym < 0 || !r->s) return 0;
    uint64_t *counts = calloc((size_t)syl_program_symbol_count(r->p), sizeof *counts);
    syl_string_count(r->s, counts);
    uint64_t n = counts[sym];
    free(counts);
    return n;
}

/* Text assertions that show the text when they fail. */
#define assert_contains(text, needle)                                                            \
    do {                                                                                         \
        const char *t_ = (text);                                                                 \
        if (!t_ || !strstr(t_, (needle))) fail_msg("expected \"%s\" in:\n%s", (needle), t_ ? t_ : "(null)"); \
    } while (0)
#define assert_not_contains(text, needle)                                                        \
    do {                                                                                         \
        const char *t_ = (text);                                                                 \
        if (t_ && strstr(t_, (needle))) fail_msg("did not expect \"%s\" in:\n%s", (needle), t_); \
    } while (0)
/* |a - b| <= eps, printing both values when it fails. */
#define assert_near(a, b, eps)                                                                  \
    do {                                                                                        \
        double a_ = (a), b_ = (b);                                                              \
        if (!(a_ - b_ <= (eps) && b_ - a_ <= (eps))) fail_msg("%.17g != %.17g (+-%g)", a_, b_, (double)(eps)); \
    } while (0)

/* How many times needle occurs in text. */
static inline int unit_occurrences(const char *text, const char *needle) {
    int n = 0;
    for (const char *t = text; t && (t = strstr(t, needle)); t += strlen(needle)) n++;
    return n;
}

#endif
