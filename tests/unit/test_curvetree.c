/* The curve-driven tree (the Blender plug-in's, docs/curvetree.md), by invariants the thesis
 * states, measured on the skeleton with this file's own geometry: every trunk node lies on the
 * trunk curve (within 1 % of its length: the curve evaluated here, Bézier by its Bernstein
 * form); no branch node outside the envelope, convex (a box) or not (a U: two towers over a
 * base), the inside decided here analytically; a branch never wider than its parent where it
 * grows; every branch's leaf count is the step rule's; the Gaussian variation of widths and
 * angles has sigma = 10 % of the nominal value over many branches (mean and sigma within
 * 2 points); the same seed gives the same tree. */
#include <math.h>
#include <sys/stat.h>
#include <unistd.h>

#include "unit.h"

#include "lang/schema.h"
#include "sylva/trees.h"

#define PI 3.14159265358979323846

static char dir[64];

static void write_file(const char *name, const char *text) { unit_write_file(dir, name, text); }

/* A box as an OBJ of 12 triangles. */
static void write_box(const char *name, double x0, double y0, double z0, double x1, double y1, double z1) {
    char text[1024];
    snprintf(text, sizeof text,
             "v %g %g %g\nv %g %g %g\nv %g %g %g\nv %g %g %g\nv %g %g %g\nv %g %g %g\nv %g %g %g\nv %g %g %g\n"
             "f 1 2 3\nf 1 3 4\nf 5 7 6\nf 5 8 7\nf 1 5 6\nf 1 6 2\nf 2 6 7\nf 2 7 3\nf 3 7 8\nf 3 8 4\n"
             "f 4 8 5\nf 4 5 1\n",
             x0, y0, z0, x1, y0, z0, x1, y0, z1, x0, y0, z1, x0, y1, z0, x1, y1, z0, x1, y1, z1, x0, y1, z1);
    write_file(name, text);
}

/* A U extruded along z (z in [-2, 2]): the base [-3, 3] x [3, 5] and two towers [-3, -1] and
 * [1, 3] up to y = 9; the notch between them, [-1, 1] x (5, 9], is outside. */
static void write_u(const char *name) {
    static const double rect[][4] = {{-3, 3, 3, 5}, {-3, 5, -1, 9}, {1, 5, 3, 9}}; /* front and back faces */
    /* the walls: x = const (y0, y1) and y = const (x0, x1) */
    static const double xwall[][3] = {{-3, 3, 9}, {3, 3, 9}, {-1, 5, 9}, {1, 5, 9}};
    static const double ywall[][3] = {{3, -3, 3}, {5, -1, 1}, {9, -3, -1}, {9, 1, 3}};
    char text[8192];
    size_t n = 0;
    int v = 0;
#define QUAD(ax, ay, az, bx, by, bz, cx, cy, cz, dx, dy, dz)                                                  \
    n += (size_t)snprintf(text + n, sizeof text - n,                                                       \
                          "v %g %g %g\nv %g %g %g\nv %g %g %g\nv %g %g %g\nf %d %d %d\nf %d %d %d\n", ax, ay, az, \
                          bx, by, bz, cx, cy, cz, dx, dy, dz, v + 1, v + 2, v + 3, v + 1, v + 3, v + 4),           \
        v += 4
    for (int i = 0; i < 3; i++)
        for (int s = -1; s <= 1; s += 2) {
            const double *r = rect[i];
            QUAD(r[0], r[1], 2.0 * s, r[2], r[1], 2.0 * s, r[2], r[3], 2.0 * s, r[0], r[3], 2.0 * s);
        }
    for (int i = 0; i < 4; i++) {
        const double *w = xwall[i];
        QUAD(w[0], w[1], -2.0, w[0], w[2], -2.0, w[0], w[2], 2.0, w[0], w[1], 2.0);
    }
    for (int i = 0; i < 4; i++) {
        const double *w = ywall[i];
        QUAD(w[1], w[0], -2.0, w[2], w[0], -2.0, w[2], w[0], 2.0, w[1], w[0], 2.0);
    }
#undef QUAD
    assert_true(n < sizeof text);
    write_file(name, text);
}

