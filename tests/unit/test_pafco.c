/* Pafčo's generator (docs/pafco.md): invariants that follow from the thesis, not from Sylva's
 * numbers — ring points per DETAIL as Table T.1, diameters never wider than the parent and
 * falling linearly to 0, first-generation lengths bounded by the crown profile (round and
 * conical), at most three generations, children shorter toward the parent's tip and only on
 * NEXTG_POMER of a first-generation branch, whorls of V1G_POCET, the trunk's deviation falling
 * linearly to the base; a Pafčo file's bad values falling back with a warning, its unknown
 * names errors, VIG_ and V1G_ the same, and `sylva convert`'s file reading back exactly. */
#include <math.h>

#include "unit.h"

#include "pafco/pafco.h"
#include "sylva/mesh.h"
#include "sylva/trees.h"

typedef struct Tree {
    SylProgram *p;
    PafcoParams P;
    SylSkeleton *sk;
    PafcoLog log;
    char *diag;
} Tree;

/* A Pafčo file's text (defaults for what it leaves out) built with seed 7. */
static Tree tree_of(const char *cfg) {
    Tree t = {0};
    t.p = unit_compile(cfg, &t.diag, NULL);
    if (!t.p) fail_msg("%s", t.diag);
    assert_int_equal(syl_program_kind(t.p), SYL_MODEL_PAFCO);
    assert_int_equal(pafco_params_read(t.p, &t.P, NULL), 0);
    Budget mem;
    budget_init(&mem, 0);
    t.sk = syl_skeleton_new("t");
    assert_int_equal(pafco_build(&t.P, 7, &mem, t.sk, &t.log, NULL), SYL_OK);
    return t;
}

static void tree_free(Tree *t) {
    syl_skeleton_free(t->sk);
    syl_program_free(t->p);
    free(t->log.branches);
    free(t->diag);
}

