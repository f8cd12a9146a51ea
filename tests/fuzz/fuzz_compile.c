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
    if (!p) return 0;
    SylDeriveOptions d = {.steps = 4, .threads = 1, .max_modules = 20000, .max_memory = 64u << 20, .diag = diag};
    SylString *s = NULL;
    if (syl_derive(p, &d, &s) == SYL_OK) {
        SylString *t = NULL;
        if (syl_interpret(p, s, &d, &t) == SYL_OK) syl_string_free(t);
        syl_string_write(p, s, diag);
    }
    syl_string_free(s);
    syl_program_dump(p, diag);
    syl_program_free(p);
    return 0;
}
