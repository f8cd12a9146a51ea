/* The shared environment: shadow grid (against a brute-force pyramid), point grid, OBJ
 * reader and its errors, obstacles, the marker cloud, space-colonization rounds, sky rays. */
#include <math.h>
#include <unistd.h>

#include "unit.h"

#include "env/env.h"
#include "util/diag.h"
#include "env/objread.h"
#include "env/space.h"
#include "util/rng.h"

/* ---- shadow ---- */

static ShadowParams shadow_params(float sun_x) {
    ShadowParams p = {.voxel = 0.5f, .full = 1, .a = 0.3f, .b = 2, .depth = 4, .sun = {sun_x, 1, 0}};
    float len = sqrtf(sun_x * sun_x + 1);
    p.sun[0] /= len, p.sun[1] /= len;
    return p;
}

/* The shadow at voxel (I, J, K) by the definition: a*b^-q from every caster q levels above,
 * within q voxels across (shifted by the sun's shear), in the grid's fixed point. */
static double brute_shadow(const ShadowGrid *g, const float (*c)[3], int n, int I, int J, int K) {
    int64_t s = 0;
    for (int i = 0; i < n; i++) {
        int ci = (int)floorf(c[i][0] / g->p.voxel), cj = (int)floorf(c[i][1] / g->p.voxel),
            ck = (int)floorf(c[i][2] / g->p.voxel);
        int q = cj - J;
        if (q < 0 || q > g->p.depth) continue;
        int dx = I - (ci + g->shift_x[q]), dz = K - (ck + g->shift_z[q]);
        if (abs(dx) <= q && abs(dz) <= q) s += g->layer[q];
    }
    return (double)(int32_t)(uint32_t)s / SHADOW_ONE;
}

static void check_grid(const ShadowGrid *g, const float (*c)[3], int n) {
    for (int J = g->y0; J < g->y0 + g->ny; J++)
        for (int K = g->z0; K < g->z0 + g->nz; K++)
            for (int I = g->x0; I < g->x0 + g->nx; I++) {
                float p[3] = {((float)I + 0.5f) * g->p.voxel, ((float)J + 0.5f) * g->p.voxel, ((float)K + 0.5f) * g->p.voxel};
                double want = brute_shadow(g, c, n, I, J, K);
                if (fabs(shadow_at(g, p) - want) > 1e-6)
                    fail_msg("voxel (%d, %d, %d): %g, expected %g", I, J, K, shadow_at(g, p), want);
            }
}

/* Many casters in one batch (the difference grid), one at a time (row by row), with the
 * grid growing between batches: always the brute-force pyramid sums. */
static void shadow_matches_definition(void **state) {
    (void)state;
    for (int sun = 0; sun < 2; sun++) {
        ShadowParams sp = shadow_params(sun ? 0.6f : 0);
        ShadowGrid g;
        shadow_init(&g, &sp, 0);
        float c[300][3];
        Rng r = rng_stream(1, 2, 3, 4);
        for (int i = 0; i < 300; i++) {
            c[i][0] = (float)(rng_unit(&r) * 6 - 3);
            c[i][1] = (float)(rng_unit(&r) * 4 + 0.2);
            c[i][2] = (float)(rng_unit(&r) * 6 - 3) + (i >= 200 ? 9.0f : 0); /* later ones far away */
        }
        assert_true(shadow_cast(&g, c, 150, +1));
        for (int i = 150; i < 200; i++) assert_true(shadow_cast(&g, &c[i], 1, +1));
        assert_true(shadow_cast(&g, c + 200, 100, +1)); /* the grid grows */
        check_grid(&g, c, 300);
        /* removing casters is exact */
        assert_true(shadow_cast(&g, c + 100, 200, -1));
        check_grid(&g, c, 100);
        assert_true(shadow_cast(&g, c, 100, -1));
        for (size_t v = 0; v < shadow_voxels(&g); v++) assert_int_equal(g.s[v], 0);
        shadow_free(&g);
    }
}

