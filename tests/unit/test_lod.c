/* Levels of detail, meshoptimizer passes and impostor views: invariants, not snapshots. */
#include "unit.h"

#include <math.h>

#include "mesh_fixtures.h"
#include "sylva/impostor.h"
#include "sylva/lod.h"
#include "sylva/render.h"
#include "sylva/texture.h"

/* A tree with a leaf at every node but the roots. */
static SylSkeleton *leafy_tree(void) {
    SylSkeleton *s = fx_tree(5, 3);
    size_t n = s->nnodes;
    for (size_t i = 0; i < n; i++) {
        if (s->nodes[i].parent < 0) continue;
        SylOrgan o = fx_organ(SYL_KIND_LEAF, s->nodes[i].pos[0], s->nodes[i].pos[1], s->nodes[i].pos[2], 0.3f, 1);
        o.node = (int32_t)i;
        assert_true(syl_skeleton_add_organ(s, &o) >= 0);
    }
    return s;
}

typedef struct Tri {
    float p[9];
} Tri;

static int cmp_tri(const void *a, const void *b) { return memcmp(a, b, sizeof(Tri)); }

/* Every triangle as its three corners, rotated to start at the smallest, sorted. */
static Tri *triangles(const SylMesh *m, size_t *n) {
    *n = m->nidx / 3;
    Tri *t = malloc(*n * sizeof *t);
    for (size_t i = 0; i < *n; i++) {
        int first = 0;
        for (int k = 1; k < 3; k++)
            if (memcmp(m->pos + 3 * m->idx[3 * i + k], m->pos + 3 * m->idx[3 * i + first], 12) < 0) first = k;
        for (int k = 0; k < 3; k++) memcpy(t[i].p + 3 * k, m->pos + 3 * m->idx[3 * i + (first + k) % 3], 12);
    }
    qsort(t, *n, sizeof *t, cmp_tri);
    return t;
}

