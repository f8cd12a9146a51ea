/* Terrain factors against what analytic terrains make them: planes of every slope and
 * aspect, a cone and a V-valley whose D8 accumulation can be counted, a pit and a walled
 * basin that priority-flood fills to their spill heights, a wall's shadow band and a flat
 * plane's even light, Winstral's Sx behind a ridge, the horizon bound against brute force,
 * and bilinear sampling. */
#include <math.h>

#include "unit.h"

#include "terrain/terrain.h"

#include "terrain_fixtures.h"

static double angle_diff(double a, double b) {
    double d = fmod(fabs(a - b), 360);
    return d > 180 ? 360 - d : d;
}

/* A plane of slope S facing azimuth A (downhill toward A, clockwise from north), for S in
 * 5..60 degrees and A every 15 degrees: Horn recovers both in every interior cell. */
static void planes_of_every_slope_and_aspect(void **state) {
    (void)state;
    Terrain *t = grid(9, 7, 2.5);
    float *slope = terrain_grid(t, sizeof(float), diag_sink(&(SylSink){0}, stderr, NULL)), *aspect = terrain_grid(t, sizeof(float), diag_sink(&(SylSink){0}, stderr, NULL));
    for (int s = 5; s <= 60; s += 11)
        for (int a = 0; a < 360; a += 15) {
            double ts = tan(s * M_PI / 180), ar = a * M_PI / 180;
            /* downhill (east, north) = (sin A, cos A); z points south */
            double gx = -ts * sin(ar), gz = ts * cos(ar);
            for (int k = 0; k < t->nz; k++)
                for (int i = 0; i < t->nx; i++) H(t, i, k) = (float)(100 + gx * i * t->cell + gz * k * t->cell);
            terrain_slope_aspect(t, slope, aspect, 1);
            for (int k = 1; k < t->nz - 1; k++)
                for (int i = 1; i < t->nx - 1; i++) {
                    if (fabs(AT(slope, t, i, k) - s) > 2e-3) fail_msg("slope %d aspect %d: slope %g", s, a, AT(slope, t, i, k));
                    if (angle_diff(AT(aspect, t, i, k), a) > 2e-3)
                        fail_msg("slope %d aspect %d: aspect %g", s, a, AT(aspect, t, i, k));
                }
        }
    /* flat: slope 0, aspect -1 (gdaldem writes its nodata there) */
    for (size_t c = 0; c < 63; c++) t->height[c] = 7;
    terrain_slope_aspect(t, slope, aspect, 1);
    for (size_t c = 0; c < 63; c++) {
        assert_true(slope[c] == 0);
        assert_true(aspect[c] == -1);
    }
    terrain_grid_free(t, slope, sizeof(float));
    terrain_grid_free(t, aspect, sizeof(float));
    syl_terrain_free(t);
}

static int flow_of(Terrain *t, float *acc, uint8_t *dir, float *filled) {
    uint8_t *parent = (uint8_t *)terrain_grid(t, 1, diag_sink(&(SylSink){0}, stderr, NULL));
    int st = terrain_fill(t, filled, parent, diag_sink(&(SylSink){0}, stderr, NULL));
    if (!st) {
        terrain_d8(t, filled, parent, dir, 2);
        st = terrain_accumulate(t, dir, acc, diag_sink(&(SylSink){0}, stderr, NULL));
    }
    terrain_grid_free(t, parent, 1);
    return st;
}

/* The cells upstream of each cell counted by walking every cell's path down (not by the
 * accumulation's own order), and every cell's water leaving the grid exactly once. */
static void check_by_walking(Terrain *t, const uint8_t *dir, const float *acc) {
    size_t n = (size_t)t->nx * (size_t)t->nz;
    double *count = calloc(n, sizeof *count);
    size_t out = 0;
    for (size_t c = 0; c < n; c++) {
        size_t p = c, steps = 0;
        for (;;) {
            count[p]++;
            if (dir[p] == TERRAIN_OUT) break;
            p = (size_t)((long)(p / t->nx) + terrain_d8_dk[dir[p]]) * t->nx + (p % t->nx) + terrain_d8_di[dir[p]];
            if (++steps > n) fail_msg("a cycle in the D8 directions from cell %zu", c);
        }
        out++;
    }
    assert_int_equal(out, n);
    for (size_t c = 0; c < n; c++)
        if (count[c] != acc[c]) fail_msg("cell %zu: %g cells upstream by walking, %g accumulated", c, count[c], acc[c]);
    free(count);
}

