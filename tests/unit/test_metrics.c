/* Metrics on skeletons built by hand, with answers known in advance: binary trees (Strahler
 * order, tips, internodes, length, bifurcation ratios), a pole, a small crown, flat and
 * solid convex hulls, box-counting dimensions, light interception. */
#include <math.h>

#include "unit.h"
#include "mesh_fixtures.h"
#include "metrics/metrics_internal.h"
#include "sylva/metrics.h"

static SylMetrics metrics_of(const SylSkeleton *s, int threads) {
    SylMetrics m;
    SylMetricsOptions o = {.threads = threads, .grid = 8, .directions = 256};
    assert_int_equal(syl_metrics_compute(s, &o, &m), SYL_OK);
    return m;
}

/* A binary tree of depth k: the root forks at once, every segment (length 1) forks in two at
 * +-30 degrees in the plane z = 0, k segments from the root to every tip. The first child
 * continues its parent's axis, the second starts a lateral one. */
static void fork(SylSkeleton *s, int32_t parent, int32_t axis, int32_t *axes, double angle, int depth) {
    if (!depth) return;
    const float *p = s->nodes[parent].pos;
    for (int side = 0; side < 2; side++) {
        double a = angle + (side ? -1 : 1) * M_PI / 6;
        int32_t ax = side ? (*axes)++ : axis;
        int32_t n = fx_node(s, parent, ax, p[0] + (float)cos(a), p[1] + (float)sin(a), 0, 0.1f, 0);
        fork(s, n, ax, axes, a, depth - 1);
        p = s->nodes[parent].pos; /* the array may have moved */
    }
}

static SylSkeleton *binary_tree(int k) {
    SylSkeleton *s = syl_skeleton_new("binary");
    int32_t axes = 1;
    int32_t root = fx_node(s, -1, 0, 0, 0, 0, 0.1f, 0);
    fork(s, root, 0, &axes, M_PI / 2, k);
    return s;
}

static void binary_trees(void **state) {
    (void)state;
    for (int k = 1; k <= 8; k++) {
        SylSkeleton *s = binary_tree(k);
        SylMetrics m = metrics_of(s, 0);
        double tips = ldexp(1, k), segs = ldexp(1, k + 1) - 2;
        assert_near(m.strahler, k, 0);
        assert_near(m.tips, tips, 0);
        assert_near(m.internodes, segs, 0);
        assert_near(m.total_length, segs, 1e-4);
        assert_near(m.biomass, segs * 0.01, 1e-5);
        assert_near(m.max_order, k, 0); /* every fork starts a lateral */
        for (int i = 1; i <= k; i++) assert_near(m.streams[i], ldexp(1, k - i + 1), 0);
        if (k >= 2) {
            assert_near(m.bifurcation, 2, 1e-12);
            for (int i = 1; i < k; i++) {
                int metric = 0;
                while (!syl_metrics_info[metric].per_order) metric++;
                assert_near(syl_metrics_value(&m, metric, i), 2, 0);
            }
        } else {
            assert_true(isnan(m.bifurcation));
        }
        assert_near(m.branching_angle, 60, 1e-3);
        assert_near(m.crown_volume, 0, 0); /* drawn in a plane */
        if (k <= 3) assert_near(m.crown_base, 0, 0); /* the root forks (deeper trees bend below it) */
        syl_skeleton_free(s);
    }
}

