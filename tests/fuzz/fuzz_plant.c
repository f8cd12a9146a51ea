/* libFuzzer harness: the whole way of `sylva mesh` on arbitrary source — compile, a bounded
 * derivation, `interpret` rules, the turtle and the mesher (both radius models) — with the
 * derived string bounded so that one input takes milliseconds. */
#include "fuzz.h"
#include "sylva/grow.h"
#include "sylva/mesh.h"
#include "sylva/skeleton.h"
#include "sylva/sylva.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    FILE *diag = fuzz_diag();
    SylProgram *p = fuzz_compile("fuzz.syl", (const char *)data, size, 0);
    if (!p) return 0;
    if (syl_program_kind(p) != SYL_MODEL_LSYSTEM) {
        syl_program_free(p);
        return 0;
    }
    SylDeriveOptions d = {.steps = -1, .threads = 1, .max_modules = 5000, .max_memory = 32u << 20, .diag = diag};
    if (syl_program_steps(p) > 6) d.steps = 6;
    SylString *s = NULL, *t = NULL;
    SylSkeleton *sk = NULL;
    if (syl_derive(p, &d, &s) == SYL_OK && syl_interpret(p, s, &d, &t) == SYL_OK &&
        syl_string_length(t) <= 20000 &&
        syl_turtle_draw(p, t, &(SylTurtleOptions){.diag = diag}, &sk) == SYL_OK) {
        for (int radius = SYL_RADIUS_MODEL; radius <= SYL_RADIUS_PIPE; radius++) {
            SylMesh *m = NULL;
            SylMeshOptions mo = {.sides = 5, .radius = radius, .threads = 1, .diag = diag};
            if (syl_mesh_build(sk, &mo, &m) == SYL_OK) syl_mesh_free(m);
        }
        syl_skeleton_write_json(sk, diag);
    }
    syl_skeleton_free(sk);
    syl_string_free(t);
    syl_string_free(s);
    syl_program_free(p);
    return 0;
}