/* A cone h = R - r, its apex between the four middle cells: everything drains outward, the
 * four top cells receive nothing, and a cell on a diagonal (exactly radial) receives only
 * the diagonal cells above it: d + 1 for the d-th from the middle. Every cell's count is
 * also checked by walking each path down. */
static void cone_flow_is_counted(void **state) {
    (void)state;
    int n = 40;
    Terrain *t = grid(n, n, 1);
    for (int k = 0; k < n; k++)
        for (int i = 0; i < n; i++) H(t, i, k) = (float)(30 - hypot(i + 0.5 - n / 2.0, k + 0.5 - n / 2.0));
    float *acc = terrain_grid(t, sizeof(float), diag_sink(&(SylSink){0}, stderr, NULL)), *filled = terrain_grid(t, sizeof(float), diag_sink(&(SylSink){0}, stderr, NULL));
    uint8_t *dir = (uint8_t *)terrain_grid(t, 1, diag_sink(&(SylSink){0}, stderr, NULL));
    assert_int_equal(flow_of(t, acc, dir, filled), SYL_OK);
    for (int k = 0; k < n; k++)
        for (int i = 0; i < n; i++) assert_true(AT(filled, t, i, k) == H(t, i, k)); /* no pit: nothing filled */
    int m = n / 2;
    for (int d = 0; d < m - 1; d++) { /* the grid's corners also gather its edges, which drain along them */
        assert_int_equal((int)AT(acc, t, m + d, m + d), d + 1);
        assert_int_equal((int)AT(acc, t, m - 1 - d, m - 1 - d), d + 1);
        assert_int_equal((int)AT(acc, t, m + d, m - 1 - d), d + 1);
        assert_int_equal((int)AT(acc, t, m - 1 - d, m + d), d + 1);
    }
    check_by_walking(t, dir, acc);
    terrain_grid_free(t, acc, sizeof(float));
    terrain_grid_free(t, filled, sizeof(float));
    terrain_grid_free(t, dir, 1);
    syl_terrain_free(t);
}

/* A V-valley: steep sides fall toward the middle column, which falls gently south. Each side
 * cell drains straight across, so the channel's cell on row k gathers rows 0..k whole. */
static void valley_flow_gathers_whole_rows(void **state) {
    (void)state;
    int nx = 21, nz = 30, c = 10;
    Terrain *t = grid(nx, nz, 1);
    for (int k = 0; k < nz; k++)
        for (int i = 0; i < nx; i++) H(t, i, k) = (float)(5 * abs(i - c) + 0.1 * (nz - k));
    float *acc = terrain_grid(t, sizeof(float), diag_sink(&(SylSink){0}, stderr, NULL)), *filled = terrain_grid(t, sizeof(float), diag_sink(&(SylSink){0}, stderr, NULL));
    uint8_t *dir = (uint8_t *)terrain_grid(t, 1, diag_sink(&(SylSink){0}, stderr, NULL));
    assert_int_equal(flow_of(t, acc, dir, filled), SYL_OK);
    for (int k = 0; k < nz; k++) {
        assert_int_equal((int)AT(acc, t, c, k), (k + 1) * nx);
        for (int i = 0; i < nx; i++)
            if (i != c) assert_int_equal((int)AT(acc, t, i, k), abs(i - c) <= 10 ? 11 - abs(i - c) : 1);
    }
    check_by_walking(t, dir, acc);
    terrain_grid_free(t, acc, sizeof(float));
    terrain_grid_free(t, filled, sizeof(float));
    terrain_grid_free(t, dir, 1);
    syl_terrain_free(t);
}

/* A pit in a plane falling east fills to the lowest cell of its rim on the way out (the
 * cell east of it); a basin walled at 5 with a notch at 3 fills to 3; nothing else moves,
 * and afterwards every cell drains off the grid. */
