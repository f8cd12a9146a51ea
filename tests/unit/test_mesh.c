/* The mesher: closed tubes, normals, UVs, sides, pipe radii, groups, organs, polygons,
 * determinism. Skeletons are built by hand (mesh_fixtures.h). */
#include <meshoptimizer.h>

#include "unit.h"
#include "mesh_fixtures.h"
#include "sylva/texture.h"

static SylMesh *build(const SylSkeleton *s, const SylMeshOptions *o) {
    SylMesh *m = NULL;
    assert_int_equal(syl_mesh_build(s, o, &m), SYL_OK);
    assert_non_null(m);
    return m;
}

static size_t ntris(const SylMesh *m) { return m->nidx / 3; }

static void assert_unit_normals(const SylMesh *m) {
    for (size_t v = 0; v < m->nverts; v++) {
        const float *n = m->nrm + 3 * v;
        assert_near(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-5);
    }
}

static void assert_indices_valid(const SylMesh *m) {
    assert_int_equal(m->nidx % 3, 0);
    for (size_t i = 0; i < m->nidx; i++) assert_true(m->idx[i] < m->nverts);
    size_t at = 0;
    for (int g = 0; g < m->ngroups; g++) {
        assert_int_equal(m->groups[g].first, at);
        assert_int_equal(m->groups[g].count % 3, 0);
        assert_true(m->groups[g].count > 0);
        if (g) assert_true(m->groups[g].material > m->groups[g - 1].material);
        at += m->groups[g].count;
    }
    assert_int_equal(at, m->nidx);
}

static void assert_closed(const SylMesh *m, size_t components) {
    FxClosed c = fx_closed(m, 0, m->nidx);
    if (c.bad_edges) fail_msg("%zu of %zu edges are not shared by exactly two triangles", c.bad_edges, c.edges);
    assert_int_equal(c.components, components);
    assert_true(c.volume > 0); /* faces point out */
}