/* A vertical pole of five segments: nothing branches. */
static void pole(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("pole");
    int32_t n = fx_node(s, -1, 0, 0, 0.5f, 0, 0.2f, 0);
    for (int i = 1; i <= 5; i++) n = fx_node(s, n, 0, 0, 0.5f + (float)i, 0, 0.2f, 0);
    SylMetrics m = metrics_of(s, 1);
    assert_near(m.height, 5, 1e-6);
    assert_near(m.ground, 0.5, 0);
    assert_near(m.internodes, 5, 0);
    assert_near(m.tips, 1, 0);
    assert_near(m.max_order, 0, 0);
    assert_near(m.strahler, 1, 0);
    assert_near(m.streams[1], 1, 0);
    assert_true(isnan(m.bifurcation));
    assert_true(isnan(m.branching_angle));
    assert_near(m.total_length, 5, 1e-6);
    assert_near(m.biomass, 5 * 0.04, 1e-6);
    assert_near(m.crown_width, 0, 0);
    assert_near(m.crown_depth, 5, 1e-6); /* no branching: the crown is the whole pole */
    assert_near(m.crown_volume, 0, 0);
    assert_near(m.box_dimension, 1, 1e-12);
    /* Ground points inside the pole see out through it; only the footprint's corners are shaded. */
    assert_true(m.light_interception > 0 && m.light_interception < 0.3);
    syl_skeleton_free(s);
}

/* A trunk to y = 2, then a node with a leader to y = 4 and three laterals at 45 degrees. */
static void small_crown(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("crown");
    int32_t r = fx_node(s, -1, 0, 0, 0, 0, 0.1f, 0);
    r = fx_node(s, r, 0, 0, 1, 0, 0.1f, 0);
    int32_t b = fx_node(s, r, 0, 0, 2, 0, 0.1f, 0);
    fx_node(s, b, 1, 1, 3, 0, 0.05f, 0);
    fx_node(s, b, 2, -1, 3, 0, 0.05f, 0);
    fx_node(s, b, 3, 0, 3, 1, 0.05f, 0);
    fx_node(s, b, 0, 0, 4, 0, 0.1f, 0);
    SylMetrics m = metrics_of(s, 2);
    assert_near(m.height, 4, 0);
    assert_near(m.crown_base, 2, 0);
    assert_near(m.crown_width, 2, 1e-9);
    assert_near(m.crown_depth, 2, 0);
    assert_near(m.crown_volume, 2.0 / 3.0, 1e-5);
    assert_near(m.branching_angle, 45, 1e-4);
    assert_near(m.tips, 4, 0);
    assert_near(m.internodes, 6, 0);
    assert_near(m.max_order, 1, 0);
    assert_near(m.strahler, 2, 0);
    assert_near(m.streams[1], 4, 0);
    assert_near(m.streams[2], 1, 0);
    assert_near(m.bifurcation, 4, 1e-12);
    assert_near(m.total_length, 4 + 3 * sqrt(2), 1e-5);
    syl_skeleton_free(s);
}

/* A lateral at the end of its parent axis is measured against the parent's last segment. */
static void lateral_at_an_axis_end(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("end");
    int32_t r = fx_node(s, -1, 0, 0, 0, 0, 0.1f, 0);
    int32_t a = fx_node(s, r, 0, 0, 1, 0, 0.1f, 0);
    fx_node(s, a, 1, 1, 1, 0, 0.1f, 0);  /* 90 degrees */
    fx_node(s, a, 2, 0, 1, -1, 0.1f, 0); /* 90 degrees */
    fx_node(s, a, 3, 0, 2, 0, 0.1f, 0);  /* 0 degrees */
    SylMetrics m = metrics_of(s, 1);
    assert_near(m.branching_angle, 60, 1e-4);
    assert_near(m.strahler, 2, 0);
    syl_skeleton_free(s);
}

static void empty_skeleton(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("empty");
    SylMetrics m = metrics_of(s, 0);
    assert_near(m.height, 0, 0);
    assert_near(m.internodes, 0, 0);
    assert_near(m.tips, 0, 0);
    assert_near(m.strahler, 0, 0);
    assert_near(m.crown_volume, 0, 0);
    assert_near(m.light_interception, 0, 0);
    assert_true(isnan(m.box_dimension));
    assert_true(isnan(m.branching_angle));
    assert_true(isnan(m.bifurcation));
    syl_skeleton_free(s);
}

static void parents_must_come_first(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("bad");
    fx_node(s, -1, 0, 0, 0, 0, 0.1f, 0);
    fx_node(s, 0, 0, 0, 1, 0, 0.1f, 0);
    s->nodes[0].parent = 1;
    SylMetrics m;
    SylMetricsOptions o = {0};
    assert_int_equal(syl_metrics_compute(s, &o, &m), SYL_EMODEL);
    syl_skeleton_free(s);
}

