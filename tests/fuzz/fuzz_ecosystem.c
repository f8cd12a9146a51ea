/* libFuzzer harness: `ecosystem` blocks on arbitrary source — the block's reader (src/eco/
 * params.c: species lines, tolerance curves, ranges, model names) and, when it reads, a few
 * years of the simulation on a small synthetic terrain over 1 to 3 x 3 tiles, with a cap on
 * plants so that one input takes milliseconds. */
#include <stdlib.h>

#include "fuzz.h"
#include "sylva/ecosystem.h"
#include "sylva/sylva.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    int status;
    FILE *diag = fuzz_diag();
    SylCompileOptions opt = {.diag = diag, .validate = syl_validate}; /* every kind, the ecosystem too */
    SylProgram *p = syl_compile("fuzz.syl", (const char *)data, size, &opt, &status);
    if (!p) return 0;
    static SylEcoModel m;
    if (syl_program_kind(p) == SYL_MODEL_ECOSYSTEM && !syl_ecosystem_read(p, &m, diag ? &(SylSink){syl_diagnostic_print, diag} : NULL)) {
        enum { N = 12 };
        static float h[N * N], f[SYL_TERRAIN_FACTORS][N * N];
        static uint8_t valid[N * N];
        SylTerrain t = {.nx = N, .nz = N, .cell = 2, .height = h, .valid = valid};
        for (int c = 0; c < N * N; c++) {
            h[c] = (float)(c % N + c / N);
            valid[c] = c != 5;
            for (int k = 0; k < SYL_TERRAIN_FACTORS; k++) f[k][c] = (float)((c * (k + 3)) % 17);
        }
        for (int k = 0; k < SYL_TERRAIN_FACTORS; k++) t.factor[k] = f[k];
        int tiles = size ? 1 + data[size - 1] % 3 : 1;
        SylEcoOptions o = {.years = m.years < 12 ? m.years : 12, .tiles_x = tiles, .tiles_z = tiles,
                           .threads = 1, .max_plants = 4000, .diag = diag};
        syl_ecosystem_simulate(&m, &t, &o, NULL);
    }
    syl_program_free(p);
    return 0;
}