/* One straight axis of two segments, radius 0.5, 8 sides. */
static void straight_tube(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("tube");
    int32_t r = fx_node(s, -1, 0, 0, 0, 0, 0.5f, 0);
    r = fx_node(s, r, 0, 0, 1, 0, 0.5f, 0);
    fx_node(s, r, 0, 0, 2, 0, 0.5f, 0);
    SylMesh *m = build(s, NULL);
    assert_int_equal(m->nverts, 3 * 9 + 2);
    assert_int_equal(ntris(m), 2 * 8 * 2 + 2 * 8);
    assert_indices_valid(m);
    assert_unit_normals(m);
    assert_closed(m, 1);
    FxClosed c = fx_closed(m, 0, m->nidx);
    assert_near(c.volume, 4 * 0.25 * sin(M_PI / 4) * 2, 1e-5); /* an octagonal prism */
    for (size_t v = 0; v < m->nverts; v++) {
        const float *p = m->pos + 3 * v, *n = m->nrm + 3 * v, *t = m->uv + 2 * v;
        assert_true(t[0] >= 0 && t[0] <= 1);
        if (fabsf(n[1]) < 1e-6f) { /* side: v is length over circumference */
            assert_near(t[1], p[1] / (2 * M_PI * 0.5), 1e-5);
            assert_near(hypot(p[0], p[2]), 0.5, 1e-6);
        }
    }
    assert_string_equal(m->name, "tube");
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

static void tree_is_closed_per_axis(void **state) {
    (void)state;
    SylSkeleton *s = fx_tree(5, 2);
    int32_t axes = 0;
    for (size_t i = 0; i < s->nnodes; i++)
        if (s->nodes[i].axis + 1 > axes) axes = s->nodes[i].axis + 1;
    assert_true(axes > 10);
    s->nodes[3].material = 2; /* a colour change inside an axis */
    for (int pipe = 0; pipe < 2; pipe++) {
        SylMeshOptions o = {.radius = pipe ? SYL_RADIUS_PIPE : SYL_RADIUS_MODEL, .threads = 1};
        SylMesh *m = build(s, &o);
        assert_indices_valid(m);
        assert_unit_normals(m);
        assert_closed(m, (size_t)axes);
        syl_mesh_free(m);
    }
    syl_skeleton_free(s);
}

/* On a twig thinner than 1/100 of the thickest tube, v grows as if its radius were that:
 * bounded (docs/mesh.md, Bark UVs), where length / circumference diverges at a point. */
static void uv_radius_floor(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("uv floor");
    const float ys[] = {0, 1, 2, 3, 4}, rs[] = {1, 1, 0.5f, 0.005f, 0.0001f};
    int32_t p = -1;
    for (int k = 0; k < 5; k++) p = fx_node(s, p, 0, 0, ys[k], 0, rs[k], 0);
    SylMeshOptions o = {.caps = -1};
    SylMesh *m = build(s, &o);
    double expect[5] = {0};
    for (int k = 1; k < 5; k++) {
        double r = 0.5 * ((k == 1 ? rs[1] : rs[k - 1]) + rs[k]);
        expect[k] = expect[k - 1] + (ys[k] - ys[k - 1]) / (2 * M_PI * fmax(r, 0.01));
    }
    for (size_t v = 0; v < m->nverts; v++) {
        int k = (int)lrintf(m->pos[3 * v + 1]);
        assert_true(k >= 0 && k < 5 && fabsf(m->pos[3 * v + 1] - ys[k]) < 1e-4f);
        assert_near(m->uv[2 * v + 1], expect[k], 1e-4 * expect[k] + 1e-5);
    }
    assert_true(expect[4] < 20); /* without the floor: over 60 */
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

/* v grows by segment length / circumference along a tapering, straight axis. */
static void uv_continuous_along_axis(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("uv");
    const float ys[] = {0, 1, 1.5f, 3, 3.2f}, rs[] = {0.4f, 0.4f, 0.3f, 0.2f, 0.1f};
    int32_t p = -1;
    for (int k = 0; k < 5; k++) p = fx_node(s, p, 0, 0, ys[k], 0, rs[k], 0);
    SylMeshOptions o = {.caps = -1};
    SylMesh *m = build(s, &o);
    assert_int_equal(ntris(m), 2 * 8 * 4);
    double expect[5] = {0};
    for (int k = 1; k < 5; k++) {
        float r0 = k == 1 ? rs[1] : rs[k - 1]; /* the first ring has the first segment's radius */
        expect[k] = expect[k - 1] + (ys[k] - ys[k - 1]) / (2 * M_PI * 0.5 * (r0 + rs[k]));
    }
    for (size_t v = 0; v < m->nverts; v++) {
        int k = -1;
        for (int q = 0; q < 5; q++)
            if (fabsf(m->pos[3 * v + 1] - ys[q]) < 1e-5f) k = q;
        assert_true(k >= 0);
        assert_near(m->uv[2 * v + 1], expect[k], 1e-5);
    }
    syl_mesh_free(m);
    /* a bent axis: along every edge v changes by at most one segment's worth */
    SylSkeleton *b = syl_skeleton_new("bent");
    p = -1;
    for (int k = 0; k < 12; k++) p = fx_node(b, p, 0, sinf(k * 0.7f), (float)k * 0.5f, cosf(k * 0.4f), 0.2f, 0);
    m = build(b, &o);
    float vmax = 0;
    for (size_t t = 0; t < m->nidx; t += 3)
        for (int e = 0; e < 3; e++) {
            float va = m->uv[2 * m->idx[t + e] + 1], vb = m->uv[2 * m->idx[t + (e + 1) % 3] + 1];
            assert_true(fabsf(va - vb) < 1.6f / (2 * M_PI * 0.2f));
            vmax = fmaxf(vmax, va);
        }
    assert_true(vmax > 5);
    syl_mesh_free(m);
    syl_skeleton_free(b);
    syl_skeleton_free(s);
}

static void thin_branches_get_fewer_sides(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("sides");
    int32_t r = fx_node(s, -1, 0, 0, 0, 0, 1, 0);
    int32_t a = fx_node(s, r, 0, 0, 2, 0, 1, 0);
    fx_node(s, a, 1, 2, 3, 0, 0.25f, 0);  /* 8 sqrt(1/4) = 4 sides */
    fx_node(s, a, 2, -2, 3, 0, 0.01f, 0); /* 0.8: the minimum, 3 */
    SylMesh *m = build(s, NULL);
    assert_int_equal(ntris(m), 4 * 8 + 4 * 4 + 4 * 3);
    assert_closed(m, 3);
    syl_mesh_free(m);
    SylMeshOptions o = {.sides = 16, .min_sides = 5};
    m = build(s, &o);
    assert_int_equal(ntris(m), 4 * 16 + 4 * 8 + 4 * 5);
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

static void pipe_model_at_forks(void **state) {
    (void)state;
    SylSkeleton *s = fx_tree(4, 2);
    size_t n = s->nnodes;
    float *r = malloc(n * sizeof *r);
    double *sum = calloc(n, sizeof *sum);
    int *kids = calloc(n, sizeof *kids);
    SylMeshOptions o = {.radius = SYL_RADIUS_PIPE, .pipe_exponent = 2.5f, .tip_radius = 0.01f};
    assert_int_equal(syl_mesh_radii(s, &o, r), SYL_OK);
    for (size_t i = 0; i < n; i++)
        if (s->nodes[i].parent >= 0) {
            sum[s->nodes[i].parent] += pow(r[i], 2.5);
            kids[s->nodes[i].parent]++;
        }
    int forks = 0;
    for (size_t i = 0; i < n; i++) {
        if (!kids[i]) assert_near(r[i], 0.01, 1e-7);
        else assert_near(pow(r[i], 2.5) / sum[i], 1.0, 1e-4);
        forks += kids[i] > 1;
    }
    assert_true(forks > 5);
    assert_true(r[0] > 0.02f); /* the trunk is thicker than a tip */
    /* default tip: the mean of the model's tip radii */
    SylMeshOptions d = {.radius = SYL_RADIUS_PIPE};
    assert_int_equal(syl_mesh_radii(s, &d, r), SYL_OK);
    double tips = 0;
    int ntips = 0;
    for (size_t i = 0; i < n; i++)
        if (!kids[i]) tips += s->nodes[i].radius, ntips++;
    for (size_t i = 0; i < n; i++)
        if (!kids[i]) assert_near(r[i], tips / ntips, 1e-6);
    /* the model's radii */
    SylMeshOptions mm = {0};
    assert_int_equal(syl_mesh_radii(s, &mm, r), SYL_OK);
    for (size_t i = 0; i < n; i++) assert_true(r[i] == s->nodes[i].radius);
    free(r);
    free(sum);
    free(kids);
    syl_skeleton_free(s);
}

static void groups_by_material(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("groups");
    int32_t p = fx_node(s, -1, 0, 0, 0, 0, 0.1f, 0);
    p = fx_node(s, p, 0, 0, 1, 0, 0.1f, 0);
    p = fx_node(s, p, 0, 0, 2, 0, 0.1f, 2);
    fx_node(s, p, 0, 0, 3, 0, 0.1f, 2);
    SylOrgan leaf = fx_organ(SYL_KIND_LEAF, 0, 3, 0, 0.5f, 1);
    syl_skeleton_add_organ(s, &leaf);
    const float tri[3][3] = {{1, 0, 0}, {2, 0, 0}, {1, 1, 0}};
    syl_skeleton_add_polygon(s, tri, 3, -1, 3, 0);
    SylMesh *m = build(s, NULL);
    assert_indices_valid(m);
    assert_int_equal(m->ngroups, 4);
    const uint32_t want[4] = {3 * (16 + 8), 3 * 16, 3 * (32 + 8), 3 * 2};
    for (int g = 0; g < 4; g++) {
        assert_int_equal(m->groups[g].material, g);
        assert_int_equal(m->groups[g].count, want[g]);
    }
    /* the tube is still one closed surface across the colour change */
    FxClosed c0 = fx_closed(m, m->groups[0].first, m->groups[0].count);
    assert_true(c0.bad_edges > 0);
    syl_skeleton_free(s);
    syl_mesh_free(m);
}

static bool same_mesh(const SylMesh *a, const SylMesh *b) {
    return a->nverts == b->nverts && a->nidx == b->nidx && a->ngroups == b->ngroups &&
           !memcmp(a->pos, b->pos, a->nverts * 3 * sizeof(float)) &&
           !memcmp(a->nrm, b->nrm, a->nverts * 3 * sizeof(float)) &&
           !memcmp(a->uv, b->uv, a->nverts * 2 * sizeof(float)) && !memcmp(a->idx, b->idx, a->nidx * 4) &&
           !memcmp(a->groups, b->groups, (size_t)a->ngroups * sizeof *a->groups);
}

static void deterministic_across_threads(void **state) {
    (void)state;
    SylSkeleton *s = fx_tree(8, 4);
    for (size_t i = 0; i < s->nnodes; i += 97) s->nodes[i].material = (uint8_t)(i % 5);
    for (int k = 0; k < 300; k++) {
        SylOrgan o = fx_organ((uint8_t)(SYL_KIND_LEAF + k % 4), (float)k * 0.01f, 1, 0, 0.2f, (uint8_t)(1 + k % 3));
        syl_skeleton_add_organ(s, &o);
    }
    SylMeshOptions o1 = {.threads = 1}, o3 = {.threads = 3}, o0 = {0};
    SylMesh *a = build(s, &o1), *b = build(s, &o3), *c = build(s, &o0), *d = build(s, &o1);
    assert_true(ntris(a) > 100000);
    assert_true(same_mesh(a, b));
    assert_true(same_mesh(a, c));
    assert_true(same_mesh(a, d));
    assert_indices_valid(b);
    assert_unit_normals(b);
    syl_mesh_free(a);
    syl_mesh_free(b);
    syl_mesh_free(c);
    syl_mesh_free(d);
    syl_skeleton_free(s);
}

/* Triangles t and u are the same face seen from the two sides. */
static bool back_to_back(const SylMesh *m, size_t t, size_t u) {
    for (int rot = 0; rot < 3; rot++) {
        bool ok = true;
        for (int k = 0; k < 3 && ok; k++) {
            const float *p = m->pos + 3 * m->idx[3 * t + k], *q = m->pos + 3 * m->idx[3 * u + (rot - k + 3) % 3];
            ok = !memcmp(p, q, 3 * sizeof(float));
        }
        if (ok) {
            const float *n = m->nrm + 3 * m->idx[3 * t], *nb = m->nrm + 3 * m->idx[3 * u];
            return n[0] == -nb[0] && n[1] == -nb[1] && n[2] == -nb[2];
        }
    }
    return false;
}

static void organs(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("organs");
    SylOrgan leaf = fx_organ(SYL_KIND_LEAF, 0, 0, 0, 2, 1);
    syl_skeleton_add_organ(s, &leaf);
    SylMesh *m = build(s, NULL);
    assert_int_equal(ntris(m), 16);
    assert_unit_normals(m);
    for (size_t t = 0; t < 8; t++) assert_true(back_to_back(m, t, t + 8));
    float lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
    for (size_t v = 0; v < m->nverts; v++) {
        for (int k = 0; k < 3; k++) lo[k] = fminf(lo[k], m->pos[3 * v + k]), hi[k] = fmaxf(hi[k], m->pos[3 * v + k]);
        assert_true(m->uv[2 * v] >= 0 && m->uv[2 * v] <= 1 && m->uv[2 * v + 1] >= 0 && m->uv[2 * v + 1] <= 1);
    }
    assert_near(hi[1] - lo[1], 2, 1e-6); /* along H: its size */
    assert_true(hi[0] - lo[0] > 0.3 && hi[0] - lo[0] < 2); /* across L */
    assert_near(hi[2] - lo[2], 0, 1e-6);                  /* flat, facing U */
    syl_mesh_free(m);
    syl_skeleton_free(s);

    s = syl_skeleton_new("closed organs");
    SylOrgan sphere = fx_organ(SYL_KIND_SPHERE, 0, 0, 0, 2, 4), needle = fx_organ(SYL_KIND_NEEDLE, 5, 0, 0, 1, 1);
    syl_skeleton_add_organ(s, &sphere);
    syl_skeleton_add_organ(s, &needle);
    m = build(s, NULL);
    assert_unit_normals(m);
    assert_indices_valid(m);
    FxClosed c = fx_closed(m, m->groups[1].first, m->groups[1].count); /* the sphere */
    assert_int_equal(c.bad_edges, 0);
    assert_int_equal(c.components, 1);
    assert_true(c.volume > 0.6 * 4.0 / 3 * M_PI && c.volume < 4.0 / 3 * M_PI);
    c = fx_closed(m, m->groups[0].first, m->groups[0].count); /* the needle */
    assert_int_equal(c.bad_edges, 0);
    assert_true(c.volume > 0);
    syl_mesh_free(m);
    syl_skeleton_free(s);

    s = syl_skeleton_new("flower");
    SylOrgan fl = fx_organ(SYL_KIND_FLOWER, 0, 0, 0, 1, 2), bud = fx_organ(SYL_KIND_BUD, 0, 0, 0, 1, 2),
             none = fx_organ(SYL_KIND_LEAF, 0, 0, 0, 0, 2);
    syl_skeleton_add_organ(s, &fl);
    syl_skeleton_add_organ(s, &bud);  /* nothing to draw */
    syl_skeleton_add_organ(s, &none); /* size 0 */
    m = build(s, NULL);
    assert_int_equal(ntris(m), 5 * 16);
    assert_unit_normals(m);
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

static double tri_area(const SylMesh *m, size_t t) {
    const float *a = m->pos + 3 * m->idx[3 * t], *b = m->pos + 3 * m->idx[3 * t + 1], *c = m->pos + 3 * m->idx[3 * t + 2];
    double u[3], v[3];
    for (int k = 0; k < 3; k++) u[k] = b[k] - a[k], v[k] = c[k] - a[k];
    double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
    return 0.5 * sqrt(x * x + y * y + z * z);
}

/* A disc (@c) of diameter 2: on each side the regular 8-gon of radius 1 (area 2√2), flat
 * in the organ's H-L plane, every triangle wound to face its vertices' normal. */
static void disc(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("disc");
    SylOrgan d = fx_organ(SYL_KIND_DISC, 1, 2, 3, 2, 0);
    syl_skeleton_add_organ(s, &d);
    SylMesh *m = build(s, NULL);
    assert_int_equal(m->nverts, 2 * 9);
    assert_int_equal(ntris(m), 2 * 8);
    assert_unit_normals(m);
    assert_indices_valid(m);
    double area = 0;
    for (size_t t = 0; t < ntris(m); t++) {
        const float *a = m->pos + 3 * m->idx[3 * t], *b = m->pos + 3 * m->idx[3 * t + 1], *c = m->pos + 3 * m->idx[3 * t + 2];
        const float *n = m->nrm + 3 * m->idx[3 * t];
        double u[3], v[3];
        for (int k = 0; k < 3; k++) u[k] = b[k] - a[k], v[k] = c[k] - a[k];
        double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
        assert_true(x * n[0] + y * n[1] + z * n[2] > 0);
        area += tri_area(m, t);
    }
    assert_near(area, 2 * 2 * sqrt(2.0), 1e-5);
    for (size_t t = 0; t < 8; t++) assert_true(back_to_back(m, t, t + 8));
    for (size_t v = 0; v < m->nverts; v++) {
        const float *p = m->pos + 3 * v;
        double r = sqrt((p[0] - 1) * (p[0] - 1) + (p[1] - 2) * (p[1] - 2));
        assert_near(p[2], 3, 1e-6); /* in the H-L plane through the organ */
        assert_true(fabs(r) < 1e-6 || fabs(r - 1) < 1e-6);
    }
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

static void polygons(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("polygons");
    /* an L of area 3 in the plane z = 1, with a repeated point and the start repeated at the end */
    const float ell[9][3] = {{0, 0, 1}, {2, 0, 1}, {2, 0, 1}, {2, 1, 1}, {1, 1, 1},
                             {1, 2, 1}, {0, 2, 1}, {0, 1, 1},  {0, 0, 1}};
    syl_skeleton_add_polygon(s, ell, 9, -1, 1, 0);
    const float line[3][3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}; /* no area: nothing */
    syl_skeleton_add_polygon(s, line, 3, -1, 1, 0);
    SylMesh *m = build(s, NULL);
    assert_int_equal(m->nverts, 2 * 7);
    assert_int_equal(ntris(m), 2 * 5); /* 7 corners, one of them straight (0,1) */
    double area = 0;
    for (size_t t = 0; t < ntris(m) / 2; t++) {
        area += tri_area(m, t);
        assert_true(back_to_back(m, t, t + ntris(m) / 2));
    }
    assert_near(area, 3, 1e-5);
    for (size_t v = 0; v < m->nverts; v++) {
        assert_true(m->uv[2 * v] >= -1e-6 && m->uv[2 * v] <= 1 + 1e-6);
        assert_true(m->uv[2 * v + 1] >= -1e-6 && m->uv[2 * v + 1] <= 1 + 1e-6);
        assert_near(fabs(m->nrm[3 * v + 2]), 1, 1e-6);
    }
    /* front faces wind counter-clockwise about their normal */
    for (size_t t = 0; t < ntris(m); t++) {
        const float *a = m->pos + 3 * m->idx[3 * t], *b = m->pos + 3 * m->idx[3 * t + 1], *c = m->pos + 3 * m->idx[3 * t + 2];
        double z = (double)(b[0] - a[0]) * (c[1] - a[1]) - (double)(b[1] - a[1]) * (c[0] - a[0]);
        assert_true(z * m->nrm[3 * m->idx[3 * t] + 2] >= 0);
    }
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

static void smooth_nodes(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("smooth");
    int32_t p = -1;
    for (int k = 0; k < 6; k++) p = fx_node(s, p, 0, (float)(k % 2), (float)k, 0, 0.1f, 0);
    SylMesh *plain = build(s, NULL);
    for (size_t i = 0; i < s->nnodes; i++) s->nodes[i].flags |= SYL_NODE_SMOOTH;
    SylMesh *m = build(s, NULL);
    assert_true(ntris(m) > ntris(plain));
    assert_closed(m, 1);
    assert_unit_normals(m);
    syl_mesh_free(m);
    syl_mesh_free(plain);
    syl_skeleton_free(s);
}

/* A lateral starts inside its parent, and not out of the parent's far side. */
static void lateral_base_is_sunk(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("sink");
    int32_t r = fx_node(s, -1, 0, 0, 0, 0, 0.3f, 0);
    int32_t a = fx_node(s, r, 0, 0, 1, 0, 0.3f, 0);
    fx_node(s, a, 0, 0, 2, 0, 0.3f, 0);
    fx_node(s, a, 1, 1, 1, 0, 0.2f, 0); /* at right angles */
    SylMesh *m = build(s, NULL);
    assert_closed(m, 2);
    bool sunk = false;
    for (size_t v = 0; v < m->nverts; v++) {
        const float *p = m->pos + 3 * v, *n = m->nrm + 3 * v;
        if (p[0] < 0.29f) assert_true(hypot(p[0], p[2]) <= 0.3 + 1e-5); /* inside the trunk */
        if (n[0] < -0.999f && p[0] < -0.1f) sunk = true;                 /* the lateral's base cap */
    }
    assert_true(sunk);
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

static void odd_input(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("odd");
    SylMesh *m = build(s, NULL); /* empty */
    assert_int_equal(m->nverts, 0);
    assert_int_equal(m->ngroups, 0);
    syl_mesh_free(m);
    int32_t r = fx_node(s, -1, 0, 0, 0, 0, 0.1f, 0);
    int32_t a = fx_node(s, r, 0, 0, 1, 0, 0.1f, 0);
    a = fx_node(s, a, 0, 0, 1, 0, 0.1f, 0); /* zero length */
    a = fx_node(s, a, 0, 0, 2, 0, 0.1f, 0);
    int32_t nan = fx_node(s, a, 1, 0, 3, 0, 0.1f, 0);
    s->nodes[nan].pos[1] = NAN;
    fx_node(s, a, 2, 1, 3, 0, 0, 0);        /* no width: nothing */
    fx_node(s, -1, 3, 5, 5, 5, 0.1f, 0);    /* a lone root */
    m = build(s, NULL);
    assert_closed(m, 1);
    assert_int_equal(ntris(m), 2 * 2 * 8 + 2 * 8); /* two segments and two caps */
    syl_mesh_free(m);
    SylMeshOptions bad = {.sides = 2};
    assert_int_equal(syl_mesh_build(s, &bad, &m), SYL_EUSAGE);
    assert_null(m);
    s->nodes[1].parent = 3; /* a parent after its child */
    char *diag = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&diag, &len);
    SylMeshOptions o = {.diag = f};
    assert_int_equal(syl_mesh_build(s, &o, &m), SYL_EMODEL);
    fclose(f);
    assert_contains(diag, "parent");
    free(diag);
    syl_skeleton_free(s);
}

static void open_tubes_without_caps(void **state) {
    (void)state;
    SylSkeleton *s = fx_tree(3, 1);
    SylMeshOptions o = {.caps = -1};
    SylMesh *m = build(s, &o);
    FxClosed c = fx_closed(m, 0, m->nidx);
    assert_true(c.bad_edges > 0);
    assert_unit_normals(m);
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

/* A lobed cross-section (SylNode.lobes, lobe_depth): every vertex of a ring lies at
 * r (1 + depth sin(lobes a)) from the axis, a its angle about the axis from the ring's first
 * vertex; a ring gets four sides a lobe; normals stay unit and point outward. */
static void lobed_rings(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("lobed");
    int32_t a = fx_node(s, -1, 0, 0, 0, 0, 0.5f, SYL_MATERIAL_BARK);
    int32_t b = fx_node(s, a, 0, 0, 2, 0, 0.5f, SYL_MATERIAL_BARK);
    for (int32_t i = a; i <= b; i++) s->nodes[i].lobes = 5, s->nodes[i].lobe_depth = 1500; /* depth 0.15 */
    SylMeshOptions o = {.threads = 1, .caps = -1};
    SylMesh *m = NULL;
    assert_int_equal(syl_mesh_build(s, &o, &m), SYL_OK);
    assert_int_equal(m->nverts, 2 * (20 + 1)); /* 4 x 5 sides and the seam, two rings */
    /* each vertex's ring by its height and its place j on the ring by u = j / 20, whatever
     * order the mesher stores them in */
    int at[2][21];
    memset(at, -1, sizeof at);
    for (int i = 0; i < 42; i++) {
        int ring = m->pos[3 * i + 1] > 1, j = (int)lrintf(m->uv[2 * i] * 20);
        assert_true(j >= 0 && j <= 20 && at[ring][j] < 0);
        at[ring][j] = i;
    }
    for (int ring = 0; ring < 2; ring++) {
        const float *v0 = m->pos + 3 * (size_t)at[ring][0], y = ring ? 2.0f : 0.0f;
        const float a0 = atan2f(v0[2], v0[0]);
        for (int j = 0; j < 21; j++) {
            const float *v = m->pos + 3 * (size_t)at[ring][j], *n = m->nrm + 3 * (size_t)at[ring][j];
            assert_true(fabsf(v[1] - y) < 1e-5f);
            /* the angle from the first vertex, either way round (the frame's handedness) */
            float ang = atan2f(v[2], v[0]) - a0, d = sqrtf(v[0] * v[0] + v[2] * v[2]);
            float want1 = 0.5f * (1 + 0.15f * sinf(5 * ang)), want2 = 0.5f * (1 + 0.15f * sinf(-5 * ang));
            if (j > 0 && j < 20) assert_true(fabsf(d - want1) < 1e-4f || fabsf(d - want2) < 1e-4f);
            assert_true(fabsf(d - (j == 0 || j == 20 ? 0.5f : d)) < 1e-4f);
            assert_true(fabsf(sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1) < 1e-4f);
            assert_true(n[0] * v[0] + n[2] * v[2] > 0);
        }
    }
    /* one direction of turning fits every vertex */
    int fits[2] = {0, 0};
    const float a0 = atan2f(m->pos[2], m->pos[0]);
    for (int j = 1; j < 20; j++) {
        const float *v = m->pos + 3 * j;
        float ang = atan2f(v[2], v[0]) - a0, d = sqrtf(v[0] * v[0] + v[2] * v[2]);
        fits[0] += fabsf(d - 0.5f * (1 + 0.15f * sinf(5 * ang))) < 1e-4f;
        fits[1] += fabsf(d - 0.5f * (1 + 0.15f * sinf(-5 * ang))) < 1e-4f;
    }
    assert_true(fits[0] == 19 || fits[1] == 19);
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

/* The trunk's jitter (SylMaterial.trunk_jitter, Weber–Penn's 0ScaleV): each vertex of an
 * order-0 ring moves along its radius to between 1 - k and 1 + k times it, not all by the
 * same factor; a branch (order 1) stays as it was; 1 and 3 threads give the same mesh. */
static void trunk_jitter(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("jitter");
    int32_t a = fx_node(s, -1, 0, 0, 0, 0, 0.5f, SYL_MATERIAL_BARK);
    int32_t b = fx_node(s, a, 0, 0, 2, 0, 0.5f, SYL_MATERIAL_BARK);
    int32_t c = fx_node(s, b, 1, 1, 2, 0, 0.2f, SYL_MATERIAL_BARK);
    s->nodes[c].order = 1;
    SylMeshOptions o1 = {.threads = 1, .caps = -1}, o3 = {.threads = 3, .caps = -1};
    SylMesh *round = build(s, &o1);
    s->materials[SYL_MATERIAL_BARK].trunk_jitter = 0.2f;
    SylMesh *m = build(s, &o1), *m3 = build(s, &o3);
    assert_true(same_mesh(m, m3));
    assert_int_equal(m->nverts, round->nverts);
    int trunk = 0, spread = 0;
    for (size_t v = 0; v < m->nverts; v++) {
        const float *p = m->pos + 3 * v, *q = round->pos + 3 * v;
        float d0 = hypotf(q[0], q[2]);
        if (fabsf(d0 - 0.5f) > 1e-4f) { /* the branch */
            assert_memory_equal(p, q, 3 * sizeof(float));
            continue;
        }
        float f = hypotf(p[0], p[2]) / d0;
        trunk++;
        assert_true(fabsf(p[1] - q[1]) < 1e-6f);
        assert_true(fabsf(p[0] * q[2] - p[2] * q[0]) < 1e-5f); /* along its radius */
        assert_true(f >= 0.8f - 1e-5f && f <= 1.2f + 1e-5f);
        spread += fabsf(f - 1) > 0.1f;
    }
    assert_int_equal(trunk, 2 * 9);
    assert_true(spread >= 3);
    /* a trunk of another material (a scene's plant beside a jittered tree) stays round */
    s->nodes[a].material = s->nodes[b].material = SYL_MATERIAL_PLAIN;
    SylMesh *kept = build(s, &o1);
    assert_int_equal(kept->nverts, round->nverts);
    assert_memory_equal(kept->pos, round->pos, 3 * round->nverts * sizeof(float));
    syl_mesh_free(kept);
    syl_mesh_free(round);
    syl_mesh_free(m);
    syl_mesh_free(m3);
    syl_skeleton_free(s);
}

/* Leaves are emitted at the best vertex-cache order there is (every vertex fetched once): the
 * optimizer keeps their triangles in order (vertices may be renumbered), and still reorders
 * a tube whose triangles were shuffled. */
static void optimize_keeps_best_orders(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("leaves");
    for (int k = 0; k < 50; k++) {
        SylOrgan o = fx_organ(SYL_KIND_LEAF, (float)k, 0, 0, 0.5f, SYL_MATERIAL_LEAF);
        syl_skeleton_add_organ(s, &o);
    }
    SylMeshOptions o = {.threads = 1};
    SylMesh *m = NULL;
    assert_int_equal(syl_mesh_build(s, &o, &m), SYL_OK);
    size_t nidx = m->nidx;
    float *corners = malloc(3 * nidx * sizeof *corners); /* triangle corners in order, by position */
    for (size_t i = 0; i < nidx; i++) memcpy(corners + 3 * i, m->pos + 3 * m->idx[i], 3 * sizeof *corners);
    assert_int_equal(syl_mesh_optimize(m), SYL_OK);
    assert_int_equal(m->nidx, nidx);
    for (size_t i = 0; i < nidx; i++) assert_memory_equal(corners + 3 * i, m->pos + 3 * m->idx[i], 3 * sizeof *corners);
    free(corners);
    syl_mesh_free(m);
    syl_skeleton_free(s);

    s = syl_skeleton_new("tube");
    int32_t prev = fx_node(s, -1, 0, 0, 0, 0, 0.1f, SYL_MATERIAL_BARK);
    for (int k = 1; k <= 40; k++) prev = fx_node(s, prev, 0, 0, (float)k * 0.1f, 0, 0.1f, SYL_MATERIAL_BARK);
    assert_int_equal(syl_mesh_build(s, &o, &m), SYL_OK);
    size_t nt = m->nidx / 3;
    for (size_t t = 0; t < nt; t++) { /* a fixed shuffle of whole triangles */
        size_t u = (t * 7919 + 13) % nt;
        for (int c = 0; c < 3; c++) {
            uint32_t x = m->idx[3 * t + c];
            m->idx[3 * t + c] = m->idx[3 * u + c], m->idx[3 * u + c] = x;
        }
    }
    float before = meshopt_analyzeVertexCache(m->idx, m->nidx, m->nverts, 16, 0, 0).acmr;
    assert_int_equal(syl_mesh_optimize(m), SYL_OK);
    float after = meshopt_analyzeVertexCache(m->idx, m->nidx, m->nverts, 16, 0, 0).acmr;
    assert_true(after < 0.8f * before);
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

static double area_of(const SylMesh *m, size_t first, size_t count) {
    double a = 0;
    for (size_t t = first / 3; t < (first + count) / 3; t++) a += tri_area(m, t);
    return a;
}

/* A tube tapering to radius 0 ends in a ring of coincident vertices: its last segment has
 * one triangle without area a side and its tip cap is nothing but such triangles. The
 * optimizer drops them (and the vertices only they used); the surface keeps its area. */
static void optimize_drops_degenerate(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("cone");
    int32_t r = fx_node(s, -1, 0, 0, 0, 0, 0.5f, SYL_MATERIAL_BARK);
    r = fx_node(s, r, 0, 0, 1, 0, 0.25f, SYL_MATERIAL_BARK);
    fx_node(s, r, 0, 0, 2, 0, 0.0f, SYL_MATERIAL_BARK);
    SylMeshOptions o = {.threads = 1, .sides = 8, .min_sides = 8};
    SylMesh *m = NULL;
    assert_int_equal(syl_mesh_build(s, &o, &m), SYL_OK);
    size_t nt = m->nidx / 3, nv = m->nverts;
    double area = area_of(m, 0, m->nidx);
    assert_int_equal(syl_mesh_optimize(m), SYL_OK);
    assert_int_equal(m->nidx / 3, nt - 8 - 8); /* the tip cap and one triangle a side of the last segment */
    assert_int_equal(m->nverts, nv - 2);       /* the tip cap's centre and the tip ring's seam copy */
    assert_near(area_of(m, 0, m->nidx), area, 1e-6 * area);
    for (size_t t = 0; t < m->nidx / 3; t++) assert_true(tri_area(m, t) > 0);
    assert_indices_valid(m);
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

/* Leaf clusters: 30 clumps of 12 leaves (or needles) far apart, 12 a card: no more cards
 * than 360 / 12, each a flat unit-normal square with UVs over the unit square, and the cards
 * show (area x the texture's kept share) what the copied leaves show on one side (half
 * their triangles' area: both faces of a blade, or a closed needle on average). */
static void leaf_clusters(void **state) {
    (void)state;
    for (int kind = 0; kind < 2; kind++) {
        SylSkeleton *s = syl_skeleton_new("clusters");
        for (int c = 0; c < 30; c++)
            for (int i = 0; i < 12; i++) {
                float a = 0.5f * (float)i;
                SylOrgan o = fx_organ(kind ? SYL_KIND_NEEDLE : SYL_KIND_LEAF, 10.0f * (float)(c % 6) + 0.1f * cosf(a),
                                      10.0f * (float)(c / 6), 0.1f * sinf(a), 0.3f, 1);
                o.h[0] = cosf(a), o.h[1] = 0, o.h[2] = sinf(a);
                o.l[0] = 0, o.l[1] = 1, o.l[2] = 0;
                syl_skeleton_add_organ(s, &o);
            }
        SylMesh *copied = build(s, NULL);
        double shown = 0.5 * area_of(copied, 0, copied->nidx);
        SylMeshOptions o = {.leaves = SYL_LEAVES_CLUSTERS, .cluster_leaves = 12};
        SylMesh *m = build(s, &o);
        assert_int_equal(m->leaves, SYL_LEAVES_CLUSTERS);
        assert_int_equal(m->leaf_shape, kind ? SYL_CLUSTER_NEEDLES : SYL_LEAF_OVATE);
        assert_indices_valid(m);
        assert_unit_normals(m);
        size_t cards = ntris(m) / 2;
        assert_true(cards >= 10 && cards <= 30);
        assert_int_equal(m->nverts, 4 * cards);
        for (size_t k = 0; k < cards; k++) {
            const float *p = m->pos + 12 * k, *n = m->nrm + 12 * k, *uv = m->uv + 8 * k;
            for (int v = 1; v < 4; v++) {
                double d = 0;
                for (int c = 0; c < 3; c++) d += (p[3 * v + c] - p[c]) * n[c];
                assert_near(d, 0, 1e-5); /* flat, the normal across it */
            }
            double e1 = 0, e2 = 0;
            for (int c = 0; c < 3; c++) e1 += (p[3 + c] - p[c]) * (p[3 + c] - p[c]), e2 += (p[9 + c] - p[c]) * (p[9 + c] - p[c]);
            assert_near(e1, e2, 1e-3 * (e1 + e2)); /* square (to float precision 50 units out) */
            for (int v = 0; v < 8; v++) assert_true(uv[v] == 0 || uv[v] == 1);
        }
        double fill = syl_leaf_cluster_fill(m->leaf_shape);
        assert_near(fill * area_of(m, 0, m->nidx), shown, 1e-3 * shown);
        syl_mesh_free(copied);
        syl_mesh_free(m);
        syl_skeleton_free(s);
    }
}

/* The share a cluster card keeps, measured small, is the full-size texture's to 1%. */
static void cluster_fill(void **state) {
    (void)state;
    enum { N = 512 };
    uint8_t *rgba = malloc(4 * N * N);
    for (int shape = 0; shape <= SYL_CLUSTER_NEEDLES; shape++) {
        assert_true(syl_leaf_draw_cluster(shape, N, rgba));
        size_t kept = 0;
        for (int i = 0; i < N * N; i++) kept += rgba[4 * i + 3] >= 128;
        assert_near(syl_leaf_cluster_fill(shape), (double)kept / (N * N), 0.01);
        for (int i = 0; i < N; i++) assert_int_equal(rgba[4 * i + 3] | rgba[4 * (N * (N - 1) + i) + 3], 0);
    }
    free(rgba);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(straight_tube),
        cmocka_unit_test(leaf_clusters),
        cmocka_unit_test(cluster_fill),
        cmocka_unit_test(lobed_rings),
        cmocka_unit_test(optimize_keeps_best_orders),
        cmocka_unit_test(optimize_drops_degenerate),
        cmocka_unit_test(tree_is_closed_per_axis),
        cmocka_unit_test(uv_continuous_along_axis),
        cmocka_unit_test(uv_radius_floor),
        cmocka_unit_test(thin_branches_get_fewer_sides),
        cmocka_unit_test(pipe_model_at_forks),
        cmocka_unit_test(groups_by_material),
        cmocka_unit_test(deterministic_across_threads),
        cmocka_unit_test(trunk_jitter),
        cmocka_unit_test(organs),
        cmocka_unit_test(disc),
        cmocka_unit_test(polygons),
        cmocka_unit_test(smooth_nodes),
        cmocka_unit_test(lateral_base_is_sunk),
        cmocka_unit_test(odd_input),
        cmocka_unit_test(open_tubes_without_caps),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