static void priority_flood_fills_to_the_spill_height(void **state) {
    (void)state;
    int n = 32;
    Terrain *t = grid(n, n, 1);
    for (int k = 0; k < n; k++)
        for (int i = 0; i < n; i++) H(t, i, k) = (float)(10 - 0.1 * i);
    for (int k = 15; k <= 17; k++)
        for (int i = 15; i <= 17; i++) H(t, i, k) = (float)(0.5 * (i - 15) + 0.25 * k - 4);
    float *acc = terrain_grid(t, sizeof(float), diag_sink(&(SylSink){0}, stderr, NULL)), *filled = terrain_grid(t, sizeof(float), diag_sink(&(SylSink){0}, stderr, NULL));
    uint8_t *dir = (uint8_t *)terrain_grid(t, 1, diag_sink(&(SylSink){0}, stderr, NULL));
    assert_int_equal(flow_of(t, acc, dir, filled), SYL_OK);
    for (int k = 0; k < n; k++)
        for (int i = 0; i < n; i++) {
            bool pit = k >= 15 && k <= 17 && i >= 15 && i <= 17;
            float want = pit ? H(t, 18, 16) : H(t, i, k);
            if (AT(filled, t, i, k) != want) fail_msg("cell %d,%d filled to %g, not %g", i, k, AT(filled, t, i, k), want);
        }
    check_by_walking(t, dir, acc);
    /* the basin: a square wall from 8 to 24 at height 5 on flat 0, a notch at 3 */
    for (int k = 0; k < n; k++)
        for (int i = 0; i < n; i++) {
            bool wall = (i == 8 || i == 24) ? k >= 8 && k <= 24 : (k == 8 || k == 24) && i >= 8 && i <= 24;
            H(t, i, k) = wall ? 5 : 0;
        }
    H(t, 24, 16) = 3;
    assert_int_equal(flow_of(t, acc, dir, filled), SYL_OK);
    for (int k = 0; k < n; k++)
        for (int i = 0; i < n; i++) {
            bool inside = i > 8 && i < 24 && k > 8 && k < 24;
            float want = inside ? 3 : H(t, i, k);
            if (AT(filled, t, i, k) != want) fail_msg("basin cell %d,%d filled to %g, not %g", i, k, AT(filled, t, i, k), want);
        }
    /* all 15 x 15 inside cells leave through the notch */
    assert_true(AT(acc, t, 24, 16) >= 15 * 15 + 1);
    check_by_walking(t, dir, acc);
    terrain_grid_free(t, acc, sizeof(float));
    terrain_grid_free(t, filled, sizeof(float));
    terrain_grid_free(t, dir, 1);
    syl_terrain_free(t);
}

static float *insolation(Terrain *t, const TerrainSun *suns, size_t nsuns, int threads) {
    float *out = terrain_grid(t, sizeof(float), diag_sink(&(SylSink){0}, stderr, NULL));
    assert_int_equal(terrain_insolation(t, suns, nsuns, out, threads, diag_sink(&(SylSink){0}, stderr, NULL)), SYL_OK);
    return out;
}

/* A wall 10 high across a flat field, the sun due south 30 degrees up: the wall's shadow
 * falls on the cells north of it closer than 10 / tan 30 = 17.3 cells, and nowhere else. */
static void a_wall_shades_a_band(void **state) {
    (void)state;
    int n = 64, w = 40;
    Terrain *t = grid(n, n, 1);
    for (int i = 0; i < n; i++) H(t, i, w) = 10;
    TerrainSun sun = {{0, 0.5f, (float)cos(M_PI / 6)}, 1};
    float *out = insolation(t, &sun, 1, 2);
    for (int k = 0; k < n; k++)
        for (int i = 0; i < n; i++) {
            int d = w - k; /* cells north of the wall */
            if (abs(d) <= 1) continue; /* the wall and its feet, which slope */
            float want = d >= 2 && d <= 17 ? 0 : 1;
            if (fabsf(AT(out, t, i, k) - want) > 1e-5f)
                fail_msg("cell %d,%d (%d north of the wall): %g, not %g", i, k, d, AT(out, t, i, k), want);
        }
    terrain_grid_free(t, out, sizeof(float));
    /* the year's suns on a flat plane: every cell the same, as sunny as open flat ground */
    for (int i = 0; i < n; i++) H(t, i, w) = 0;
    size_t ns;
    TerrainSun *suns = terrain_suns(46, 12, 60, &ns);
    assert_true(ns > 50);
    out = insolation(t, suns, ns, 2);
    for (size_t c = 0; c < (size_t)n * n; c++) assert_true(fabsf(out[c] - 1) < 1e-6f);
    terrain_grid_free(t, out, sizeof(float));
    /* a south slope is sunnier than open ground, a north slope less sunny, at 46 degrees north */
    for (int k = 0; k < n; k++)
        for (int i = 0; i < n; i++) H(t, i, k) = (float)(0.3 * k); /* rising south: faces north */
    out = insolation(t, suns, ns, 1);
    float north = AT(out, t, 30, 30);
    terrain_grid_free(t, out, sizeof(float));
    for (int k = 0; k < n; k++)
        for (int i = 0; i < n; i++) H(t, i, k) = (float)(-0.3 * k);
    out = insolation(t, suns, ns, 1);
    float south = AT(out, t, 30, 30);
    assert_true(north < 0.95f && south > 1.05f);
    terrain_grid_free(t, out, sizeof(float));
    free(suns);
    syl_terrain_free(t);
}