static double dist(const float *a, const float *b) {
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* A branch's length along its points, from the parent's point it grows from. */
static double branch_length(const SylSkeleton *sk, const PafcoBranch *b) {
    double len = 0;
    int32_t prev = b->attach;
    for (int32_t i = b->first; i <= b->last; prev = i++) len += dist(sk->nodes[prev].pos, sk->nodes[i].pos);
    return len;
}

#define THREE_GENERATIONS "VYSKA_STROMU=9\nV2GENER=true\nV3GENER=true\nV2G_MAX=1.6\nV3G_MAX=0.6\nSEG_VET=5\n"

/* Table T.1 as the thesis prints it: trunk, generations 1, 2, 3 at DETAIL 1, 2, 3. */
static const int table_t1[3][4] = {{6, 5, 3, 3}, {8, 6, 5, 3}, {12, 8, 6, 5}};

static void ring_points_are_table_t1(void **state) {
    (void)state;
    for (int d = 1; d <= 3; d++) {
        char cfg[256];
        snprintf(cfg, sizeof cfg, THREE_GENERATIONS "SPH_LISTY=false\nDETAIL=%d\n", d);
        Tree t = tree_of(cfg);
        SylMesh *m = NULL;
        SylMeshOptions mo = {.vertex_nodes = 1, .caps = -1, .threads = 1};
        assert_int_equal(syl_mesh_build(t.sk, &mo, &m), SYL_OK);
        /* a tube's vertices all name its last node: points x (ring + 1, the seam's copy) */
        size_t *per = calloc(t.sk->nnodes, sizeof *per);
        for (size_t v = 0; v < m->nverts; v++)
            if (m->node[v] >= 0) per[m->node[v]]++;
        int seen[4] = {0};
        for (int i = 0; i < t.log.n; i++) {
            const PafcoBranch *b = &t.log.branches[i];
            size_t points = (size_t)(b->last - b->first + 1) + (b->gen > 0);
            assert_int_equal(per[b->last] % points, 0);
            assert_int_equal(per[b->last] / points - 1, table_t1[d - 1][b->gen]);
            seen[b->gen]++;
        }
        for (int g = 0; g < 4; g++) assert_true(seen[g] > 0); /* every generation was there */
        free(per);
        syl_mesh_free(m);
        tree_free(&t);
    }
}

static void sides_asked_for_win_over_detail(void **state) {
    (void)state;
    Tree t = tree_of(THREE_GENERATIONS "SPH_LISTY=false\nDETAIL=3\n");
    SylMesh *a = NULL, *b = NULL;
    SylMeshOptions mo = {.caps = -1, .threads = 1}, m8 = {.caps = -1, .threads = 1, .sides = 12, .min_sides = 12};
    assert_int_equal(syl_mesh_build(t.sk, &mo, &a), SYL_OK);
    assert_int_equal(syl_mesh_build(t.sk, &m8, &b), SYL_OK);
    assert_true(b->nverts > a->nverts); /* --sides 12 everywhere: more than DETAIL 3's 12/8/6/5 */
    syl_mesh_free(a);
    syl_mesh_free(b);
    tree_free(&t);
}

static void diameters_never_wider_than_the_parent_and_fall_to_zero(void **state) {
    (void)state;
    /* a thick branch ratio: the parent's radius is what bounds most bases */
    Tree t = tree_of(THREE_GENERATIONS "VRV_POMER=0.3\nKRV_POMER=0.01\n");
    const SylNode *n = t.sk->nodes;
    for (int i = 0; i < t.log.n; i++) {
        const PafcoBranch *b = &t.log.branches[i];
        int m = b->last - b->first + (b->gen == 0 ? 0 : 1); /* segments */
        assert_true(n[b->last].radius == 0.0f);
        if (b->gen == 0) continue;
        double r0 = n[b->first].radius * (double)m / (double)(m - 1); /* the base, from the first point */
        assert_true(r0 <= n[b->attach].radius * (1 + 1e-5) + 1e-7);
        for (int32_t k = b->first; k <= b->last; k++) { /* linear: r_k = r0 (1 - k/m) */
            double want = r0 * (1 - (double)(k - b->first + 1) / m);
            assert_true(fabs(n[k].radius - want) <= 1e-5 * (r0 + 1e-6));
            if (k > b->first) assert_true(n[k].radius <= n[k - 1].radius);
        }
    }
    tree_free(&t);
}

static double profile(bool round, double f) { return round ? sin(M_PI * (0.1 + 0.9 * f)) : 1 - f; }

static void first_generation_follows_the_crown_profile(void **state) {
    (void)state;
    for (int round = 0; round <= 1; round++) {
        char cfg[256];
        snprintf(cfg, sizeof cfg, "VYSKA_STROMU=12\nSIRKA_VYSKA=0.4\nKORUNA_KMEN=0.75\nV_ROZPTYL=0\nOKR_KORUNA=%s\n"
                                  "V2GENER=false\nSEG_KMEN=4\n", round ? "true" : "false");
        Tree t = tree_of(cfg);
        double H = 12, C = 0.75 * H, longest = 0.4 * H, low = 0, mid = 0, high = 0;
        int n1 = 0;
        for (int i = 0; i < t.log.n; i++) {
            const PafcoBranch *b = &t.log.branches[i];
            if (b->gen != 1) continue;
            double f = (t.sk->nodes[b->attach].pos[1] - (H - C)) / C;
            assert_true(f >= -1e-6 && f <= 1 + 1e-6); /* only from the crown's trunk points */
            double bound = longest * profile(round, f), len = branch_length(t.sk, b);
            assert_true(len <= bound * (1 + 1e-4));
            assert_true(len >= 0.8 * bound * (1 - 1e-4));
            if (f < 0.1) low = fmax(low, len);
            if (f > 0.35 && f < 0.55) mid = fmax(mid, len);
            if (f > 0.8) high = fmax(high, len);
            n1++;
        }
        assert_true(n1 > 10);
        /* conical: the longest at the base, shorter up; round: widest in the middle */
        if (!round) assert_true(low > mid && mid > high);
        else assert_true(mid > low && mid > high);
        tree_free(&t);
    }
}

static void at_most_three_generations(void **state) {
    (void)state;
    const char *cfgs[3] = {"V2GENER=false\nV3GENER=true\n", "V2GENER=true\nV3GENER=false\n", THREE_GENERATIONS};
    const int want[3] = {1, 2, 3};
    for (int c = 0; c < 3; c++) {
        Tree t = tree_of(cfgs[c]);
        int top = 0;
        for (size_t i = 0; i < t.sk->nnodes; i++) top = t.sk->nodes[i].order > top ? t.sk->nodes[i].order : top;
        assert_int_equal(top, want[c]);
        tree_free(&t);
    }
}

static void children_shorten_toward_the_tip_within_nextg(void **state) {
    (void)state;
    Tree t = tree_of(THREE_GENERATIONS "NEXTG_POMER=0.5\n");
    const PafcoBranch *B = t.log.branches;
    int checked = 0;
    for (int i = 0; i < t.log.n; i++) {
        if (B[i].gen < 2) continue;
        const PafcoBranch *par = &B[B[i].parent];
        int m = par->last - par->first + 1;
        double tpos = (double)(B[i].attach - par->first + 1) / m;
        double max = B[i].gen == 2 ? 1.6 : 0.6;
        if (B[i].gen == 2) assert_true(tpos <= 0.5 + 1e-9); /* NEXTG_POMER of the first generation */
        assert_true(B[i].bound <= max * (1 - tpos) + 1e-5);  /* falling toward the parent's tip */
        assert_true(branch_length(t.sk, &B[i]) <= B[i].bound * (1 + 1e-4));
        /* the next child of the same parent, further out, has a smaller bound */
        if (i + 1 < t.log.n) {
            for (int j = i + 1; j < t.log.n; j++)
                if (B[j].parent == B[i].parent && B[j].gen == B[i].gen) {
                    assert_true(B[j].bound < B[i].bound);
                    break;
                }
        }
        checked++;
    }
    assert_true(checked > 20);
    tree_free(&t);
}

static void whorls_of_v1g_pocet(void **state) {
    (void)state;
    for (int w = 1; w <= 5; w += 2) {
        char cfg[200];
        snprintf(cfg, sizeof cfg, "VYSKA_STROMU=10\nOKR_KORUNA=false\nKORUNA_KMEN=0.6\nV1G_POCET=%d\nV2GENER=false\n", w);
        Tree t = tree_of(cfg);
        int *at = calloc(t.sk->nnodes, sizeof *at);
        for (int i = 0; i < t.log.n; i++)
            if (t.log.branches[i].gen == 1) at[t.log.branches[i].attach]++;
        int points = 0;
        for (size_t i = 0; i < t.sk->nnodes; i++)
            if (at[i]) assert_int_equal(at[i], w), points++;
        assert_true(points >= 6);
        free(at);
        tree_free(&t);
    }
}

static void trunk_deviation_falls_linearly_to_the_base(void **state) {
    (void)state;
    Tree t = tree_of("VYSKA_STROMU=10\nMAX_ROZPTYL_KMEN=0.8\nSEG_KMEN=3\n");
    const PafcoBranch *trunk = &t.log.branches[0];
    int n = trunk->last - trunk->first;
    double most = 0;
    for (int i = 0; i <= n; i++) {
        const float *p = t.sk->nodes[trunk->first + i].pos;
        double off = sqrt(p[0] * p[0] + p[2] * p[2]);
        assert_true(off <= 0.8 * i / n + 1e-5);
        most = fmax(most, off);
    }
    assert_true(most > 0.1); /* it does deviate */
    tree_free(&t);
}

static void bad_values_fall_back_with_a_warning(void **state) {
    (void)state;
    Tree t = tree_of("VYSKA_STROMU=8\nDETAIL=9\nSPH_LISTY=maybe\nV2G_MAX=-1\n");
    assert_int_equal(t.P.detail, 2);    /* the defaults */
    assert_true(t.P.sph_leaves);
    assert_true(t.P.maxlen[1] == 1.5);
    assert_true(t.P.height == 8);
    assert_non_null(strstr(t.diag, "test.syl:2:8: warning: DETAIL must be in [1, 3], not 9; its default is kept"));
    assert_non_null(strstr(t.diag, "test.syl:3:11: warning: SPH_LISTY takes true or false"));
    assert_non_null(strstr(t.diag, "parameters are not given, their defaults are used"));
    tree_free(&t);
    /* in a .syl block the same value is an error */
    char *diag = NULL;
    int st;
    SylProgram *p = unit_compile("pafco T {\n    DETAIL 9\n}\n", &diag, &st);
    assert_null(p);
    assert_non_null(strstr(diag, "test.syl:2:12: error: DETAIL must be in [1, 3], not 9"));
    free(diag);
}

static void unknown_names_are_errors_with_a_caret(void **state) {
    (void)state;
    char *diag = NULL;
    int st;
    SylProgram *p = unit_compile("VYSKA_STROMU=8\nSIRKA_VYSKAA=0.3\n", &diag, &st);
    assert_null(p);
    assert_int_equal(st, SYL_EMODEL);
    assert_non_null(strstr(diag, "test.syl:2:1: error: Pafčo's generator has no parameter 'SIRKA_VYSKAA' (did you mean "
                                 "'SIRKA_VYSKA'"));
    assert_non_null(strstr(diag, "    2 | SIRKA_VYSKAA=0.3\n      | ^"));
    free(diag);
}

static void vig_v1g_and_english_names_are_one(void **state) {
    (void)state;
    Tree a = tree_of("VIG_UHOL=70\nVIG_POCET=3\nVIG_GRAV=4\nVIG_SUN=5\n");
    Tree b = tree_of("V1G_UHOL=70\nV1G_POCET=3\nV1G_GRAV=4\nV1G_SUN=5\n");
    assert_memory_equal(&a.P, &b.P, sizeof a.P);
    assert_int_equal(a.sk->nnodes, b.sk->nnodes);
    assert_memory_equal(a.sk->nodes, b.sk->nodes, a.sk->nnodes * sizeof *a.sk->nodes);
    tree_free(&a);
    tree_free(&b);
    SylProgram *p = unit_compile("pafco T {\n    branch_angle 70\n    whorl 3\n    gravity 4\n    sun 5\n}\n", NULL, NULL);
    assert_non_null(p);
    PafcoParams c;
    assert_int_equal(pafco_params_read(p, &c, NULL), 0);
    assert_true(c.angle[0] == 70 && c.whorl == 3 && c.grav[0] == 4 && c.sun[0] == 5);
    syl_program_free(p);
}

static void convert_reads_back_exactly(void **state) {
    (void)state;
    Tree t = tree_of("VYSKA_STROMU=12.3456789012345\nKRV_POMER=0.1\nTEX_SUBORY=a.png b_flower.png\nK_SUBOR=bark.png\n"
                     "OKR_KORUNA=false\n");
    char *one = NULL, *two = NULL;
    size_t n1 = 0, n2 = 0;
    FILE *f = open_memstream(&one, &n1);
    assert_int_equal(pafco_write_cfg(&t.P, f), SYL_OK);
    fclose(f);
    Tree u = tree_of(one);
    assert_memory_equal(&t.P, &u.P, sizeof t.P);
    assert_null(strstr(u.diag, "warning")); /* every parameter written */
    f = open_memstream(&two, &n2);
    assert_int_equal(pafco_write_cfg(&u.P, f), SYL_OK);
    fclose(f);
    assert_string_equal(one, two);
    free(one), free(two);
    tree_free(&t);
    tree_free(&u);
}

static void one_seed_one_tree(void **state) {
    (void)state;
    Tree a = tree_of(THREE_GENERATIONS "BIL_LISTY=true\n"), b = tree_of(THREE_GENERATIONS "BIL_LISTY=true\n");
    assert_int_equal(a.sk->nnodes, b.sk->nnodes);
    assert_int_equal(a.sk->norgans, b.sk->norgans);
    assert_memory_equal(a.sk->nodes, b.sk->nodes, a.sk->nnodes * sizeof *a.sk->nodes);
    assert_memory_equal(a.sk->organs, b.sk->organs, a.sk->norgans * sizeof *a.sk->organs);
    tree_free(&a);
    tree_free(&b);
}

static void leaves_where_the_thesis_puts_them(void **state) {
    (void)state;
    /* spherical: LSPH_POCET on a sphere of LSPH_POLOMER around every branch end and the trunk's */
    Tree t = tree_of(THREE_GENERATIONS "LSPH_POCET=6\nLSPH_POLOMER=0.25\n");
    assert_int_equal(t.sk->norgans, (size_t)6 * (size_t)t.log.n);
    for (size_t i = 0; i < t.sk->norgans; i++) {
        const SylOrgan *o = &t.sk->organs[i];
        assert_true(fabs(dist(o->pos, t.sk->nodes[o->node].pos) - 0.25) < 1e-4);
        assert_true(o->size == 0.2f); /* L_VELKOST */
    }
    tree_free(&t);
    /* billboards: one on every point of the last generation's branches, LBIL_UHOL to it */
    t = tree_of("V2GENER=true\nV3GENER=false\nSPH_LISTY=false\nBIL_LISTY=true\nLBIL_UHOL=30\nLBIL_DLZKA=0.2\n"
                "LBIL_SIRKA=0.05\n");
    size_t want = 0;
    for (int i = 0; i < t.log.n; i++)
        if (t.log.branches[i].gen == 2) want += (size_t)(t.log.branches[i].last - t.log.branches[i].first + 1);
    assert_int_equal(t.sk->norgans, want);
    for (size_t i = 0; i < t.sk->norgans; i++) {
        const SylOrgan *o = &t.sk->organs[i];
        const SylNode *n = &t.sk->nodes[o->node];
        assert_int_equal(n->order, 2);
        double c = o->h[0] * n->h[0] + o->h[1] * n->h[1] + o->h[2] * n->h[2];
        assert_true(fabs(acos(fmin(1, c)) * 180 / M_PI - 30) < 0.01);
    }
    assert_true(fabs(t.sk->materials[t.sk->organs[0].material].leaf_width - 0.25f) < 1e-6); /* LBIL_SIRKA / LBIL_DLZKA */
    tree_free(&t);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(ring_points_are_table_t1),
        cmocka_unit_test(sides_asked_for_win_over_detail),
        cmocka_unit_test(diameters_never_wider_than_the_parent_and_fall_to_zero),
        cmocka_unit_test(first_generation_follows_the_crown_profile),
        cmocka_unit_test(at_most_three_generations),
        cmocka_unit_test(children_shorten_toward_the_tip_within_nextg),
        cmocka_unit_test(whorls_of_v1g_pocet),
        cmocka_unit_test(trunk_deviation_falls_linearly_to_the_base),
        cmocka_unit_test(bad_values_fall_back_with_a_warning),
        cmocka_unit_test(unknown_names_are_errors_with_a_caret),
        cmocka_unit_test(vig_v1g_and_english_names_are_one),
        cmocka_unit_test(convert_reads_back_exactly),
        cmocka_unit_test(one_seed_one_tree),
        cmocka_unit_test(leaves_where_the_thesis_puts_them),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
