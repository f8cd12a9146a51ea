/* libFuzzer harness: Pícek's plant-file reader (src/lang/picek.c) on arbitrary lines. The input
 * follows an `iteration:` line, so that every input is read as such a file; then the compiler,
 * a small bounded derivation and its interpretation, as fuzz_compile does. */
#include "fuzz.h"
#include "sylva/sylva.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    static const char head[] = "iteration: 3\n";
    char *text = malloc(sizeof head - 1 + size + 1);
    if (!text) abort();
    memcpy(text, head, sizeof head - 1);
    memcpy(text + sizeof head - 1, data, size);
    int status;
    FILE *diag = fuzz_diag();
    SylCompileOptions opt = {.diag = diag, .lint = 1};
    SylProgram *p = syl_compile("fuzz.txt", text, sizeof head - 1 + size, &opt, &status);
    if (p) {
        SylDeriveOptions d = {.steps = 3, .threads = 1, .max_modules = 20000, .max_memory = 64u << 20, .diag = diag};
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
    free(text);
    return 0;
}
