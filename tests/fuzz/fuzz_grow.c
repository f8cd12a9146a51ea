/* libFuzzer harness: `grow` blocks and `scene` blocks on arbitrary source, grown for two
 * years with small limits, then meshed — the directive readers of src/sot and the growth
 * engine behind them. */
#include "fuzz.h"
#include "sylva/grow.h"
#include "sylva/mesh.h"
#include "sylva/sylva.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    FILE *diag = fuzz_diag();
    SylProgram *p = fuzz_compile("fuzz.syl", (const char *)data, size, 0);
    if (!p) return 0;
    SylModelKind kind = syl_program_kind(p);
    SylGrowOptions g = {.years = 2, .threads = 1, .max_metamers = 3000, .diag = diag};
    SylSkeleton *sk = NULL;
    SylMesh *obstacles = NULL;
    int st = SYL_EMODEL;
    if (kind == SYL_MODEL_GROW) st = syl_grow_build(p, &g, &sk);
    else if (kind == SYL_MODEL_SCENE) st = syl_grow_build_scene(p, &g, &sk, &obstacles);
    if (st == SYL_OK && sk) {
        SylMesh *m = NULL;
        SylMeshOptions mo = {.sides = 4, .radius = SYL_RADIUS_PIPE, .threads = 1, .diag = diag};
        if (syl_mesh_build(sk, &mo, &m) == SYL_OK) syl_mesh_free(m);
    }
    syl_mesh_free(obstacles);
    syl_skeleton_free(sk);
    syl_program_free(p);
    return 0;
}
