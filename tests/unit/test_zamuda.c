/* Zamuda's (2006) terrain measures against what analytic terrains make them: a flat plane is
 * alike everywhere; runoff humidity conserves the rain, grows monotonically down a tilted plane
 * and gathers on a valley's floor, not its ridges; his lee-angle windiness is 1 on the
 * windward side of a ridge and below 1 in its lee, 1 again behind a wall steeper than Θ0;
 * sunniness is higher on a south-facing slope than a north-facing one (north of the equator)
 * and mirror-symmetric east–west as his sun's path is; the maps do not depend on threads. */
#include <math.h>
#include <string.h>

#include "unit.h"

#include "terrain/terrain.h"

#include "terrain_fixtures.h"

static void compute(Terrain *t, int threads) {
    SylTerrainOptions o = {.measures = SYL_TERRAIN_ZAMUDA, .threads = threads, .diag = stderr};
    assert_int_equal(syl_terrain_compute(t, &o), SYL_OK);
    assert_null(t->factor[SYL_TERRAIN_WETNESS]); /* GIS's not asked for */
}

static double mean(const Terrain *t, const float *g) {
    double s = 0;
    for (int c = 0; c < t->nx * t->nz; c++) s += g[c];
    return s / (t->nx * t->nz);
}

static void a_plane_is_alike_everywhere(void **state) {
    (void)state;
    Terrain *t = grid(12, 9, 25);
    for (int c = 0; c < 12 * 9; c++) t->height[c] = 400;
    compute(t, 2);
    const float *hu = t->factor[SYL_TERRAIN_HUMIDITY], *su = t->factor[SYL_TERRAIN_SUNNINESS],
                *wi = t->factor[SYL_TERRAIN_WINDINESS];
    for (int c = 0; c < 12 * 9; c++) {
        assert_true(hu[c] == 1); /* the rain, no runoff */
        assert_true(su[c] == su[0]);
        assert_true(wi[c] == 1); /* open ground: his W = 1 */
    }
    /* flat ground at 46°N: 9 suns, weights 1..2..1, cosines of the suns' elevations; sunrise
     * and sunset on the horizon give 0 */
    double want = 0, e = 44 * M_PI / 180;
    for (int n = 0; n < 9; n++) {
        double u = n / 4.0, p[3];
        double p0[3] = {1, 0, -0.37}, mid[3] = {0, sin(e), cos(e)}, p1[3] = {-1, 0, -0.37};
        for (int a = 0; a < 3; a++) p[a] = n <= 4 ? p0[a] + u * (mid[a] - p0[a]) : mid[a] + (u - 1) * (p1[a] - mid[a]);
        want += p[1] / sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) * (n <= 4 ? 1 + u : 3 - u);
    }
    assert_true(fabs(su[0] - want / 9) < 1e-6);
    syl_terrain_free(t);
}

/* Down a plane tilted toward the south, water runs row to row: each column alike, the
 * humidity never less downhill and more at the foot than at the top; none is lost. */
static void runoff_grows_down_a_tilted_plane(void **state) {
    (void)state;
    Terrain *t = grid(10, 30, 25);
    for (int k = 0; k < 30; k++)
        for (int i = 0; i < 10; i++) H(t, i, k) = (float)(600 - 8 * k);
    compute(t, 1);
    const float *hu = t->factor[SYL_TERRAIN_HUMIDITY];
    for (int k = 0; k < 30; k++) {
        for (int i = 1; i < 10; i++) assert_true(fabs(AT(hu, t, i, k) - AT(hu, t, 0, k)) < 1e-6);
        if (k) assert_true(AT(hu, t, 0, k) >= AT(hu, t, 0, k - 1) - 1e-6);
    }
    assert_true(AT(hu, t, 0, 29) > 1.5 * AT(hu, t, 0, 0));
    assert_true(fabs(mean(t, hu) - 1) < 1e-6); /* conserved: the blur too */
    syl_terrain_free(t);
}

/* A V-valley along z: its floor is wetter than its ridges; water below the water level adds
 * 10 to the mean in proportion. */
