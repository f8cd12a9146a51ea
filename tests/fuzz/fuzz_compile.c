/* libFuzzer harness: lexer, parser, checker (lint on) and compiler on arbitrary bytes, with
 * the diagnostics printed (so the caret printer of util/diag.c runs on every error), then a
 * small bounded derivation, the string and the program printed. */
#include "fuzz.h"
#include "sylva/grow.h"
#include "sylva/sylva.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    FILE *diag = fuzz_diag();
    SylProgram *p = fuzz_compile("fuzz.syl", (const char *)data, size, 1); /* lint on, as sylva check */
    if (p) fuzz_derive_and_free(p, 4, diag);
    return 0;
}