static void shadow_light_formula(void **state) {
    (void)state;
    ShadowParams sp = shadow_params(0);
    ShadowGrid g;
    shadow_init(&g, &sp, 0);
    float c[1][3] = {{0.25f, 2.25f, 0.25f}};
    assert_true(shadow_cast(&g, c, 1, +1));
    /* its own voxel: s = a, so Q = C - a + a = C */
    assert_near(shadow_light(&g, c[0]), 1.0, 1e-3);
    float below[3] = {0.25f, 1.75f, 0.25f}, aside[3] = {0.75f, 1.75f, 0.25f}, far[3] = {2.25f, 1.75f, 0.25f};
    assert_near(shadow_at(&g, below), 0.15, 1e-3);      /* a / b */
    assert_near(shadow_at(&g, aside), 0.15, 1e-3);      /* the pyramid widens */
    assert_near(shadow_at(&g, far), 0, 1e-9);
    assert_near(shadow_light(&g, below), 1 - 0.15 + 0.3, 1e-3);
    float up[3] = {0.25f, 2.75f, 0.25f};
    assert_near(shadow_at(&g, up), 0, 1e-9); /* no shadow above */
    float grad[3];
    shadow_gradient(&g, below, grad);
    assert_true(grad[1] < 0); /* darker above: least shadow is downward here */
    shadow_gradient(&g, (float[3]){1.25f, 1.25f, 0.25f}, grad);
    assert_true(grad[0] > 0); /* away from the caster's column */
    shadow_free(&g);
}

/* ---- point grid ---- */

static void pointgrid_matches_brute_force(void **state) {
    (void)state;
    enum { N = 2000 };
    static float pts[N][3];
    Rng r = rng_stream(5, 0, 0, 0);
    for (int i = 0; i < N; i++)
        for (int k = 0; k < 3; k++) pts[i][k] = (float)(rng_unit(&r) * 10 - 5);
    PointGrid g = {0};
    assert_true(pgrid_build(&g, 0.7f, pts[0], 3, N));
    for (int t = 0; t < 500; t++) {
        float q[3] = {(float)(rng_unit(&r) * 12 - 6), (float)(rng_unit(&r) * 12 - 6), (float)(rng_unit(&r) * 12 - 6)};
        float rad = (float)(rng_unit(&r) * 1.2);
        bool want = false;
        for (int i = 0; i < N && !want; i++) {
            float dx = pts[i][0] - q[0], dy = pts[i][1] - q[1], dz = pts[i][2] - q[2];
            want = dx * dx + dy * dy + dz * dz < rad * rad;
        }
        assert_int_equal(pgrid_any_within(&g, q, rad, UINT32_MAX), want);
    }
    /* every point is in the grid once */
    uint8_t seen[N] = {0};
    for (size_t k = 0; k < g.n; k++) seen[g.ids[k]]++;
    for (int i = 0; i < N; i++) assert_int_equal(seen[i], 1);
    pgrid_free(&g);
}

/* ---- OBJ ---- */

static char *parse_error(const char *text, int *status) {
    char *msg = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&msg, &len);
    ObjMesh m;
    *status = obj_parse("wall.obj", text, strlen(text), &m, diag_sink(&(SylSink){0}, mem, NULL));
    fclose(mem);
    obj_free(&m);
    return msg;
}

static void obj_reads_faces(void **state) {
    (void)state;
    const char *text = "# a quad and a triangle\nmtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                       "vn 0 0 1\nvt 0 0\nf 1/1/1 2/2/1 3//1 4\nf -1 -2 -3\n";
    ObjMesh m;
    assert_int_equal(obj_parse("t.obj", text, strlen(text), &m, NULL), SYL_OK);
    assert_int_equal(m.nv, 4);
    assert_int_equal(m.nt, 3); /* the quad as a fan of two */
    assert_int_equal(m.tri[3 * 2 + 0], 3);
    assert_int_equal(m.tri[3 * 2 + 1], 2);
    assert_int_equal(m.tri[3 * 2 + 2], 1);
    obj_free(&m);
}