static bool in_u(const float *p, double tol) {
    double x = p[0], y = p[1], z = p[2];
    if (fabs(z) > 2 + tol || fabs(x) > 3 + tol || y < 3 - tol || y > 9 + tol) return false;
    return y <= 5 + tol || fabs(x) >= 1 - tol;
}

static int setup(void **state) {
    (void)state;
    snprintf(dir, sizeof dir, "/tmp/sylva-curvetree-XXXXXX");
    assert_non_null(mkdtemp(dir));
    write_box("box.obj", -3, 2, -3, 3, 9, 3);
    write_u("u.obj");
    write_file("trunk.obj", "# a trunk as Blender exports a curve\no Curve\nv 0 4 0\nv 0.3 6 0.2\nv 0 0 0\n"
                            "v 0.2 2 -0.1\nl 3 4\nl 4 1\nl 1 2\n");
    return 0;
}

static int teardown(void **state) {
    (void)state;
    const char *const names[] = {"box.obj", "u.obj", "trunk.obj", "t.syl"};
    unit_remove_files(dir, names, sizeof names / sizeof *names);
    return 0;
}

/* The tree of a curvetree block's lines, compiled from a file in the temporary folder. */
static SylSkeleton *tree(const char *lines, uint64_t seed) {
    char text[2048], path[128];
    snprintf(text, sizeof text, "curvetree T {\n%s\n}\n", lines);
    snprintf(path, sizeof path, "%s/t.syl", dir);
    int st;
    SylCompileOptions opt = {.diag = stderr, .validate = syl_validate};
    SylProgram *p = syl_compile(path, text, strlen(text), &opt, &st);
    assert_non_null(p);
    SylTreeOptions to = {.diag = stderr, .use_seed = seed != 0, .seed = seed};
    SylSkeleton *sk = NULL;
    assert_int_equal(syl_curvetree_build(p, &to, &sk), SYL_OK);
    syl_program_free(p);
    return sk;
}