/* ---- convex hulls ---- */

static double rnd(uint64_t *lcg) {
    *lcg = *lcg * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*lcg >> 11) / 9007199254740992.0;
}

static double hull(const float (*p)[3], size_t n) {
    double v = -1;
    assert_true(metrics_hull_volume(p, n, &v));
    return v;
}

static void hull_volumes(void **state) {
    (void)state;
    enum { N = 4000 };
    uint64_t seed = 12345;
    float(*p)[3] = malloc(N * sizeof *p);
    /* A unit cube: its corners, points inside and on its faces, duplicates. */
    size_t n = 0;
    for (int i = 0; i < 8; i++) p[n][0] = (float)(i & 1), p[n][1] = (float)(i >> 1 & 1), p[n][2] = (float)(i >> 2), n++;
    for (int i = 0; i < 500; i++, n++)
        for (int k = 0; k < 3; k++) p[n][k] = (float)rnd(&seed);
    for (int i = 0; i < 300; i++, n++) { /* on the faces */
        for (int k = 0; k < 3; k++) p[n][k] = (float)rnd(&seed);
        p[n][i % 3] = (float)(i / 3 % 2);
    }
    for (int i = 0; i < 8; i++, n++) memcpy(p[n], p[i], sizeof *p);
    double cube = hull((const float(*)[3])p, n);
    assert_near(cube, 1, 1e-5);
    /* The same set in another order: exactly the same polytope. */
    for (size_t i = n - 1; i > 0; i--) {
        size_t j = (size_t)(rnd(&seed) * (double)(i + 1));
        float t[3];
        memcpy(t, p[i], sizeof t);
        memcpy(p[i], p[j], sizeof t);
        memcpy(p[j], t, sizeof t);
    }
    assert_true(hull((const float(*)[3])p, n) == cube);

    /* A tetrahedron and an octahedron. */
    float tet[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    assert_near(hull((const float(*)[3])tet, 4), 1.0 / 6.0, 1e-6);
    float oct[7][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, 0, 0}};
    assert_near(hull((const float(*)[3])oct, 7), 4.0 / 3.0, 1e-5);

    /* Points on a sphere: the hull approaches the ball. */
    for (int i = 0; i < N; i++) {
        double z = 1 - (2.0 * i + 1) / N, r = sqrt(1 - z * z), phi = 2.39996322972865332 * i;
        p[i][0] = (float)(3 + 2 * r * cos(phi)), p[i][1] = (float)(2 * r * sin(phi)), p[i][2] = (float)(2 * z);
    }
    double ball = 4.0 / 3.0 * M_PI * 8;
    double v = hull((const float(*)[3])p, N);
    assert_true(v < ball && v > 0.995 * ball);

    /* Flat sets: a plane, a tilted plane, a line, a point, too few points. */
    for (int i = 0; i < 1000; i++) {
        double a = rnd(&seed) * 10, b = rnd(&seed) * 10;
        p[i][0] = (float)a, p[i][1] = (float)b, p[i][2] = 3;
    }
    assert_near(hull((const float(*)[3])p, 1000), 0, 0);
    for (int i = 0; i < 1000; i++) { /* the plane x + 2y + 3z = 1, in float */
        double a = rnd(&seed) * 10 - 5, b = rnd(&seed) * 10 - 5;
        p[i][0] = (float)a, p[i][1] = (float)b, p[i][2] = (float)((1 - a - 2 * b) / 3);
    }
    assert_near(hull((const float(*)[3])p, 1000), 0, 0);
    for (int i = 0; i < 100; i++) p[i][0] = p[i][1] = p[i][2] = (float)i;
    assert_near(hull((const float(*)[3])p, 100), 0, 0);
    for (int i = 0; i < 100; i++) p[i][0] = p[i][1] = p[i][2] = 7;
    assert_near(hull((const float(*)[3])p, 100), 0, 0);
    assert_near(hull((const float(*)[3])tet, 3), 0, 0);
    assert_near(hull((const float(*)[3])p, 0), 0, 0);

    /* Many points on a few planes (a tree's nodes are often like this). */
    for (int i = 0; i < N; i++) {
        p[i][0] = (float)(int)(rnd(&seed) * 5), p[i][1] = (float)(int)(rnd(&seed) * 5), p[i][2] = (float)(int)(rnd(&seed) * 5);
    }
    assert_near(hull((const float(*)[3])p, N), 64, 1e-4);
    free(p);
}

