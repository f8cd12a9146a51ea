/* env/parity.c, the inside test of a closed mesh without Embree, against answers decided
 * here analytically: a box (convex, its faces split along diagonals) and a torus (not convex,
 * with a hole the ray passes through), at random points kept clear of the surface; and
 * against Embree's crossings (obstacles_inside) at the same points. A mesh that is empty or a
 * point that is not finite is outside. */
#include <math.h>
#include <stdlib.h>

#include "unit.h"

#include "env/obstacles.h"
#include "env/parity.h"
#include "util/rng.h"

#define PI 3.14159265358979323846

typedef struct Mesh {
    float v[3 * 4096];
    uint32_t tri[3 * 8192];
    size_t nv, nt;
} Mesh;

static void box(Mesh *m, float x0, float y0, float z0, float x1, float y1, float z1) {
    const float c[8][3] = {{x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1},
                           {x0, y1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1}};
    static const uint32_t f[12][3] = {{0, 1, 2}, {0, 2, 3}, {4, 6, 5}, {4, 7, 6}, {0, 4, 5}, {0, 5, 1},
                                      {1, 5, 6}, {1, 6, 2}, {2, 6, 7}, {2, 7, 3}, {3, 7, 4}, {3, 4, 0}};
    m->nv = 8, m->nt = 12;
    for (int i = 0; i < 8; i++)
        for (int j = 0; j < 3; j++) m->v[3 * i + j] = c[i][j];
    for (int i = 0; i < 12; i++)
        for (int j = 0; j < 3; j++) m->tri[3 * i + j] = f[i][j];
}

/* A torus about the y axis: ring radius R, tube radius r, n x k quads as two triangles. */
static void torus(Mesh *m, double R, double r, int n, int k) {
    m->nv = 0, m->nt = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < k; j++) {
            double a = 2 * PI * i / n, b = 2 * PI * j / k;
            float *p = m->v + 3 * m->nv++;
            p[0] = (float)((R + r * cos(b)) * cos(a)), p[1] = (float)(r * sin(b)), p[2] = (float)((R + r * cos(b)) * sin(a));
        }
    for (int i = 0; i < n; i++)
        for (int j = 0; j < k; j++) {
            uint32_t a = (uint32_t)(i * k + j), b = (uint32_t)(((i + 1) % n) * k + j);
            uint32_t c = (uint32_t)(((i + 1) % n) * k + (j + 1) % k), d = (uint32_t)(i * k + (j + 1) % k);
            uint32_t *t = m->tri + 3 * m->nt;
            t[0] = a, t[1] = b, t[2] = c, t[3] = a, t[4] = c, t[5] = d;
            m->nt += 2;
        }
}

/* Random points in [lo, hi]^3; those whose analytic answer is clear (signed distance beyond
 * margin) checked against the grid and against Embree. */
static void check(const Mesh *m, float lo, float hi, double (*sdf)(const float p[3]), double margin) {
    ParityGrid pg;
    assert_true(parity_build(&pg, m->v, m->nv, m->tri, m->nt));
    Obstacles o = {0};
    assert_true(obstacles_add(&o, m->v, m->nv, m->tri, m->nt));
    RTCDevice dev = rtcNewDevice("threads=1");
    assert_int_equal(obstacles_commit(&o, dev, NULL), 0);
    Rng rng = rng_stream(7, 0, 0, 0);
    int checked = 0, inside = 0;
    for (int i = 0; i < 20000; i++) {
        float p[3];
        for (int j = 0; j < 3; j++) p[j] = lo + (hi - lo) * (float)rng_unit(&rng);
        double d = sdf(p);
        if (fabs(d) < margin) continue;
        bool want = d < 0;
        assert_int_equal(parity_inside(&pg, p), want);
        assert_int_equal(obstacles_inside(&o, p), want);
        checked++, inside += want;
    }
    assert_true(checked > 10000 && inside > 500 && checked - inside > 1000);
    obstacles_free(&o);
    rtcReleaseDevice(dev);
    parity_free(&pg);
}

static double box_sdf(const float p[3]) { /* the box [-1,2] x [0,3] x [-0.5,0.5]: outside > 0 */
    double lo[3] = {-1, 0, -0.5}, hi[3] = {2, 3, 0.5}, d = -INFINITY;
    for (int j = 0; j < 3; j++) d = fmax(d, fmax(lo[j] - p[j], p[j] - hi[j]));
    return d;
}

static double torus_sdf(const float p[3]) { /* R 2, r 0.6 */
    double q = sqrt((double)p[0] * p[0] + (double)p[2] * p[2]) - 2;
    return sqrt(q * q + (double)p[1] * p[1]) - 0.6;
}

static void box_inside(void **state) {
    (void)state;
    static Mesh m;
    box(&m, -1, 0, -0.5f, 2, 3, 0.5f);
    check(&m, -2, 4, box_sdf, 1e-4);
}

static void torus_inside(void **state) {
    (void)state;
    static Mesh m;
    torus(&m, 2, 0.6, 64, 32);
    /* the flat facets lie inside the round tube by at most its sagitta, 0.6 (1 - cos(pi/32)) */
    check(&m, -3, 3, torus_sdf, 0.6 * (1 - cos(PI / 32)) + (2.6) * (1 - cos(PI / 64)) + 1e-4);
}

static void empty_or_not_finite(void **state) {
    (void)state;
    ParityGrid pg;
    assert_true(parity_build(&pg, NULL, 0, NULL, 0));
    assert_false(parity_inside(&pg, (float[3]){0, 0, 0}));
    parity_free(&pg);
    static Mesh m;
    box(&m, -1, -1, -1, 1, 1, 1);
    assert_true(parity_build(&pg, m.v, m.nv, m.tri, m.nt));
    assert_true(parity_inside(&pg, (float[3]){0, 0, 0}));
    assert_false(parity_inside(&pg, (float[3]){NAN, 0, 0}));
    assert_false(parity_inside(&pg, (float[3]){0, INFINITY, 0}));
    parity_free(&pg);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(box_inside),
        cmocka_unit_test(torus_inside),
        cmocka_unit_test(empty_or_not_finite),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
