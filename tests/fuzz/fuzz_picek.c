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
    if (p) fuzz_derive_and_free(p, 3, diag);
    free(text);
    return 0;
}