static void runoff_gathers_in_a_valley(void **state) {
    (void)state;
    Terrain *t = grid(41, 20, 25);
    for (int k = 0; k < 20; k++)
        for (int i = 0; i < 41; i++) H(t, i, k) = (float)(300 + 6 * abs(i - 20) + 0.5 * k);
    compute(t, 1);
    const float *hu = t->factor[SYL_TERRAIN_HUMIDITY];
    for (int k = 0; k < 20; k++) {
        assert_true(AT(hu, t, 20, k) > AT(hu, t, 0, k));
        assert_true(AT(hu, t, 20, k) > AT(hu, t, 40, k));
        assert_true(fabs(AT(hu, t, 10, k) - AT(hu, t, 30, k)) < 1e-4); /* mirror-symmetric */
    }
    assert_true(fabs(mean(t, hu) - 1) < 1e-5);
    /* water: ȳ below 0.1 (the valley floor's lowest cells) */
    float lo = 1e9f, hi = -1e9f;
    for (int c = 0; c < 41 * 20; c++) lo = fminf(lo, t->height[c]), hi = fmaxf(hi, t->height[c]);
    int wet = 0;
    for (int c = 0; c < 41 * 20; c++) wet += (t->height[c] - lo) / (double)(hi - lo) < 0.1;
    float *w = terrain_grid(t, sizeof(float), diag_sink(&(SylSink){0}, stderr, NULL));
    assert_int_equal(terrain_runoff(t, t->factor[SYL_TERRAIN_SLOPE], 10, 0.1, w, diag_sink(&(SylSink){0}, stderr, NULL)), SYL_OK);
    assert_true(wet > 0);
    assert_true(fabs(mean(t, w) - (1 + 10.0 * wet / (41 * 20))) < 1e-5);
    terrain_grid_free(t, w, sizeof(float));
    syl_terrain_free(t);
}

/* A ridge along z, the wind from the west: the windward (west) side is open (1), the lee
 * (east) side within N_w patches sheltered (< 1) by 1 − φ/Θ0, and the map mirror-symmetric
 * north–south (the wind blows along x). */
static void the_lee_of_a_ridge_is_calmer(void **state) {
    (void)state;
    int n = 61, r = 30;
    Terrain *t = grid(n, 11, 10);
    for (int k = 0; k < 11; k++)
        for (int i = 0; i < n; i++) H(t, i, k) = (float)fmax(0, 50 - 4 * abs(i - r)); /* 21.8° sides */
    compute(t, 3);
    const float *wi = t->factor[SYL_TERRAIN_WINDINESS];
    for (int k = 0; k < 11; k++)
        for (int i = 0; i < n; i++) {
            assert_true(fabs(AT(wi, t, i, k) - AT(wi, t, i, 10 - k)) < 1e-6);
            if (i <= r) assert_true(AT(wi, t, i, k) == 1);
        }
    /* 5 cells east of the crest, 20 m lower: the crest is 5 cells upwind, φ = atan(20 / 50) */
    double phi = atan(20.0 / 50) * 180 / M_PI;
    assert_true(fabs(AT(wi, t, r + 5, 5) - (1 - phi / 45)) < 1e-4);
    for (int i = r + 1; i <= r + 12; i++) assert_true(AT(wi, t, i, 5) < 1);
    assert_true(AT(wi, t, 55, 5) == 1); /* flat ground more than N_w = 10 patches past the foot (r + 12.5) */
    syl_terrain_free(t);
}

/* Behind a wall steeper than Θ0 = 45° the shelter vanishes (his 4.10): windiness 1 right
 * behind it, sheltered farther on where the angle to its top is below 45°. */
static void behind_a_steep_wall_the_wind_comes_back(void **state) {
    (void)state;
    Terrain *t = grid(40, 3, 1);
    for (int k = 0; k < 3; k++)
        for (int i = 0; i < 40; i++) H(t, i, k) = i == 10 ? 5 : 0;
    compute(t, 1);
    const float *wi = t->factor[SYL_TERRAIN_WINDINESS];
    assert_true(AT(wi, t, 11, 1) == 1);             /* atan(5 / 1) > 45° */
    assert_true(AT(wi, t, 14, 1) == 1);             /* atan(5 / 4) > 45° */
    assert_true(AT(wi, t, 16, 1) < 0.15);           /* atan(5 / 6), just below 45°: nearly calm */
    assert_true(fabs(AT(wi, t, 16, 1) - (1 - atan(5.0 / 6) * 180 / M_PI / 45)) < 1e-4);
    assert_true(AT(wi, t, 19, 1) > AT(wi, t, 16, 1)); /* farther: less shelter */
    assert_true(AT(wi, t, 21, 1) == 1);             /* 11 cells: beyond N_w = 10 */
    syl_terrain_free(t);
}