/* The sun's path: at the equinox's noon the sun stands 90 - latitude high in the south; on
 * the June solstice 23.45 higher; the year's positions are above the horizon. */
static void the_sun_path_has_its_noon_heights(void **state) {
    (void)state;
    size_t n;
    TerrainSun *s = terrain_suns(46, 1, 1440, &n); /* one day (172.25: the solstice), one position: noon */
    assert_int_equal(n, 1);
    assert_true(fabs(asin(s[0].dir[1]) * 180 / M_PI - (90 - 46 + 23.45)) < 1e-3);
    assert_true(s[0].dir[2] > 0 && fabsf(s[0].dir[0]) < 1e-6f); /* due south (+z) */
    free(s);
    s = terrain_suns(46, 12, 60, &n);
    double w = 0;
    for (size_t i = 0; i < n; i++) {
        assert_true(s[i].dir[1] > 0);
        w += s[i].weight;
    }
    free(s);
    /* 12 days of 24 positions, about half of them above the horizon */
    assert_true(w > 0.45 * 12 * 24 && w < 0.55 * 12 * 24);
}

/* The bound that spares rays is a bound: in each quadrant no cell rises above it. */
static void the_horizon_bound_holds(void **state) {
    (void)state;
    int n = 24;
    Terrain *t = grid(n, n, 2);
    for (int k = 0; k < n; k++)
        for (int i = 0; i < n; i++) H(t, i, k) = (float)(20 * sin(i * 0.7) * cos(k * 0.45) + 0.3 * ((i * 7 + k * 13) % 11));
    float *bound = terrain_grid(t, 4 * sizeof(float), diag_sink(&(SylSink){0}, stderr, NULL)), *scratch = terrain_grid(t, 2 * sizeof(float), diag_sink(&(SylSink){0}, stderr, NULL));
    terrain_horizon_bound(t, bound, scratch);
    size_t cells = (size_t)n * n;
    for (int q = 0; q < 4; q++) {
        int sx = q & 1 ? 1 : -1, sz = q & 2 ? 1 : -1;
        for (int k = 0; k < n; k++)
            for (int i = 0; i < n; i++)
                for (int k2 = 0; k2 < n; k2++)
                    for (int i2 = 0; i2 < n; i2++) {
                        int dx = (i2 - i) * sx, dz = (k2 - k) * sz;
                        if (dx < 0 || dz < 0 || (dx == 0 && dz == 0)) continue;
                        double r = (H(t, i2, k2) - H(t, i, k)) / (hypot(dx, dz) * t->cell);
                        if (r > bound[q * cells + (size_t)k * n + i] + 1e-6)
                            fail_msg("quadrant %d, cell %d,%d: %d,%d rises %g, above the bound %g", q, i, k, i2, k2, r,
                                     bound[q * cells + (size_t)k * n + i]);
                    }
    }
    terrain_grid_free(t, bound, 4 * sizeof(float));
    terrain_grid_free(t, scratch, 2 * sizeof(float));
    syl_terrain_free(t);
}

/* A ridge 10 high, 10 cells to its feet, across a flat field. Wind from the west: a flat lee
 * cell d cells beyond the crest sees it at atan(10 / d); on the lee slope the crest is 45
 * degrees up; windward the farthest flat ground is the highest angle, atan(-h / distance);
 * beyond the search distance the ridge shelters nothing. The same with the wind from the
 * north and the ridge turned. */
