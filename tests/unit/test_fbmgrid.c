/* fbm_grid_at and fbm_grid_row (a whole row at once), which textures read at every pixel from
 * per-column and per-row lattice cells (fbm_axis), are fbm_at to the bit: every pattern's noises, at pixel centres of several sizes
 * and at random places (negative, past the period), compared as bits. */
#include "unit.h"

#include "texture/texture.h"
#include "util/rng.h"

static void same_bits(const Fbm *f, const float *xs, int nx, const float *ys, int ny) {
    FbmCell *cx = malloc((size_t)f->octaves * (size_t)nx * sizeof *cx), *cy = malloc((size_t)f->octaves * (size_t)ny * sizeof *cy);
    assert_non_null(cx), assert_non_null(cy);
    assert_true(fbm_axis(f, 0, xs, nx, cx));
    assert_true(fbm_axis(f, 1, ys, ny, cy));
    float *row = malloc((size_t)nx * sizeof *row);
    assert_non_null(row);
    for (int y = 0; y < ny; y++) {
        fbm_grid_row(f, cx, nx, cy, ny, y, row);
        for (int x = 0; x < nx; x++) {
            float want = fbm_at(f, xs[x], ys[y]), got = fbm_grid_at(f, cx, nx, x, cy, ny, y);
            if (memcmp(&want, &got, sizeof want) || memcmp(&want, &row[x], sizeof want))
                fail_msg("fbm %dx%d at (%a, %a): fbm_at %a, grid %a, row %a", f->fx, f->fy, (double)xs[x],
                         (double)ys[y], (double)want, (double)got, (double)row[x]);
        }
    }
    free(cx), free(cy), free(row);
}

static void grid_is_fbm_at(void **state) {
    (void)state;
    /* the patterns' fbms (texture.c's noises) and a few more */
    const struct { int fx, fy, octaves; float p; uint32_t seed; } cfg[] = {
        {12, 2, 4, 0.5f, 23}, {32, 4, 3, 0.5f, 37}, {3, 1, 2, 0.5f, 51}, {8, 8, 3, 0.5f, 71},
        {6, 6, 3, 0.5f, 81}, {8, 8, 4, 0.5f, 91}, {64, 64, 2, 0.6f, 93}, {1, 1, 8, 0.7f, 5}, {5, 3, 5, 0.45f, 7},
    };
    Rng r = rng_stream(33, 0, 0, 0);
    for (size_t c = 0; c < sizeof cfg / sizeof *cfg; c++) {
        Fbm f;
        fbm_init(&f, cfg[c].fx, cfg[c].fy, cfg[c].p, cfg[c].octaves, cfg[c].seed);
        const int sizes[] = {1, 7, 64, 256};
        for (size_t k = 0; k < sizeof sizes / sizeof *sizes; k++) { /* pixel centres, shifted as grass's */
            int n = sizes[k];
            float xs[256], ys[256];
            for (int i = 0; i < n; i++) xs[i] = ((float)i + 0.5f) / (float)n, ys[i] = xs[i] + 0.61f;
            same_bits(&f, xs, n, ys, n);
        }
        float xs[200], ys[50];
        for (int i = 0; i < 200; i++) xs[i] = (float)(rng_unit(&r) * 6 - 3);
        for (int i = 0; i < 50; i++) ys[i] = (float)(rng_unit(&r) * 6 - 3);
        same_bits(&f, xs, 200, ys, 50);
        fbm_free(&f);
    }
}

/* Without gradient tables (an octave not periodic) there is no grid: fbm_axis says so. */
static void no_table_no_grid(void **state) {
    (void)state;
    Fbm f;
    fbm_init(&f, 6, 0, 0.5f, 3, 11); /* the bark's stripes: no period along y */
    FbmCell cells[3 * 4];
    float at[4] = {0.1f, 0.2f, 0.3f, 0.4f};
    assert_false(fbm_axis(&f, 0, at, 4, cells));
    fbm_free(&f);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(grid_is_fbm_at),
        cmocka_unit_test(no_table_no_grid),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
