/* libFuzzer harness: `strands` blocks on arbitrary source — the block's reader (src/strands/
 * params.c: numbers, curves, ranges, --set-free), Algorithm 2 under a small memory budget so
 * that one input takes milliseconds, and the mesher on the tree. */
#include "fuzz.h"
#include "sylva/grow.h"
#include "sylva/mesh.h"
#include "sylva/sylva.h"
#include "sylva/trees.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    FILE *diag = fuzz_diag();
    SylProgram *p = fuzz_compile("fuzz.syl", (const char *)data, size, 0);
    if (!p) return 0;
    if (syl_program_kind(p) == SYL_MODEL_STRANDS) {
        double age = size ? (double)data[size - 1] / 255 : 0; /* 0 or 1: full grown */
        SylTreeOptions t = {.threads = 1, .age = age, .max_memory = 2u << 20, .diag = diag};
        SylSkeleton *sk = NULL;
        int st = syl_strands_build(p, &t, &sk);
        fuzz_mesh_tree_and_free(st, sk, diag);
    }
    syl_program_free(p);
    return 0;
}