/* A ridge along x: its southern face, turned to the noon sun at 46°N, is sunnier than its
 * northern face; the map is mirror-symmetric east–west; south of the equator the faces swap. */
static void a_south_slope_is_sunnier(void **state) {
    (void)state;
    int n = 41, r = 20;
    for (int hemi = 0; hemi < 2; hemi++) {
        Terrain *t = grid(21, n, 10);
        for (int k = 0; k < n; k++)
            for (int i = 0; i < 21; i++) H(t, i, k) = (float)(200 - 3 * abs(k - r) - 0.02 * (i - 10) * (i - 10));
        SylTerrainOptions o = {.measures = SYL_TERRAIN_ZAMUDA, .threads = 2, .latitude = hemi ? -46 : 46, .sun_set = 1};
        assert_int_equal(syl_terrain_compute(t, &o), SYL_OK);
        const float *su = t->factor[SYL_TERRAIN_SUNNINESS];
        for (int d = 2; d < r; d++) {
            double south = AT(su, t, 10, r + d), north = AT(su, t, 10, r - d);
            assert_true(hemi ? north > south : south > north);
        }
        for (int k = 0; k < n; k++)
            for (int i = 0; i < 21; i++) assert_true(fabs(AT(su, t, i, k) - AT(su, t, 20 - i, k)) < 1e-6);
        syl_terrain_free(t);
    }
}

/* Any thread count: the same bytes. */
static void threads_change_nothing(void **state) {
    (void)state;
    float *g[2][3];
    for (int run = 0; run < 2; run++) {
        Terrain *t = grid(37, 29, 25);
        for (int k = 0; k < 29; k++)
            for (int i = 0; i < 37; i++) H(t, i, k) = (float)(300 + 80 * sin(i * 0.4) * cos(k * 0.3) + 3 * i);
        compute(t, run ? 7 : 1);
        for (int f = 0; f < 3; f++) {
            g[run][f] = malloc(37 * 29 * sizeof(float));
            memcpy(g[run][f], t->factor[SYL_TERRAIN_HUMIDITY + f], 37 * 29 * sizeof(float));
        }
        syl_terrain_free(t);
    }
    for (int f = 0; f < 3; f++) {
        assert_memory_equal(g[0][f], g[1][f], 37 * 29 * sizeof(float));
        free(g[0][f]), free(g[1][f]);
    }
}

/* Bad options are refused, not computed. */
static void bad_options_are_refused(void **state) {
    (void)state;
    Terrain *t = grid(4, 4, 1);
    SylTerrainOptions o = {.measures = SYL_TERRAIN_ZAMUDA, .sun_samples = 8};
    assert_int_equal(syl_terrain_compute(t, &o), SYL_EUSAGE);
    o = (SylTerrainOptions){.measures = SYL_TERRAIN_ZAMUDA, .lee_angle = 120};
    assert_int_equal(syl_terrain_compute(t, &o), SYL_EUSAGE);
    o = (SylTerrainOptions){.measures = 9};
    assert_int_equal(syl_terrain_compute(t, &o), SYL_EUSAGE);
    syl_terrain_free(t);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_plane_is_alike_everywhere),
        cmocka_unit_test(runoff_grows_down_a_tilted_plane),
        cmocka_unit_test(runoff_gathers_in_a_valley),
        cmocka_unit_test(the_lee_of_a_ridge_is_calmer),
        cmocka_unit_test(behind_a_steep_wall_the_wind_comes_back),
        cmocka_unit_test(a_south_slope_is_sunnier),
        cmocka_unit_test(threads_change_nothing),
        cmocka_unit_test(bad_options_are_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