static void obj_errors_name_file_and_line(void **state) {
    (void)state;
    int st;
    char *msg = parse_error("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 7\n", &st);
    assert_int_equal(st, SYL_EMODEL);
    assert_string_equal(msg, "wall.obj:4:7: error: face vertex 7 is out of range (3 vertices so far)\n");
    free(msg);
    msg = parse_error("v 0 0\n", &st);
    assert_int_equal(st, SYL_EMODEL);
    assert_string_equal(msg, "wall.obj:1:6: error: a vertex needs three coordinates ('v x y z')\n");
    free(msg);
    msg = parse_error("v 0 0 zero\n", &st);
    assert_string_equal(msg, "wall.obj:1:7: error: coordinate 'zero' is not a number\n");
    free(msg);
    msg = parse_error("v 0 0 0\nv 1 0 0\nf 1 2\n", &st);
    assert_string_equal(msg, "wall.obj:3:1: error: a face needs at least three vertices, not 2\n");
    free(msg);
    msg = parse_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 x 3\n", &st);
    assert_string_equal(msg, "wall.obj:4:5: error: face vertex 'x' is not an index\n");
    free(msg);
    /* Embree traces in float: a coordinate beyond util/coord.h's bound is refused where it is */
    msg = parse_error("v 0 0 0\nv 1 0 0\nv 0 -1e18 0\nf 1 2 3\n", &st);
    assert_int_equal(st, SYL_EMODEL);
    assert_string_equal(msg, "wall.obj:3:5: error: coordinate -1e18 is out of range (at most 1e+12 from the origin)\n");
    free(msg);
    msg = parse_error("v 0 0 1e400\n", &st);
    assert_string_equal(msg, "wall.obj:1:7: error: coordinate 1e400 is out of range (at most 1e+12 from the origin)\n");
    free(msg);
    msg = parse_error("v 0 nan 0\n", &st);
    assert_string_equal(msg, "wall.obj:1:5: error: coordinate 'nan' is not a number\n");
    free(msg);
    /* a byte order mark is skipped, and columns count from after it */
    msg = parse_error("\xef\xbb\xbfv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", &st);
    assert_int_equal(st, SYL_OK);
    assert_string_equal(msg, "");
    free(msg);
    msg = parse_error("\xef\xbb\xbfv 0 0 q\n", &st);
    assert_string_equal(msg, "wall.obj:1:7: error: coordinate 'q' is not a number\n");
    free(msg);
    msg = parse_error("# nothing\n", &st);
    assert_string_equal(msg, "wall.obj: error: no faces: an obstacle needs triangles ('f a b c')\n");
    free(msg);
    ObjMesh m;
    assert_int_equal(obj_read("/nonexistent/wall.obj", &m, NULL), SYL_EIO);
}

/* ---- obstacles ---- */

/* A wall in the plane z = 0 from x -2..2, y 0..3, with a hole x -0.5..0.5, y 1..2. */
static void add_wall(Obstacles *o) {
    const float quads[][4][2] = {
        {{-2, 0}, {-0.5f, 0}, {-0.5f, 3}, {-2, 3}},
        {{0.5f, 0}, {2, 0}, {2, 3}, {0.5f, 3}},
        {{-0.5f, 0}, {0.5f, 0}, {0.5f, 1}, {-0.5f, 1}},
        {{-0.5f, 2}, {0.5f, 2}, {0.5f, 3}, {-0.5f, 3}},
    };
    for (int q = 0; q < 4; q++) {
        float v[12];
        for (int k = 0; k < 4; k++) v[3 * k] = quads[q][k][0], v[3 * k + 1] = quads[q][k][1], v[3 * k + 2] = 0;
        const uint32_t tri[6] = {0, 1, 2, 0, 2, 3};
        assert_true(obstacles_add(o, v, 4, tri, 2));
    }
}

static void obstacles_block_segments(void **state) {
    (void)state;
    Env e;
    assert_int_equal(env_init(&e, 1, NULL), SYL_OK);
    add_wall(&e.obstacles);
    assert_int_equal(obstacles_commit(&e.obstacles, e.dev, NULL), SYL_OK);
    const Obstacles *o = &e.obstacles;
    assert_true(obstacles_blocked(o, (float[3]){1, 0.5f, -1}, (float[3]){1, 0.5f, 1}, 0));
    assert_false(obstacles_blocked(o, (float[3]){0, 1.5f, -1}, (float[3]){0, 1.5f, 1}, 0)); /* the hole */
    assert_false(obstacles_blocked(o, (float[3]){1, 0.5f, -1}, (float[3]){1, 0.5f, -0.2f}, 0)); /* short */
    assert_true(obstacles_blocked(o, (float[3]){1, 0.5f, -1}, (float[3]){1, 0.5f, -0.2f}, 0.3f)); /* margin */
    assert_false(obstacles_blocked(o, (float[3]){3, 0.5f, -1}, (float[3]){3, 0.5f, 1}, 0)); /* beside */
    float h;
    assert_true(obstacles_height(o, 1, 0, 10, &h) == false || h <= 3); /* a vertical wall: a grazing ray */
    env_free(&e);
}

/* Embree aborts on rays from beyond 1.844e18 (its documented limit); util/coord.h keeps to
 * 1e12. Rays that would start beyond it are answered without tracing (blocked, distance 0,
 * no sky: these asked Embree before and aborted the process), and obstacles beyond it are
 * refused when committed, with the message. */
