/* libFuzzer harness: Pafčo files and `pafco` blocks on arbitrary source — the file's reader
 * (src/lang/pafco_cfg.c: told by content, NAME=value lines), the parameters' reader (src/pafco/
 * params.c: ranges, switches, file names, fallbacks with warnings), the generator under a small
 * memory budget so that one input takes milliseconds, and the mesher on the tree. */
#include "fuzz.h"
#include "sylva/grow.h"
#include "sylva/mesh.h"
#include "sylva/sylva.h"
#include "sylva/trees.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    FILE *diag = fuzz_diag();
    SylProgram *p = fuzz_compile("fuzz.cfg", (const char *)data, size, 0);
    if (!p) return 0;
    if (syl_program_kind(p) == SYL_MODEL_PAFCO) {
        double age = size ? (double)data[size - 1] / 255 : 0; /* growth by height; 0 or 1: full grown */
        SylTreeOptions t = {.threads = 1, .age = age, .max_memory = 2u << 20, .diag = diag};
        SylSkeleton *sk = NULL;
        int st = syl_pafco_build(p, &t, &sk);
        fuzz_mesh_tree_and_free(st, sk, diag);
    }
    syl_program_free(p);
    return 0;
}
