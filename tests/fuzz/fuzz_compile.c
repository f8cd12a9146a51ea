/* libFuzzer harness: lexer, parser, checker and compiler on arbitrary bytes, then a small
 * bounded derivation, so that nothing a user types can crash Sylva. */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "sylva/sylva.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    int status;
    SylCompileOptions opt = {.diag = NULL, .lint = 1};
    SylProgram *p = syl_compile("fuzz.syl", (const char *)data, size, &opt, &status);
    if (!p) return 0;
    SylDeriveOptions d = {.steps = 4, .threads = 1, .max_modules = 20000, .max_memory = 64u << 20};
    SylString *s = NULL;
    if (syl_derive(p, &d, &s) == SYL_OK) {
        SylString *t = NULL;
        if (syl_interpret(p, s, &d, &t) == SYL_OK) syl_string_free(t);
        FILE *null = fopen("/dev/null", "w");
        if (null) {
            syl_string_write(p, s, null);
            fclose(null);
        }
    }
    syl_string_free(s);
    FILE *null = fopen("/dev/null", "w");
    if (null) {
        syl_program_dump(p, null);
        fclose(null);
    }
    syl_program_free(p);
    return 0;
}
