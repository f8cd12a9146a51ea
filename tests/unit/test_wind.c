/* The sway model against hand-computed cases (docs/mesh.md#wind), and the mesher's vertex
 * nodes: not snapshots. */
#include "unit.h"

#include <math.h>

#include "mesh_fixtures.h"
#include "sylva/lod.h"
#include "sylva/wind.h"

/* A trunk of two 1 m segments (radius 0.1) with a branch of one 1 m segment (radius 0.01)
 * from its middle, and a twig on the branch. */
static SylSkeleton *small_tree(void) {
    SylSkeleton *s = syl_skeleton_new("t");
    int32_t r = fx_node(s, -1, 0, 0, 0, 0, 0.1f, 0);
    int32_t a = fx_node(s, r, 0, 0, 1, 0, 0.1f, 0);
    fx_node(s, a, 0, 0, 2, 0, 0.1f, 0);
    int32_t b = fx_node(s, a, 1, 1, 1, 0, 0.01f, 0);
    fx_node(s, b, 2, 1, 1.5f, 0, 0.005f, 0);
    return s;
}

static float *radii(const SylSkeleton *s) {
    float *r = malloc(s->nnodes * sizeof *r);
    for (size_t i = 0; i < s->nnodes; i++) r[i] = s->nodes[i].radius;
    return r;
}

static double angle(const float *q) { return 2 * acos(fmin(1.0, fabs((double)q[3]))); }

static void joints_and_amplitudes(void **state) {
    (void)state;
    SylSkeleton *s = small_tree();
    float *r = radii(s);
    SylWind w;
    SylWindOptions o = {.speed = 5, .seconds = 4};
    assert_int_equal(syl_wind_build(s, r, &o, &w), SYL_OK);
    assert_int_equal(w.nstems, 3);
    assert_int_equal(w.njoints, 2); /* trunk and branch; the twig (order 2) rides the branch */
    assert_int_equal(w.joints[0].parent, -1);
    assert_int_equal(w.joints[1].parent, 0);
    assert_int_equal(w.stems[2].joint, 1);
    assert_near(w.stems[1].base[1], 1, 1e-6);
    assert_near(w.stems[0].length, 2, 1e-6);
    /* trunk: a0 = 4 * 2 / 0.1 = 80 deg = 1.396 rad, a1 = 0.1396, a2 = 0.2094: capped to a total
     * of 0.12; bend = 1 * 5 / 1000 = 0.005: amplitude 0.005 + sqrt(2) 0.12 */
    assert_near(w.joints[0].amplitude, 0.005 + sqrt(2.0) * 0.12, 1e-5);
    /* branch: bend (0.1 / 0.01)^2 * 5 / 1000 = 0.5, capped at 0.1 */
    assert_near(w.joints[1].amplitude, 0.1 + sqrt(2.0) * 0.12, 1e-5);
    /* frequencies: 265 r / L^2 = 6.625 Hz for the trunk, capped at 4; the branch 2.65 Hz,
     * rounded to 11 cycles in 4 s */
    assert_near(w.joints[0].frequency, 4, 1e-6);
    assert_near(w.joints[1].frequency, 11 / 4.0, 1e-6);
    assert_int_equal(w.nkeys, 61);
    /* the branch's blend: from the trunk's radius 0.1 (< L/4 = 0.25) over 4 r = 0.04, along its
     * first segment, +x; the trunk (a root) has none */
    assert_near(w.joints[1].blend_start, 0.1, 1e-6);
    assert_near(w.joints[1].blend_length, 0.04, 1e-6);
    assert_near(w.stems[1].dir[0], 1, 1e-6);
    assert_near(w.joints[0].blend_length, 0, 0);
    for (int j = 0; j < w.njoints; j++) {
        const float *q = w.rot + 4 * (size_t)j * (size_t)w.nkeys;
        assert_memory_equal(q, q + 4 * (w.nkeys - 1), 4 * sizeof *q); /* the loop closes */
        for (int k = 0; k < w.nkeys; k++) assert_true(angle(q + 4 * k) <= w.joints[j].amplitude + 1e-5);
    }
    syl_wind_free(&w);
    free(r);
    syl_skeleton_free(s);
}