static void diameters(void **state) {
    (void)state;
    enum { N = 300 };
    uint64_t seed = 54321;
    double p[N][2];
    for (int round = 0; round < 20; round++) {
        size_t n = 2 + (size_t)(rnd(&seed) * (N - 2));
        for (size_t i = 0; i < n; i++) {
            p[i][0] = round % 3 == 0 ? (double)(int)(rnd(&seed) * 4) : rnd(&seed) * 10 - 5;
            p[i][1] = round % 5 == 0 ? 2 * p[i][0] : rnd(&seed) * 3;
        }
        double best = 0, d = -1;
        for (size_t i = 0; i < n; i++)
            for (size_t j = 0; j < n; j++) best = fmax(best, hypot(p[i][0] - p[j][0], p[i][1] - p[j][1]));
        assert_true(metrics_diameter_2d((const double(*)[2])p, n, &d));
        assert_near(d, best, 1e-12);
    }
    double one[1][2] = {{1, 2}}, d = -1;
    assert_true(metrics_diameter_2d((const double(*)[2])one, 1, &d));
    assert_near(d, 0, 0);
}

/* ---- box counting ---- */

static SylSkeleton *line(float dx, float dy, float dz, int segments) {
    SylSkeleton *s = syl_skeleton_new("line");
    int32_t n = fx_node(s, -1, 0, 0, 0, 0, 0.1f, 0);
    for (int i = 1; i <= segments; i++) n = fx_node(s, n, 0, dx * (float)i, dy * (float)i, dz * (float)i, 0.1f, 0);
    return s;
}

/* An H-tree: it fills its square more densely at every level. */
static void h_tree(SylSkeleton *s, int32_t at, int32_t *axes, float len, int horizontal, int depth) {
    if (!depth) return;
    const float *p = s->nodes[at].pos;
    float x = p[0], y = p[1];
    for (int side = -1; side <= 1; side += 2) {
        float nx = horizontal ? x + (float)side * len : x, ny = horizontal ? y : y + (float)side * len;
        int32_t n = fx_node(s, at, (*axes)++, nx, ny, 0, 0.01f, 0);
        h_tree(s, n, axes, len * 0.70710678f, !horizontal, depth - 1);
    }
}

static void box_dimensions(void **state) {
    (void)state;
    double d = 0;
    SylSkeleton *s = line(0, 1, 0, 3);
    assert_true(metrics_box_dimension(s, &d));
    assert_near(d, 1, 1e-12);
    syl_skeleton_free(s);
    s = line(0.3f, 1, 0.7f, 50);
    assert_true(metrics_box_dimension(s, &d));
    assert_near(d, 1, 0.1);
    syl_skeleton_free(s);

    s = syl_skeleton_new("h");
    int32_t axes = 1;
    int32_t root = fx_node(s, -1, 0, 0, 0, 0, 0.01f, 0);
    h_tree(s, root, &axes, 1, 1, 16);
    assert_true(metrics_box_dimension(s, &d));
    assert_true(d > 1.6 && d <= 2.05);
    syl_skeleton_free(s);

    s = syl_skeleton_new("none");
    assert_true(metrics_box_dimension(s, &d));
    assert_true(isnan(d));
    fx_node(s, -1, 0, 1, 1, 1, 0.1f, 0);
    fx_node(s, 0, 0, 1, 1, 1, 0.1f, 0); /* a segment of length 0 */
    assert_true(metrics_box_dimension(s, &d));
    assert_true(isnan(d));
    syl_skeleton_free(s);
}