static void winstral_sx_behind_a_ridge(void **state) {
    (void)state;
    int n = 101, m = 9, r = 50;
    Terrain *t = grid(n, m, 1);
    for (int k = 0; k < m; k++)
        for (int i = 0; i < n; i++) H(t, i, k) = (float)fmax(0, 10 - abs(i - r));
    float *sx = terrain_grid(t, sizeof(float), diag_sink(&(SylSink){0}, stderr, NULL));
    terrain_wind(t, 270, 300, sx, 2);
    const double deg = 180 / M_PI;
    for (int k = 0; k < m; k++)
        for (int i = 0; i < n; i++) {
            double want;
            if (i > r + 10) want = atan(10.0 / (i - r)) * deg;
            else if (i > r) want = 45;
            else if (i >= r - 10) want = i ? atan(-H(t, i, k) / i) * deg : 0;
            else want = 0;
            if (fabs(AT(sx, t, i, k) - want) > 1e-4) fail_msg("cell %d: Sx %g, not %g", i, AT(sx, t, i, k), want);
        }
    terrain_wind(t, 270, 20, sx, 1);
    assert_true(fabs(AT(sx, t, r + 15, 4) - atan(10.0 / 15) * deg) < 1e-4); /* the crest within 20 */
    assert_true(fabs(AT(sx, t, r + 30, 4)) < 1e-6);                         /* only flat ground within 20 */
    terrain_grid_free(t, sx, sizeof(float));
    syl_terrain_free(t);
    /* turned: the ridge along x, the wind from the north (−z), the lee to the south */
    t = grid(m, n, 1);
    for (int k = 0; k < n; k++)
        for (int i = 0; i < m; i++) H(t, i, k) = (float)fmax(0, 10 - abs(k - r));
    sx = terrain_grid(t, sizeof(float), diag_sink(&(SylSink){0}, stderr, NULL));
    terrain_wind(t, 0, 300, sx, 1);
    for (int k = r + 11; k < n; k++) assert_true(fabs(AT(sx, t, 4, k) - atan(10.0 / (k - r)) * deg) < 1e-4);
    assert_true(AT(sx, t, 4, r - 20) == 0); /* windward flat ground */
    terrain_grid_free(t, sx, sizeof(float));
    syl_terrain_free(t);
}

/* Sampling: bilinear between cell centres reproduces a plane anywhere inside, clamps
 * outside; aspect is the nearest cell's; a factor not computed is NaN. */
static void sampling_is_bilinear(void **state) {
    (void)state;
    Terrain *t = grid(6, 5, 2);
    t->x0 = -3, t->z0 = 10;
    for (int k = 0; k < 5; k++)
        for (int i = 0; i < 6; i++) H(t, i, k) = (float)(3 * i - 2 * k);
    for (double x = -2; x <= 7; x += 0.37)
        for (double z = 11; z <= 18; z += 0.41) {
            double i = (x - t->x0) / 2 - 0.5, k = (z - t->z0) / 2 - 0.5;
            assert_true(fabs(terrain_factor_at(t, SYL_TERRAIN_ALTITUDE, x, z) - (3 * i - 2 * k)) < 1e-9);
        }
    assert_true(terrain_factor_at(t, SYL_TERRAIN_ALTITUDE, -100, -100) == H(t, 0, 0));
    assert_true(terrain_factor_at(t, SYL_TERRAIN_ALTITUDE, 100, 100) == H(t, 5, 4));
    assert_true(isnan(syl_terrain_factor_at(t, SYL_TERRAIN_SLOPE, 0, 12)));
    SylTerrainOptions o = {.threads = 1, .sun_days = 2, .sun_minutes = 240};
    assert_int_equal(syl_terrain_compute(t, &o), SYL_OK);
    /* aspect of a plane rising east and north: every cell faces the same way */
    double a = terrain_factor_at(t, SYL_TERRAIN_ASPECT, 2.9, 13.1);
    assert_true(a == AT(t->factor[SYL_TERRAIN_ASPECT], t, 2, 1));
    syl_terrain_free(t);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(planes_of_every_slope_and_aspect),
        cmocka_unit_test(cone_flow_is_counted),
        cmocka_unit_test(valley_flow_gathers_whole_rows),
        cmocka_unit_test(priority_flood_fills_to_the_spill_height),
        cmocka_unit_test(a_wall_shades_a_band),
        cmocka_unit_test(the_sun_path_has_its_noon_heights),
        cmocka_unit_test(the_horizon_bound_holds),
        cmocka_unit_test(winstral_sx_behind_a_ridge),
        cmocka_unit_test(sampling_is_bilinear),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