static void far_points_are_not_traced(void **state) {
    (void)state;
    Env e;
    assert_int_equal(env_init(&e, 1, NULL), SYL_OK);
    add_wall(&e.obstacles);
    assert_int_equal(obstacles_commit(&e.obstacles, e.dev, NULL), SYL_OK);
    const Obstacles *o = &e.obstacles;
    const float far[3] = {0, 1e19f, 0}, down[3] = {0, -1, 0}, up[3] = {0, 1, 0};
    assert_true(obstacles_blocked(o, far, (float[3]){0, 1.5f, 1}, 0));
    assert_true(obstacles_blocked(o, (float[3]){0, 1.5f, -1}, (float[3]){0, 1.5f, 2e12f}, 0)); /* either end */
    assert_near(obstacles_distance(o, far, down, 1e9f), 0, 0);
    assert_near(obstacles_distance(o, (float[3]){1, 0.5f, -1}, (float[3]){0, 0, 1}, 1e9f), 1, 1e-5); /* near: traced */
    float h;
    assert_false(obstacles_height(o, 2e12f, 0, 10, &h));
    sky_reset(&e.sky);
    assert_true(sky_add(&e.sky, far, 0.5f)); /* left out, not an error */
    assert_int_equal(e.sky.n, 0);
    assert_int_equal(sky_commit(&e.sky, e.dev, &e.obstacles), 0);
    Rng r = rng_stream(1, 1, 1, 1);
    assert_near(sky_exposure(&e.sky, far, up, 8, &r, 0.01f), 0, 0);
    /* a wall moved out to 1e13 is refused, with the bound */
    const float v[9] = {1e13f, 0, 0, 1e13f, 1, 0, 1e13f, 0, 1};
    const uint32_t tri[3] = {0, 1, 2};
    assert_true(obstacles_add(&e.obstacles, v, 3, tri, 1));
    char *msg = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&msg, &len);
    assert_int_equal(obstacles_commit(&e.obstacles, e.dev, diag_sink(&(SylSink){0}, mem, NULL)), SYL_EMODEL);
    fclose(mem);
    assert_string_equal(msg, "sylva: error: an obstacle reaches 1e+13 units from the origin; Sylva traces at most 1e+12 units\n");
    free(msg);
    env_free(&e);
}

/* ---- markers ---- */

static void marker_cloud_is_order_independent(void **state) {
    (void)state;
    MarkerCloud a, b;
    markers_init(&a, 1, 20, 0.3f, 0, 9);
    markers_init(&b, 1, 20, 0.3f, 0, 9);
    float p[3] = {0.5f, 2, 0.5f}, q[3] = {3.2f, 2.5f, -1};
    assert_true(markers_ensure(&a, p, 1.5f, NULL));
    assert_true(markers_ensure(&a, q, 1.5f, NULL));
    assert_true(markers_ensure(&b, q, 1.5f, NULL));
    assert_true(markers_ensure(&b, p, 1.5f, NULL));
    assert_int_equal(a.n, b.n);
    assert_true(a.n > 50);
    /* the same cell holds the same markers */
    long ba = markers_block(&a, 0, 2, 0), bb = markers_block(&b, 0, 2, 0);
    assert_true(ba >= 0 && bb >= 0);
    assert_int_equal(a.blocks[ba].count, b.blocks[bb].count);
    assert_memory_equal(a.pos[a.blocks[ba].first], b.pos[b.blocks[bb].first], a.blocks[ba].count * sizeof *a.pos);
    size_t before = markers_alive(&a);
    markers_kill_near(&a, p);
    assert_true(markers_alive(&a) < before);
    for (size_t i = 0; i < a.n; i++)
        if (a.alive[i]) {
            float dx = a.pos[i][0] - p[0], dy = a.pos[i][1] - p[1], dz = a.pos[i][2] - p[2];
            assert_true(dx * dx + dy * dy + dz * dz >= 0.3f * 0.3f);
        }
    markers_free(&a);
    markers_free(&b);
}

/* ---- space colonization ---- */

static SpaceBud bud_at(float x, float y, float z, float dx, float dy, float dz, uint64_t key) {
    SpaceBud b = {.pos = {x, y, z}, .dir = {dx, dy, dz}, .reach = 1.5f, .cos_half = cosf(0.8f), .markers = 24, .key = key};
    return b;
}

