/* Shared bits of the libFuzzer harnesses (tests/fuzz/fuzz_*.c). Each harness feeds one
 * reader arbitrary bytes with small limits, so that a run of a few seconds gets deep, and
 * prints diagnostics to /dev/null, so that the message and caret printers run too. */
#ifndef SYL_FUZZ_H
#define SYL_FUZZ_H
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lang/arbaro.h"
#include "sylva/grow.h"
#include "sylva/sylva.h"

/* Where diagnostics go: /dev/null, or stderr with SYLVA_FUZZ_VERBOSE=1 (to read what a
 * crash input does). Opened once: the harness process is the fuzzer's. */
static FILE *fuzz_diag(void) {
    static FILE *f;
    if (!f) f = getenv("SYLVA_FUZZ_VERBOSE") ? stderr : fopen("/dev/null", "w");
    return f;
}

/* fuzz_diag() as a sink, for the functions that report to one. */
static const SylSink *fuzz_sink(void) {
    static SylSink s;
    s = (SylSink){syl_diagnostic_print, fuzz_diag()};
    return &s;
}

/* A NUL-terminated copy of the input (readers that want C strings). */
static char *fuzz_text(const uint8_t *data, size_t size) {
    char *t = malloc(size + 1);
    if (!t) abort();
    memcpy(t, data, size);
    t[size] = 0;
    return t;
}

/* The input as a NUL-terminated XML text for the XML readers (lang/arbaro.c): behind head
 * (a root element) when it does not read as XML already, so that every input reaches
 * libxml2; its length in *n. */
static char *fuzz_xml_text(const uint8_t *data, size_t size, const char *head, size_t *n) {
    Source src = {.path = "fuzz.xml", .text = (const char *)data, .len = size};
    size_t h = syl_arbaro_detect(&src) ? 0 : strlen(head);
    char *text = malloc(size + h + 1);
    if (!text) abort();
    memcpy(text, head, h);
    memcpy(text + h, data, size);
    text[size + h] = 0;
    *n = size + h;
    return text;
}

/* The source harnesses' compile, as `sylva check` does it: `grow` and `scene` blocks
 * validated, warnings too when lint is set, diagnostics to fuzz_diag(). NULL: no program. */
static SylProgram *fuzz_compile(const char *path, const char *text, size_t size, int lint) {
    int status;
    SylCompileOptions opt = {.diag = fuzz_diag(), .lint = lint, .validate = syl_validate};
    return syl_compile(path, text, size, &opt, &status);
}

/* What the compiler harnesses do with a program once compiled: a small bounded derivation
 * and its interpretation, the string and the program printed; then the program is freed. */
static void fuzz_derive_and_free(SylProgram *p, int steps, FILE *diag) {
    SylDeriveOptions d = {.steps = steps, .threads = 1, .max_modules = 20000, .max_memory = 64u << 20, .diag = diag};
    SylString *s = NULL;
    if (syl_derive(p, &d, &s) == SYL_OK) {
        SylString *t = NULL;
        if (syl_interpret(p, s, &d, &t) == SYL_OK) syl_string_free(t);
        syl_string_write(p, s, diag);
    }
    syl_string_free(s);
    syl_program_dump(p, diag);
    syl_program_free(p);
}

/* What the tree harnesses (weber, strands) do with a tree once built (st == SYL_OK): mesh it
 * with few sides; then the tree is freed. */
static void fuzz_mesh_tree_and_free(int st, SylSkeleton *sk, FILE *diag) {
    if (st == SYL_OK) {
        SylMesh *m = NULL;
        SylMeshOptions mo = {.sides = 4, .threads = 1, .diag = diag};
        if (syl_mesh_build(sk, &mo, &m) == SYL_OK) syl_mesh_free(m);
    }
    syl_skeleton_free(sk);
}

#endif
