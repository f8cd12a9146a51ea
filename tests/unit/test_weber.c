/* The Weber–Penn generator's pieces against the paper's and Arbaro's formulas: ShapeRatio's
 * table, the parameter table's defaults and the doc that lists it, frames, radii. */
#include <math.h>
#include <string.h>

#include "unit.h"
#include "weber/internal.h"
#include "weber/lanes.h"

static void shape_ratio_table(void **state) {
    (void)state;
    WeberParams w;
    weber_params_default(&w);
    w.PruneWidthPeak = 0.5, w.PrunePowerLow = 1, w.PrunePowerHigh = 1;
    const struct { int shape; double r, want; } rows[] = {
        {0, 0.3, 0.3}, /* Arbaro's conical */
        {1, 0.5, 1.0}, {1, 0.0, 0.2}, {2, 1.0, 1.0}, {2, 0.0, 0.2}, {3, 0.7, 1.0}, {4, 0.2, 0.6},
        {5, 0.35, 0.5}, {5, 0.85, 0.5}, {5, 0.7, 1.0}, {6, 0.5, 0.6}, {7, 0.35, 0.75}, {7, 0.85, 0.75},
        {8, 0.25, 0.5}, {8, 0.75, 0.5}, {8, 1.5, 0}, {8, -0.1, 0},
    };
    for (size_t i = 0; i < sizeof rows / sizeof *rows; i++)
        assert_true(fabs(weber_shape_ratio(&w, rows[i].shape, rows[i].r) - rows[i].want) < 1e-12);
    w.convention = WEBER_PAPER;
    assert_true(fabs(weber_shape_ratio(&w, 0, 0.3) - 0.44) < 1e-12); /* 0.2 + 0.8 r */
    /* the envelope below its peak: Arbaro divides by 1 - P, the paper by P */
    w.PruneWidthPeak = 0.6;
    assert_true(fabs(weber_shape_ratio(&w, 8, 0.7) - 0.3 / 0.6) < 1e-12);
    w.convention = WEBER_ARBARO;
    assert_true(fabs(weber_shape_ratio(&w, 8, 0.7) - 0.3 / 0.4) < 1e-12);
}

static void defaults_are_arbaros(void **state) {
    (void)state;
    WeberParams w;
    weber_params_default(&w);
    assert_true(w.Shape == 0 && w.Levels == 3 && w.Scale == 10 && w.Ratio == 0.05 && w.BaseSize == 0.25);
    assert_true(w.CurveRes[0] == 3 && w.CurveRes[1] == 3 && w.CurveRes[2] == 1 && w.CurveRes[3] == 1);
    assert_true(w.Branches[0] == 1 && w.Branches[1] == 10 && w.Branches[2] == 5 && w.Branches[3] == 5);
    assert_true(w.DownAngle[0] == 0 && w.DownAngle[1] == 30 && w.Rotate[3] == 120);
    assert_true(w.Length[0] == 1 && w.Length[1] == 0.5 && w.BranchDist[0] == 0 && w.BranchDist[2] == 1);
    assert_true(w.LeafScale == 0.2 && w.LeafScaleX == 0.5 && w.LeafDistrib == 4 && w.Flare == 0.5);
    assert_int_equal(w.convention, WEBER_ARBARO);
    assert_int_equal((int)w.seed, 13);
    assert_true(weber_lv(7) == 3 && weber_lv(2) == 2);
}

/* docs/weberpenn.md's parameter tables name exactly the parameters of params.def */
static void doc_lists_the_table(void **state) {
    (void)state;
    FILE *f = fopen("docs/weberpenn.md", "r");
    assert_non_null(f);
    char line[1024];
    int seen[128] = {0}, rows = 0;
    bool per_level = false;
    while (fgets(line, sizeof line, f)) {
        if (strstr(line, "| Parameter (per level)")) per_level = true;
        if (strncmp(line, "| `", 3)) continue;
        char *end = strchr(line + 3, '`');
        assert_non_null(end);
        *end = 0;
        int found = -1;
        for (int i = 0; i < weber_param_count; i++)
            if (!strcmp(weber_param_table[i].name, line + 3) && weber_param_table[i].per_level == per_level) found = i;
        if (found < 0) fail_msg("docs/weberpenn.md lists '%s', which params.def does not have", line + 3);
        seen[found]++;
        rows++;
    }
    fclose(f);
    for (int i = 0; i < weber_param_count; i++)
        if (seen[i] != 1) fail_msg("'%s' is listed %d times in docs/weberpenn.md", weber_param_table[i].name, seen[i]);
    assert_int_equal(rows, weber_param_count);
}

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* rotations keep the frame orthonormal and right-handed; a local turn about x moves z toward -y */
static void frames_stay_orthonormal(void **state) {
    (void)state;
    Frame f;
    frame_identity(&f);
    frame_rot_local(&f, 1, 0, 0, 90);
    assert_true(fabs(f.z[1] + 1) < 1e-12 && fabs(f.y[2] - 1) < 1e-12);
    Rng r = rng_stream(5, 0, 0, 0);
    for (int i = 0; i < 1000; i++) {
        switch (i % 4) {
        case 0: frame_rot_local(&f, 1, 0, 0, 360 * rng_unit(&r)); break;
        case 1: frame_rotxz(&f, 180 * rng_unit(&r), 360 * rng_unit(&r)); break;
        case 2: frame_rot_local(&f, cos(i), sin(i), 0, 90 * rng_unit(&r)); break;
        default: frame_rot_global(&f, (double[3]){0, 0, 1}, 360 * rng_unit(&r)); break;
        }
    }
    assert_true(fabs(dot(f.x, f.x) - 1) < 1e-9 && fabs(dot(f.y, f.y) - 1) < 1e-9 && fabs(dot(f.z, f.z) - 1) < 1e-9);
    assert_true(fabs(dot(f.x, f.y)) < 1e-9 && fabs(dot(f.y, f.z)) < 1e-9 && fabs(dot(f.x, f.z)) < 1e-9);
    double c[3] = {f.x[1] * f.y[2] - f.x[2] * f.y[1], f.x[2] * f.y[0] - f.x[0] * f.y[2], f.x[0] * f.y[1] - f.x[1] * f.y[0]};
    assert_true(fabs(dot(c, f.z) - 1) < 1e-9); /* x cross y = z */
}