static double dist3(const double a[3], const float b[3]) {
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* Distance from q to the polyline pts (n points), and the polyline's length. */
static double to_polyline(const double (*pts)[3], int n, const float q[3], double *length) {
    double best = INFINITY, len = 0;
    for (int i = 0; i + 1 < n; i++) {
        double d[3], w[3], dd = 0, t = 0;
        for (int j = 0; j < 3; j++) d[j] = pts[i + 1][j] - pts[i][j], w[j] = q[j] - pts[i][j];
        for (int j = 0; j < 3; j++) dd += d[j] * d[j], t += d[j] * w[j];
        len += sqrt(dd);
        t = dd > 0 ? fmax(0, fmin(1, t / dd)) : 0;
        double c[3] = {pts[i][0] + t * d[0], pts[i][1] + t * d[1], pts[i][2] + t * d[2]};
        best = fmin(best, dist3(c, q));
    }
    if (length) *length = len;
    return best;
}

static void trunk_within(const SylSkeleton *sk, const double (*pts)[3], int n) {
    double length;
    to_polyline(pts, n, sk->nodes[0].pos, &length);
    size_t trunk = 0;
    for (size_t i = 0; i < sk->nnodes; i++)
        if (sk->nodes[i].order == 0) {
            double d = to_polyline(pts, n, sk->nodes[i].pos, NULL);
            if (d > 0.01 * length) fail_msg("trunk node %zu is %g from the curve (length %g)", i, d, length);
            trunk++;
        }
    assert_true(trunk >= 10);
}

static void trunk_follows_the_curve(void **state) {
    (void)state;
    /* a chain of two cubic Béziers, evaluated here at 4000 points a piece */
    static const double cp[7][3] = {{0, 0, 0}, {1, 2, 0}, {-1, 4, 0.5}, {0, 6, 0}, {1, 7, -0.5}, {0.5, 8, 0}, {0, 9, 0}};
    enum { N = 4000 };
    static double pts[2 * N + 1][3];
    for (int k = 0; k < 2; k++)
        for (int i = 0; i <= N; i++) {
            double t = (double)i / N, u = 1 - t;
            for (int j = 0; j < 3; j++)
                pts[k * N + i][j] = u * u * u * cp[3 * k][j] + 3 * u * u * t * cp[3 * k + 1][j] +
                                    3 * u * t * t * cp[3 * k + 2][j] + t * t * t * cp[3 * k + 3][j];
        }
    SylSkeleton *sk = tree("trunk bezier (0,0,0) (1,2,0) (-1,4,0.5) (0,6,0) (1,7,-0.5) (0.5,8,0) (0,9,0)\n"
                           "envelope \"box.obj\"",
                           0);
    trunk_within(sk, (const double (*)[3])pts, 2 * N + 1);
    syl_skeleton_free(sk);
    static const double poly[4][3] = {{0, 0, 0}, {0.5, 3, 0}, {-0.5, 6, 1}, {0, 8.5, 0}};
    sk = tree("trunk polyline (0,0,0) (0.5,3,0) (-0.5,6,1) (0,8.5,0)\nenvelope \"box.obj\"", 0);
    trunk_within(sk, poly, 4);
    syl_skeleton_free(sk);
    /* from an OBJ's lines, given out of order: the chain starts at its lower end */
    static const double obj[4][3] = {{0, 0, 0}, {0.2, 2, -0.1}, {0, 4, 0}, {0.3, 6, 0.2}};
    sk = tree("trunk \"trunk.obj\"\nenvelope \"box.obj\"", 0);
    assert_true(fabsf(sk->nodes[0].pos[1]) < 1e-6f);
    trunk_within(sk, obj, 4);
    syl_skeleton_free(sk);
}

static void no_branch_node_outside(const SylSkeleton *sk, bool u) {
    size_t branch = 0, towers = 0;
    for (size_t i = 0; i < sk->nnodes; i++) {
        const SylNode *n = &sk->nodes[i];
        if (n->order == 0) continue;
        branch++;
        const float *p = n->pos;
        bool in = u ? in_u(p, 1e-4)
                    : p[0] >= -3 - 1e-4 && p[0] <= 3 + 1e-4 && p[1] >= 2 - 1e-4 && p[1] <= 9 + 1e-4 &&
                          p[2] >= -3 - 1e-4 && p[2] <= 3 + 1e-4;
        if (!in) fail_msg("branch node %zu (order %d) at (%g, %g, %g) is outside", i, n->order, p[0], p[1], p[2]);
        if (u && p[1] > 5.5 && fabsf(p[0]) > 1) towers++;
    }
    assert_true(branch > 200);
    if (u) assert_true(towers > 10); /* they do grow into the towers: the shape, not its hull */
}

static void branches_stay_inside_the_envelope(void **state) {
    (void)state;
    SylSkeleton *sk = tree("trunk polyline (0,0,0) (0,8.5,0)\nenvelope \"box.obj\"\nbranch1Density 3\n"
                           "branch2Density 2\nbranchAngle 0.2\nbranchCurvature 0.5",
                           0);
    no_branch_node_outside(sk, false);
    syl_skeleton_free(sk);
    /* not convex: the trunk ends in the U's base; branches must stop short of the notch */
    for (uint64_t seed = 1; seed <= 3; seed++) {
        sk = tree("trunk polyline (0,0,0) (0,4.9,0)\nenvelope \"u.obj\"\nbranch1Density 3\nbranch2Density 2.5\n"
                  "branchAngle 0\nbranchCurvature 0.3\nbranch2Len 1.5",
                  seed);
        no_branch_node_outside(sk, true);
        syl_skeleton_free(sk);
    }
}

/* Each branch's first node: its parent is the node of the parent branch it grows from. */
static bool first_of_branch(const SylSkeleton *sk, size_t i) {
    const SylNode *n = &sk->nodes[i];
    return n->parent >= 0 && sk->nodes[n->parent].axis != n->axis;
}

static void branches_are_never_wider_than_their_parent(void **state) {
    (void)state;
    SylSkeleton *sk = tree("trunk bezier (0,0,0) (0.5,3,0) (-0.5,6,0) (0,9,0)\nenvelope \"box.obj\"\n"
                           "branch1Density 4\nbranch2Density 2\nbranch1Width 2\nbranch2Width 2\ntrunkEndWidth 0.3",
                           0);
    size_t branches = 0;
    for (size_t i = 0; i < sk->nnodes; i++) {
        if (!first_of_branch(sk, i)) continue;
        branches++;
        float parent = sk->nodes[sk->nodes[i].parent].radius;
        /* the branch's widest point is its base: no node of its axis is wider than its parent there */
        for (size_t k = i; k < sk->nnodes && sk->nodes[k].axis == sk->nodes[i].axis; k++)
            if (sk->nodes[k].radius > parent)
                fail_msg("node %zu of a branch is %g wide, its parent %g where it grows", k, sk->nodes[k].radius,
                         parent);
    }
    assert_true(branches > 100);
    syl_skeleton_free(sk);
}

/* The step rule as the thesis states it (§4.4, Eq. 6): the first leaf one step from the base,
 * step = length / 10 / density, then x 19/20 after each leaf, never below length / 30. */
static int step_rule(double length, double density) {
    if (density <= 0) return 0;
    int n = 0;
    double step = length / 10 / density, at = step;
    while (at < length) {
        n++;
        step = fmax(step * 19 / 20, length / 30);
        at += step;
    }
    return n;
}

static void leaf_counts_follow_the_step_rule(void **state) {
    (void)state;
    static const double densities[] = {0, 0.3, 1, 1.5, 2};
    for (size_t d = 0; d < sizeof densities / sizeof *densities; d++) {
        char lines[512];
        snprintf(lines, sizeof lines,
                 "trunk polyline (0,0,0) (0,8,0)\nenvelope \"box.obj\"\nbranch1Density 2\nleavesDensity %g",
                 densities[d]);
        SylSkeleton *sk = tree(lines, 0);
        /* leaves per axis, and each branch's length along its nodes from where it grows */
        int32_t maxaxis = 0;
        for (size_t i = 0; i < sk->nnodes; i++) maxaxis = sk->nodes[i].axis > maxaxis ? sk->nodes[i].axis : maxaxis;
        int *count = calloc((size_t)maxaxis + 1, sizeof *count);
        double *len = calloc((size_t)maxaxis + 1, sizeof *len);
        for (size_t i = 0; i < sk->norgans; i++) count[sk->nodes[sk->organs[i].node].axis]++;
        for (size_t i = 0; i < sk->nnodes; i++) {
            const SylNode *n = &sk->nodes[i];
            if (n->parent < 0) continue;
            double a[3] = {sk->nodes[n->parent].pos[0], sk->nodes[n->parent].pos[1], sk->nodes[n->parent].pos[2]};
            len[n->axis] += dist3(a, n->pos);
        }
        assert_int_equal(count[0], 0); /* none on the trunk */
        for (int32_t a = 1; a <= maxaxis; a++) {
            int want = step_rule(len[a], densities[d]);
            if (count[a] != want)
                fail_msg("density %g: branch %d of length %g has %d leaves, the step rule %d", densities[d], a, len[a],
                         count[a], want);
        }
        if (densities[d] == 1) assert_int_equal(step_rule(1, 1), 13); /* 0.1 (1 + .95 + ... ) passes 1 after 13 */
        free(count);
        free(len);
        syl_skeleton_free(sk);
    }
}

typedef struct Stats {
    double sum, sum2;
    int n;
} Stats;
static void add(Stats *s, double x) { s->sum += x, s->sum2 += x * x, s->n++; }
static double mean(const Stats *s) { return s->sum / s->n; }
static double sigma(const Stats *s) { return sqrt(s->sum2 / s->n - mean(s) * mean(s)); }

static void gaussian_variation_is_ten_percent(void **state) {
    (void)state;
    Stats width = {0}, angle = {0};
    const double nominal_angle = (90 - 72 * 0.5) * PI / 180; /* branchAngle 0.5: 54 degrees from the parent */
    for (uint64_t seed = 1; seed <= 4; seed++) {
        SylSkeleton *sk = tree("trunk polyline (0,0,0) (0,8,0)\nenvelope \"box.obj\"\nbranch1Density 5\n"
                               "branch2Density 3\nbranch1Width 1\nbranch2Width 1\nbranchAngle 0.5\nleavesDensity 0",
                               seed);
        for (size_t i = 0; i < sk->nnodes; i++) {
            if (!first_of_branch(sk, i)) continue;
            const SylNode *n = &sk->nodes[i], *at = &sk->nodes[n->parent];
            /* Eq. (5): the base width is the parent's there x branchWidth / 2 */
            add(&width, n->radius / (at->radius * 0.5));
            double d[3] = {n->pos[0] - at->pos[0], n->pos[1] - at->pos[1], n->pos[2] - at->pos[2]};
            double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            double c = (d[0] * at->h[0] + d[1] * at->h[1] + d[2] * at->h[2]) / len;
            add(&angle, acos(fmax(-1, fmin(1, c))) / nominal_angle);
        }
        syl_skeleton_free(sk);
    }
    printf("  %d branches: width %.4f +- %.4f, angle %.4f +- %.4f (of nominal)\n", width.n, mean(&width),
           sigma(&width), mean(&angle), sigma(&angle));
    assert_true(width.n > 2000);
    assert_near(mean(&width), 1, 0.02);
    assert_near(sigma(&width), 0.1, 0.02);
    assert_near(mean(&angle), 1, 0.02);
    assert_near(sigma(&angle), 0.1, 0.02);
}

static void the_same_seed_gives_the_same_tree(void **state) {
    (void)state;
    const char *lines = "trunk bezier (0,0,0) (0.5,3,0) (-0.5,6,0) (0,9,0)\nenvelope \"u.obj\"";
    SylSkeleton *a = tree(lines, 5), *b = tree(lines, 5), *c = tree(lines, 6);
    assert_int_equal(a->nnodes, b->nnodes);
    assert_int_equal(a->norgans, b->norgans);
    assert_memory_equal(a->nodes, b->nodes, a->nnodes * sizeof *a->nodes);
    assert_memory_equal(a->organs, b->organs, a->norgans * sizeof *a->organs);
    assert_true(a->nnodes != c->nnodes || memcmp(a->nodes, c->nodes, a->nnodes * sizeof *a->nodes));
    syl_skeleton_free(a);
    syl_skeleton_free(b);
    syl_skeleton_free(c);
}

/* The quadrant spiral: on a straight vertical trunk, each first-level branch (in order up the
 * trunk) lies in the quadrant after the previous one's, about the trunk (azimuth measured
 * from +x toward -z, the generator's frame for a vertical parent). */
static void branches_spiral_by_quadrants(void **state) {
    (void)state;
    SylSkeleton *sk = tree("trunk polyline (0,0,0) (0,8,0)\nenvelope \"box.obj\"\nbranch1Density 3\nbranch2Density 0", 9);
    int prev = -1, n = 0;
    for (size_t i = 0; i < sk->nnodes; i++) { /* the trunk's nodes come first, in order up it */
        if (!first_of_branch(sk, i) || sk->nodes[i].order != 1) continue;
        const SylNode *b = &sk->nodes[i], *at = &sk->nodes[b->parent];
        double az = atan2(-(b->pos[2] - at->pos[2]), b->pos[0] - at->pos[0]) * 180 / PI;
        int q = (int)floor((az < 0 ? az + 360 : az) / 90) % 4;
        if (prev >= 0 && q != (prev + 1) % 4) fail_msg("branch %d is in quadrant %d after one in %d", n, q, prev);
        prev = q, n++;
    }
    assert_int_equal(n, 90); /* round(10 x 3^2) */
    syl_skeleton_free(sk);
}

/* docs/curvetree.md's parameter table names every row of the block's table, once. */
static void the_doc_lists_every_parameter(void **state) {
    (void)state;
    size_t len;
    char *doc = syl_read_file("docs/curvetree.md", &len);
    assert_non_null(doc);
    for (int i = 0; i < sch_curvetree.n; i++) {
        char cell[64];
        snprintf(cell, sizeof cell, "| `%s` |", sch_curvetree.rows[i].name);
        if (unit_occurrences(doc, cell) != 1) fail_msg("docs/curvetree.md's table lacks (or repeats) %s", cell);
    }
    free(doc);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(trunk_follows_the_curve),
        cmocka_unit_test(branches_stay_inside_the_envelope),
        cmocka_unit_test(branches_are_never_wider_than_their_parent),
        cmocka_unit_test(leaf_counts_follow_the_step_rule),
        cmocka_unit_test(gaussian_variation_is_ten_percent),
        cmocka_unit_test(the_same_seed_gives_the_same_tree),
        cmocka_unit_test(branches_spiral_by_quadrants),
        cmocka_unit_test(the_doc_lists_every_parameter),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
