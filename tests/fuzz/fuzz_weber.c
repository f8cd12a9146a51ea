/* libFuzzer harness: `weber` blocks (and Arbaro species files, which read as one) on arbitrary
 * source, then the Weber–Penn generator on what they say and the mesher on its tree. The
 * source is compiled as if it stood in tests/data/arbaro/, so that `from "palm.xml"` splices
 * a real species file (src/lang/splice.c) and a bad value in it is reported against that file;
 * tests/fuzz/run starts the harness at the repository's root. A small memory budget keeps one
 * input to milliseconds; the input's last byte may cut the stem levels. */
#include "fuzz.h"
#include "sylva/trees.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    FILE *diag = fuzz_diag();
    SylProgram *p = fuzz_compile("tests/data/arbaro/fuzz.syl", (const char *)data, size, 0);
    if (!p) return 0;
    if (syl_program_kind(p) == SYL_MODEL_WEBER) {
        int levels = size ? data[size - 1] % 5 : 0; /* 1..4 stem levels, or 0: all the block has */
        SylTreeOptions t = {.threads = 1, .levels = levels, .max_memory = 4u << 20, .diag = diag};
        SylSkeleton *sk = NULL;
        int st = syl_weber_build(p, &t, &sk);
        fuzz_mesh_tree_and_free(st, sk, diag);
    }
    syl_program_free(p);
    return 0;
}
