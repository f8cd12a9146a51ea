/* libFuzzer harness: lexer, parser, checker (lint on) and compiler on arbitrary bytes, with
 * the diagnostics printed (so the caret printer of util/diag.c runs on every error), then a
 * small bounded derivation, the string and the program printed. */
#include "fuzz.h"
#include "sylva/grow.h"
#include "sylva/sylva.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    int status;
    FILE *diag = fuzz_diag();
    SylCompileOptions opt = {.diag = diag, .lint = 1, .validate = syl_grow_validate}; /* as sylva check */
    SylProgram *p = syl_compile("fuzz.syl", (const char *)data, size, &opt, &status);
    if (p) fuzz_derive_and_free(p, 4, diag);
    return 0;
}