/* With no undirected sway to speak of, a joint leans downwind: +x turns y toward +x. */
static void leans_downwind(void **state) {
    (void)state;
    SylSkeleton *s = small_tree();
    float *r = radii(s);
    SylWind w;
    SylWindOptions o = {.speed = 5, .dir = {0, -3}, .levels = 1};
    assert_int_equal(syl_wind_build(s, r, &o, &w), SYL_OK);
    assert_int_equal(w.njoints, 1);
    double z = 0; /* the tip (0, 2, 0) rotated by each key, on average: toward -z */
    for (int k = 0; k < w.nkeys - 1; k++) {
        const float *q = w.rot + 4 * k;
        /* the unit y axis turns to (2 (xy - wz), 1 - 2 (x^2 + z^2), 2 (yz + wx)): its z */
        z += 2 * ((double)q[1] * q[2] + (double)q[3] * q[0]);
    }
    assert_true(z / (w.nkeys - 1) < -0.004);
    syl_wind_free(&w);
    free(r);
    SylWindOptions bad = {.speed = 0};
    assert_int_equal(syl_wind_build(s, NULL, &bad, &w), SYL_EUSAGE);
    syl_skeleton_free(s);
}

/* Distance from p to the segments of axis a (each from its node's parent). */
static double to_axis(const SylSkeleton *s, int32_t a, const float *p) {
    double best = INFINITY;
    for (size_t i = 0; i < s->nnodes; i++) {
        if (s->nodes[i].axis != a || s->nodes[i].parent < 0) continue;
        const float *x = s->nodes[s->nodes[i].parent].pos, *y = s->nodes[i].pos;
        double d[3], e[3], t = 0, l = 0, dist = 0;
        for (int c = 0; c < 3; c++) d[c] = y[c] - x[c], e[c] = p[c] - x[c], t += d[c] * e[c], l += d[c] * d[c];
        t = fmax(-0.2, fmin(1.2, t / l)); /* caps and the sunk base included */
        for (int c = 0; c < 3; c++) dist += (e[c] - t * d[c]) * (e[c] - t * d[c]);
        best = fmin(best, sqrt(dist));
    }
    return best;
}

/* The mesher's vertex nodes: every vertex gets a node of the skeleton (a tube's: one of its
 * axis), kept through the optimizer's reordering: each vertex stays near its node's axis. */
static void vertex_nodes(void **state) {
    (void)state;
    SylSkeleton *s = small_tree();
    SylMesh *m;
    SylMeshOptions mo = {.vertex_nodes = 1, .threads = 1};
    assert_int_equal(syl_mesh_build(s, &mo, &m), SYL_OK);
    assert_non_null(m->node);
    assert_int_equal(syl_mesh_optimize(m), SYL_OK);
    for (size_t v = 0; v < m->nverts; v++) {
        int32_t n = m->node[v];
        assert_true(n > 0 && (size_t)n < s->nnodes);
        assert_true(to_axis(s, s->nodes[n].axis, m->pos + 3 * v) < 0.25);
    }
    syl_mesh_free(m);
    SylMeshOptions plain = {.threads = 1};
    assert_int_equal(syl_mesh_build(s, &plain, &m), SYL_OK);
    assert_null(m->node);
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

/* Every level of detail keeps vertex nodes of the whole skeleton (not of its truncated
 * copy): a thin branch early in node order is dropped from LOD1, which would shift the
 * nodes after it; each vertex still lies near its node's axis. */
static void lod_vertex_nodes(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("t");
    int32_t r = fx_node(s, -1, 0, 0, 0, 0, 0.1f, 0);
    int32_t a = fx_node(s, r, 0, 0, 1, 0, 0.1f, 0);
    fx_node(s, a, 1, -1, 1, 0, 0.0001f, 0); /* thinner than 2% of the trunk: not in LOD1 */
    fx_node(s, a, 0, 0, 2, 0, 0.1f, 0);
    int32_t b = fx_node(s, a, 2, 1, 1, 0, 0.01f, 0);
    fx_node(s, b, 3, 1, 1.5f, 0, 0.005f, 0);
    SylMesh *m;
    SylMeshOptions mo = {.vertex_nodes = 1, .threads = 1};
    assert_int_equal(syl_mesh_build(s, &mo, &m), SYL_OK);
    SylLodChain c;
    assert_int_equal(syl_lod_build(s, &mo, m, 1, &c), SYL_OK);
    assert_int_equal(c.n, 2);
    assert_true(c.level[1].mesh->nverts < m->nverts);
    for (int k = 0; k < c.n; k++) {
        const SylMesh *lm = c.level[k].mesh;
        assert_non_null(lm->node);
        for (size_t v = 0; v < lm->nverts; v++) {
            int32_t n = lm->node[v];
            assert_true(n > 0 && (size_t)n < s->nnodes);
            assert_true(to_axis(s, s->nodes[n].axis, lm->pos + 3 * v) < 0.25);
        }
    }
    syl_lod_free(&c);
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(joints_and_amplitudes),
        cmocka_unit_test(leans_downwind),
        cmocka_unit_test(vertex_nodes),
        cmocka_unit_test(lod_vertex_nodes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