static void space_round_per_bud(void **state) {
    (void)state;
    /* an occupied column around the origin; a bud at its top looking up, one looking into it */
    float occ[40][3];
    for (int i = 0; i < 40; i++) occ[i][0] = 0, occ[i][1] = 0.1f * (float)i, occ[i][2] = 0;
    PointGrid nodes = {0};
    assert_true(pgrid_build(&nodes, 0.5f, occ[0], 3, 40));
    SpaceBud buds[3] = {bud_at(0, 4.0f, 0, 0, 1, 0, 1), bud_at(0.35f, 2, 0, -1, 0, 0, 2), bud_at(3, 1, 3, 1, 0, 0, 3)};
    buds[1].reach = 0.6f; /* sees only the column */
    SpaceQuery q = {.variant = SPACE_PER_BUD, .occupancy = 0.4f, .ground = 0, .nodes = &nodes, .round = 7, .threads = 1};
    Obstacles none = {0};
    q.obstacles = &none;
    SpaceResult r1[3], r2[3];
    assert_int_equal(space_round(&q, buds, 3, r1), SYL_OK);
    assert_true(r1[0].count > 0);
    assert_true(r1[0].dir[1] > 0.8f); /* up, into free space */
    assert_int_equal(r1[1].count, 0); /* everything it sees is occupied */
    assert_true(r1[2].count > 0 && r1[2].dir[0] > 0.8f);
    q.threads = 2;
    assert_int_equal(space_round(&q, buds, 3, r2), SYL_OK);
    assert_memory_equal(r1, r2, sizeof r1);
    pgrid_free(&nodes);
}

static void space_round_global_and_obstacles(void **state) {
    (void)state;
    Env e;
    assert_int_equal(env_init(&e, 1, NULL), SYL_OK);
    add_wall(&e.obstacles);
    assert_int_equal(obstacles_commit(&e.obstacles, e.dev, NULL), SYL_OK);
    markers_init(&e.cloud, 1.5f, 30, 0.2f, 0, 3);
    /* a bud behind the solid part of the wall, facing it: it cannot see through */
    SpaceBud buds[2] = {bud_at(1.2f, 1.5f, -0.3f, 0, 0, 1, 1), bud_at(0, 1.5f, -0.3f, 0, 0, 1, 2)};
    buds[0].cos_half = buds[1].cos_half = cosf(0.3f);
    SpaceQuery q = {.variant = SPACE_GLOBAL, .occupancy = 0.2f, .obstacles = &e.obstacles, .cloud = &e.cloud,
                    .round = 1, .threads = 1};
    PointGrid nodes = {0};
    q.nodes = &nodes;
    SpaceResult r[2];
    assert_int_equal(space_round(&q, buds, 2, r), SYL_OK);
    /* the first sees only the wall's near side (z < 0) at best; the second looks through the hole */
    assert_true(r[1].count > 0);
    assert_true(r[1].dir[2] > 0.5f);
    if (r[0].count) assert_true(r[0].dir[2] < 0.9f);
    env_free(&e);
}

/* ---- sky ---- */

static void sky_exposure_under_a_roof(void **state) {
    (void)state;
    Env e;
    assert_int_equal(env_init(&e, 1, NULL), SYL_OK);
    const float v[12] = {-50, 5, -50, 50, 5, -50, 50, 5, 50, -50, 5, 50};
    const uint32_t tri[6] = {0, 2, 1, 0, 3, 2};
    assert_true(obstacles_add(&e.obstacles, v, 4, tri, 2));
    assert_int_equal(obstacles_commit(&e.obstacles, e.dev, NULL), SYL_OK);
    sky_reset(&e.sky);
    assert_true(sky_add(&e.sky, (float[3]){10, 2, 10}, 0.5f));
    assert_int_equal(sky_commit(&e.sky, e.dev, &e.obstacles), 0);
    Rng r = rng_stream(1, 1, 1, 1);
    float up[3] = {0, 1, 0};
    assert_near(sky_exposure(&e.sky, (float[3]){0, 1, 0}, up, 32, &r, 0.01f), 0, 1e-6);
    assert_near(sky_exposure(&e.sky, (float[3]){0, 6, 0}, up, 32, &r, 0.01f), 1, 1e-6);
    /* a foliage sphere right above shades part of the sky */
    float q = sky_exposure(&e.sky, (float[3]){10, 6 - 4.5f, 10}, up, 64, &r, 0.01f);
    assert_true(q == 0); /* under the roof anyway */
    env_free(&e);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shadow_matches_definition),
        cmocka_unit_test(shadow_light_formula),
        cmocka_unit_test(pointgrid_matches_brute_force),
        cmocka_unit_test(obj_reads_faces),
        cmocka_unit_test(obj_errors_name_file_and_line),
        cmocka_unit_test(obstacles_block_segments),
        cmocka_unit_test(far_points_are_not_traced),
        cmocka_unit_test(marker_cloud_is_order_independent),
        cmocka_unit_test(space_round_per_bud),
        cmocka_unit_test(space_round_global_and_obstacles),
        cmocka_unit_test(sky_exposure_under_a_roof),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