/* ---- light ---- */

static void light(void **state) {
    (void)state;
    /* A short stem under a 10 x 10 horizontal square: almost no sky is seen from under it. */
    SylSkeleton *s = syl_skeleton_new("roof");
    int32_t r = fx_node(s, -1, 0, 0, 0, 0, 0.02f, 0);
    fx_node(s, r, 0, 0, 0.1f, 0, 0.02f, 0);
    float sq[4][3] = {{-5, 0.1f, -5}, {5, 0.1f, -5}, {5, 0.1f, 5}, {-5, 0.1f, 5}};
    assert_true(syl_skeleton_add_polygon(s, (const float(*)[3])sq, 4, 1, 1, 0) >= 0);
    SylMetrics m = metrics_of(s, 0);
    assert_true(m.light_interception > 0.97 && m.light_interception <= 1);
    /* The same, by the defaults, on 1 and on 3 threads. */
    SylMetricsOptions o1 = {.threads = 1}, o3 = {.threads = 3};
    SylMetrics a, b;
    assert_int_equal(syl_metrics_compute(s, &o1, &a), SYL_OK);
    assert_int_equal(syl_metrics_compute(s, &o3, &b), SYL_OK);
    assert_true(a.light_interception == b.light_interception);
    assert_true(a.light_interception > 0.97);
    syl_skeleton_free(s);

    /* A tree lets some of the light through, the same on any number of threads. */
    SylSkeleton *t = fx_tree(5, 2);
    m = metrics_of(t, 0);
    assert_true(m.light_interception > 0.01 && m.light_interception < 0.97);
    SylMetricsOptions oa = {.threads = 1}, ob = {.threads = 4};
    assert_int_equal(syl_metrics_compute(t, &oa, &a), SYL_OK);
    assert_int_equal(syl_metrics_compute(t, &ob, &b), SYL_OK);
    assert_memory_equal(&a, &b, sizeof a);
    syl_skeleton_free(t);

    /* A mesh handed in is used as it is: an empty one stops nothing. */
    s = binary_tree(3);
    SylMesh empty = {0};
    SylMetricsOptions oe = {.mesh = &empty};
    assert_int_equal(syl_metrics_compute(s, &oe, &m), SYL_OK);
    assert_near(m.light_interception, 0, 0);
    syl_skeleton_free(s);
}

static void metric_table(void **state) {
    (void)state;
    assert_true(syl_metrics_count >= 15);
    SylMetrics m = {.height = 1, .crown_width = 2, .biomass = 3};
    assert_near(syl_metrics_value(&m, 0, 0), 1, 0);
    for (int i = 0; i < syl_metrics_count; i++) {
        const SylMetricInfo *a = &syl_metrics_info[i];
        assert_non_null(a->key);
        assert_non_null(a->label);
        assert_non_null(a->unit);
        assert_non_null(a->description);
        for (int j = 0; j < i; j++)
            if (!a->per_order && !syl_metrics_info[j].per_order) assert_string_not_equal(a->key, syl_metrics_info[j].key);
        if (!strcmp(a->key, "crown_width")) assert_near(syl_metrics_value(&m, i, 0), 2, 0);
        if (!strcmp(a->key, "biomass")) assert_near(syl_metrics_value(&m, i, 0), 3, 0);
    }
    assert_true(isnan(syl_metrics_value(&m, -1, 0)));
    assert_true(isnan(syl_metrics_value(&m, syl_metrics_count, 0)));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(binary_trees),   cmocka_unit_test(pole),
        cmocka_unit_test(small_crown),    cmocka_unit_test(lateral_at_an_axis_end),
        cmocka_unit_test(empty_skeleton), cmocka_unit_test(parents_must_come_first),
        cmocka_unit_test(hull_volumes),   cmocka_unit_test(diameters),
        cmocka_unit_test(box_dimensions), cmocka_unit_test(light),
        cmocka_unit_test(metric_table),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