static void optimize_keeps_the_surface(void **state) {
    (void)state;
    SylSkeleton *s = leafy_tree();
    SylMesh *m;
    assert_int_equal(syl_mesh_build(s, &(SylMeshOptions){0}, &m), SYL_OK);
    size_t n0, n1, v0 = m->nverts;
    int g0 = m->ngroups;
    Tri *before = triangles(m, &n0);
    assert_int_equal(syl_mesh_optimize(m), SYL_OK);
    Tri *after = triangles(m, &n1);
    assert_int_equal(n0, n1);
    assert_memory_equal(before, after, n0 * sizeof *before);
    assert_true(m->nverts <= v0);
    assert_int_equal(m->ngroups, g0);
    /* vertices come in the order the triangles first use them */
    uint32_t next = 0;
    for (size_t i = 0; i < m->nidx; i++) {
        assert_true(m->idx[i] <= next);
        if (m->idx[i] == next) next++;
    }
    assert_int_equal(next, m->nverts);
    free(before), free(after);
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

static void simplify_reduces(void **state) {
    (void)state;
    SylSkeleton *s = fx_tree(8, 3);
    SylMesh *m;
    assert_int_equal(syl_mesh_build(s, &(SylMeshOptions){.sides = 12}, &m), SYL_OK);
    size_t t0 = m->nidx / 3;
    float err = -1;
    assert_int_equal(syl_mesh_simplify(m, 0.25, 0.05f, &err), SYL_OK);
    assert_true(m->nidx / 3 > 0 && m->nidx / 3 <= t0 / 2);
    assert_true(err >= 0);
    for (size_t i = 0; i < m->nidx; i++) assert_true(m->idx[i] < m->nverts);
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

static void chain_levels(void **state) {
    (void)state;
    SylSkeleton *s = leafy_tree();
    SylMeshOptions mo = {0};
    SylMesh *m;
    assert_int_equal(syl_mesh_build(s, &mo, &m), SYL_OK);
    SylLodChain c;
    assert_int_equal(syl_lod_build(s, &mo, m, 3, &c), SYL_OK);
    assert_int_equal(c.n, 4);
    for (int k = 1; k < c.n; k++) {
        const SylLodLevel *lv = &c.level[k];
        assert_true(lv->mesh->nidx < c.level[k - 1].mesh->nidx);
        assert_true(lv->coverage < c.level[k - 1].coverage && lv->coverage > 0);
        /* one order fewer a level, the trunk's children kept; leaves halved down to a
         * quarter, enlarged by 1 / sqrt(share) so their area stays */
        assert_true(lv->max_order < c.level[k - 1].max_order || lv->max_order <= 1);
        assert_true(fabsf(lv->leaf_scale - 1 / sqrtf(lv->leaf_keep)) < 1e-6f && lv->leaf_scale <= 2);
        assert_true(lv->leaf_keep < c.level[k - 1].leaf_keep || lv->leaf_keep == 0.25f);
    }
    syl_lod_free(&c);
    assert_int_equal(syl_lod_build(s, &mo, m, SYL_LOD_MAX + 1, &c), SYL_EUSAGE);
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

/* A shoot of 4,000 needles: LOD1 thins them; LOD2 and LOD3 (where half their triangle
 * share, 15% and 4.5% of LOD0's, in cards of 2 triangles makes 4 or more needles a card)
 * keep all of them on at most that many needle-tuft cluster cards; instanced leaves are
 * never clustered. */
static void cluster_levels(void **state) {
    (void)state;
    SylSkeleton *s = fx_tree(4, 1);
    for (int i = 0; i < 4000; i++) {
        float a = 0.7f * (float)i;
        SylOrgan o = fx_organ(SYL_KIND_NEEDLE, 0.2f * cosf(a), 0.001f * (float)i, 0.2f * sinf(a), 0.1f, 1);
        o.node = 1;
        assert_true(syl_skeleton_add_organ(s, &o) >= 0);
    }
    static const double share[4] = {1, 0.45, 0.15, 0.045};
    for (int mode = 0; mode < 2; mode++) {
        SylMeshOptions mo = {.leaves = mode ? SYL_LEAVES_INSTANCED : SYL_LEAVES_MESH};
        SylMesh *m;
        assert_int_equal(syl_mesh_build(s, &mo, &m), SYL_OK);
        SylLodChain c;
        assert_int_equal(syl_lod_build(s, &mo, m, 3, &c), SYL_OK);
        double tris0 = (double)(m->nidx / 3);
        for (int k = 1; k < c.n; k++) {
            const SylLodLevel *lv = &c.level[k];
            bool want = !mode && k >= 2;
            assert_int_equal(lv->cluster_leaves > 0, want);
            assert_int_equal(lv->mesh->leaves == SYL_LEAVES_CLUSTERS, want);
            if (!want) continue;
            assert_true(lv->leaf_keep == 1 && lv->leaf_scale == 1);
            assert_int_equal(lv->mesh->leaf_shape, SYL_CLUSTER_NEEDLES);
            size_t cards = 0;
            for (int g = 0; g < lv->mesh->ngroups; g++)
                if (lv->mesh->materials[lv->mesh->groups[g].material].kind == SYL_MATERIAL_LEAF)
                    cards += lv->mesh->groups[g].count / 6;
            double most = 0.5 * share[k] * tris0 / 2;
            assert_true(cards >= 1 && (double)cards <= most);
            assert_near(lv->cluster_leaves, 4000 / most, 1e-3 * lv->cluster_leaves);
        }
        syl_lod_free(&c);
        syl_mesh_free(m);
    }
    syl_skeleton_free(s);
}

/* The documented hemi-octahedral mapping, run backwards: each cell's direction encodes to
 * the cell's centre. */
static void impostor_directions(void **state) {
    (void)state;
    float d[3];
    syl_impostor_direction(1, 0, 0, d);
    assert_true(fabsf(d[1] - 1) < 1e-6f);
    for (int g = 2; g <= 9; g++)
        for (int r = 0; r < g; r++)
            for (int c = 0; c < g; c++) {
                syl_impostor_direction(g, c, r, d);
                assert_true(fabsf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - 1) < 1e-5f);
                assert_true(d[1] >= 0);
                float l1 = fabsf(d[0]) + fabsf(d[1]) + fabsf(d[2]), tx = d[0] / l1, ty = d[2] / l1;
                float ex = tx + ty, ey = tx - ty;
                assert_true(fabsf(ex - (2 * (c + 0.5f) / g - 1)) < 1e-5f);
                assert_true(fabsf(ey - (2 * (r + 0.5f) / g - 1)) < 1e-5f);
            }
}

/* A view toward the plant frames its bounding sphere: the picture's corners lie outside the
 * sphere, so nothing covers them; something covers the middle of a solid sphere. */
static void toward_frames_the_sphere(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("ball");
    SylOrgan o = fx_organ(SYL_KIND_SPHERE, 0, 1, 0, 1.5f, 1);
    assert_true(syl_skeleton_add_organ(s, &o) >= 0);
    SylMesh *m;
    assert_int_equal(syl_mesh_build(s, &(SylMeshOptions){.sides = 16}, &m), SYL_OK);
    enum { N = 48 };
    uint8_t rgb[N * N * 3], alpha[N * N], nd[N * N * 4];
    float dir[3] = {0.3f, 0.5f, 0.81f};
    SylRenderOptions ro = {.width = N, .height = N, .toward = dir, .ground = -1, .alpha = alpha, .normal = nd,
                           .threads = 1};
    assert_int_equal(syl_render_draw_mesh(m, &ro, rgb), SYL_OK);
    assert_int_equal(alpha[0] + alpha[N - 1] + alpha[N * (N - 1)] + alpha[N * N - 1], 0);
    assert_int_equal(alpha[N * N / 2 + N / 2], 255);
    const uint8_t *c = nd + 4 * (N * N / 2 + N / 2); /* the middle faces the eye */
    float n[3] = {c[0] / 127.5f - 1, c[1] / 127.5f - 1, c[2] / 127.5f - 1}, l = sqrtf(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    assert_true((n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2]) / l > 0.9f);
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(optimize_keeps_the_surface), cmocka_unit_test(simplify_reduces),
        cmocka_unit_test(chain_levels),               cmocka_unit_test(impostor_directions),
        cmocka_unit_test(cluster_levels),
        cmocka_unit_test(toward_frames_the_sphere),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