/* the radius along a stem: cone, rounded end, flare */
static void radius_profile(void **state) {
    (void)state;
    WeberGen g = {0};
    weber_params_default(&g.w);
    WStem s = {.level = 1, .length = 2, .base_radius = 0.1};
    g.w.Taper[1] = 1;
    assert_true(fabs(weber_radius(&g, &s, 1) - 0.05) < 1e-12);
    g.w.Taper[1] = 2; /* a hemisphere of the base radius at the tip */
    assert_true(fabs(weber_radius(&g, &s, 2)) < 1e-12);
    assert_true(fabs(weber_radius(&g, &s, 2 - 0.1) - 0.1) < 1e-12);
    assert_true(fabs(weber_radius(&g, &s, 1) - 0.1) < 1e-12);
    WStem t = {.level = 0, .length = 10, .base_radius = 0.5};
    g.w.Taper[0] = 0, g.w.Flare = 1, g.w.Scale0 = 1;
    assert_true(fabs(weber_radius(&g, &t, 0) - 0.5 * 1.99) < 1e-12);
    assert_true(fabs(weber_radius(&g, &t, 10.0 / 8) - 0.5) < 1e-12); /* no flare above an eighth */
}

/* 0Scale and 0ScaleV on the trunk's base radius: the paper's Ratio x length x (0Scale ± 0ScaleV),
 * one uniform draw per trunk; Arbaro's Ratio x length (0Scale comes in weber_radius, 0ScaleV
 * jitters the mesh: the bark's SylMaterial.trunk_jitter). */
static void trunk_scale(void **state) {
    (void)state;
    WeberGen g = {.seed = 13};
    weber_params_default(&g.w);
    g.w.Ratio = 0.02, g.w.Scale0 = 0.8, g.w.Scale0V = 0.3;
    WStem t = {.level = 0, .length = 10};
    assert_true(fabs(weber_base_radius(&g, &t) - 0.2) < 1e-12); /* Arbaro's */
    g.w.convention = WEBER_PAPER;
    double lo = INFINITY, hi = -INFINITY, sum = 0;
    enum { N = 400 };
    for (int k = 0; k < N; k++) {
        t.key = weber_key(1, 0, (uint64_t)k);
        double f = weber_base_radius(&g, &t) / 0.2;
        assert_true(f >= 0.5 - 1e-12 && f <= 1.1 + 1e-12);
        assert_true(weber_base_radius(&g, &t) == weber_base_radius(&g, &t)); /* the trunk's own draw */
        lo = fmin(lo, f), hi = fmax(hi, f), sum += f;
    }
    assert_true(lo < 0.53 && hi > 1.07);                /* the whole range is used */
    assert_true(fabs(sum / N - 0.8) < 3 * 0.3 / sqrt(3.0 * N)); /* mean 0Scale: 3 sigma of a uniform's */
}

/* lanes.h's four-lane sines and arctangents against libm's: angles a leaf turns by (within
 * a few turns), larger ones, every octant, the axes and signed zeros */
static void lanes_match_libm(void **state) {
    (void)state;
    Rng r = rng_stream(9, 0, 0, 0);
    double worst_sc = 0, worst_at = 0;
    for (int i = 0; i < 50000; i++) {
        v4f x, y, px, c, s;
        for (int k = 0; k < 4; k++) {
            x[k] = (float)((i % 8 == 0 ? 400 : 16) * (rng_unit(&r) - 0.5));
            double a = 2 * M_PI * rng_unit(&r), m = exp(20 * rng_unit(&r) - 10);
            y[k] = (float)(m * sin(a)), px[k] = (float)(m * cos(a));
            if (i % 16 == 0 && k == 0) y[k] = 0;
            if (i % 16 == 1 && k == 1) px[k] = 0;
        }
        v4_sincos(x, &c, &s);
        v4f at = v4_atan2(y, px);
        for (int k = 0; k < 4; k++) {
            worst_sc = fmax(worst_sc, fmax(fabs(c[k] - cos(x[k])), fabs(s[k] - sin(x[k]))));
            worst_at = fmax(worst_at, fabs(at[k] - atan2(y[k], px[k])));
        }
    }
    assert_true(worst_sc < 3e-7); /* (a float's step near 1 is 6e-8) */
    assert_true(worst_at < 5e-7);
    v4f zy = {0.0f, -0.0f, 0.0f, -0.0f}, zx = {0.0f, 0.0f, -1.0f, -1.0f}, at = v4_atan2(zy, zx);
    for (int k = 0; k < 4; k++) {
        double w = atan2(zy[k], zx[k]);
        assert_true(fabs(at[k] - w) < 5e-7 && !signbit(at[k]) == !signbit(w));
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shape_ratio_table),    cmocka_unit_test(defaults_are_arbaros),
        cmocka_unit_test(doc_lists_the_table),  cmocka_unit_test(frames_stay_orthonormal),
        cmocka_unit_test(radius_profile),       cmocka_unit_test(trunk_scale),
        cmocka_unit_test(lanes_match_libm),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
