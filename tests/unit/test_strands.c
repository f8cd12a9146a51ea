/* Holton's strands (Zamuda's Algorithm 2): invariants of the tree that follow from the model,
 * not from Sylva's numbers: 2S - 1 segments and S tips (3.1), strands conserved at every fork,
 * the split (3.5) in integer arithmetic, d = k_d sqrt(S) (3.4), the angle alpha between the
 * two sub-branches and alpha_1 of the main one (3.7-3.8), lengths (3.24-3.26), gravimorphism
 * toward the ground, age (3.33-3.34), leaves per tip, and the same skeleton for any -j; and
 * docs/strands.md's parameter table names exactly the parameters the reader knows. */
#include <math.h>

#include "unit.h"

#include "strands/params.h"
#include "strands/strands.h"
#include "sylva/trees.h"

typedef struct Tree {
    SylProgram *p;
    StrandsParams P;
    SylSkeleton *sk;
    int64_t *S; /* per node: the strands of the segment it ends */
} Tree;

static Tree tree_of(const char *text, double age) {
    Tree t = {0};
    char *diag = NULL;
    t.p = unit_compile(text, &diag, NULL);
    if (!t.p) fail_msg("%s", diag);
    free(diag);
    assert_int_equal(strands_params_read(t.p, &t.P, stderr), 0);
    StrandsCounts c = strands_counts(&t.P, age);
    t.S = calloc(c.nodes, sizeof *t.S);
    t.sk = syl_skeleton_new("t");
    assert_int_equal(strands_build(&t.P, age, t.sk, t.S, NULL), SYL_OK);
    assert_int_equal(t.sk->nnodes, c.nodes);
    assert_int_equal(t.sk->norgans, c.organs);
    return t;
}

static void tree_free(Tree *t) {
    syl_skeleton_free(t->sk);
    syl_program_free(t->p);
    free(t->S);
}

static void heading(const SylSkeleton *sk, size_t i, double out[3]) {
    const SylNode *n = &sk->nodes[i], *p = &sk->nodes[n->parent];
    double len = 0;
    for (int k = 0; k < 3; k++) out[k] = n->pos[k] - p->pos[k], len += out[k] * out[k];
    len = sqrt(len);
    for (int k = 0; k < 3; k++) out[k] /= len;
}

static double angle_deg(const double a[3], const double b[3]) {
    double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    return acos(d > 1 ? 1 : d < -1 ? -1 : d) * 180 / M_PI;
}

/* The children of every node: main (same axis) and lateral (a new one). */
typedef struct Kids {
    int32_t main, lat, count;
} Kids;
static Kids *kids_of(const SylSkeleton *sk) {
    Kids *k = calloc(sk->nnodes, sizeof *k);
    for (size_t i = 0; i < sk->nnodes; i++) k[i].main = k[i].lat = -1;
    for (size_t i = 1; i < sk->nnodes; i++) {
        int32_t p = sk->nodes[i].parent;
        k[p].count++;
        if (sk->nodes[i].axis == sk->nodes[p].axis) k[p].main = (int32_t)i;
        else k[p].lat = (int32_t)i;
    }
    return k;
}

#define MODEL(S, extra) "strands T {\n  strands " #S "\n  leaves none\n" extra "}\n"

/* 2S - 1 segments, S tips, strands conserved, the split of (3.5) exact, for several S and
 * split ratios; S1 = ceil(1 + k_s (S0 - 2)) in integers: k_s = 3/5 gives 1 + ceil(3(S0-2)/5). */
static void counts_and_conservation(void **state) {
    (void)state;
    static const char *models[] = {
        MODEL(1, ""),
        MODEL(2, ""),
        MODEL(5, "  split_ratio 0.6\n"),
        MODEL(137, "  split_ratio 0.6\n"),
        MODEL(2500, "  split_ratio 0.6\n"),
        MODEL(2500, "  split_ratio 1\n"),
        MODEL(2500, "  split_ratio 0.5\n"),
        MODEL(999, "  curve g = (0, 0.95), (3, 0.5), (15, 0.9)\n  curve w = (0, 1), (20, 0.5)\n"
                   "  split_ratio g weibull w\n"),
    };
    static const int64_t S[] = {1, 2, 5, 137, 2500, 2500, 2500, 999};
    for (size_t m = 0; m < sizeof models / sizeof *models; m++) {
        Tree t = tree_of(models[m], 0);
        const SylSkeleton *sk = t.sk;
        Kids *k = kids_of(sk);
        int64_t segments = 0, tips = 0;
        for (size_t i = 1; i < sk->nnodes; i++) {
            assert_int_equal(sk->nodes[i].kind, SYL_KIND_INTERNODE);
            segments++;
            if (k[i].count == 0) {
                tips++;
                assert_int_equal(t.S[i], 1); /* one strand ends the branching */
            } else {
                assert_int_equal(k[i].count, 2);
                assert_true(k[i].main >= 0 && k[i].lat >= 0);
                assert_int_equal(t.S[k[i].main] + t.S[k[i].lat], t.S[i]);
                assert_true(t.S[k[i].main] >= t.S[k[i].lat]); /* the thicker bundle continues */
                assert_int_equal(sk->nodes[k[i].lat].order, sk->nodes[i].order + 1);
                assert_int_equal(sk->nodes[k[i].main].order, sk->nodes[i].order);
                int64_t S0 = t.S[i];
                if (m >= 2 && m <= 4) assert_int_equal(t.S[k[i].main], 1 + (3 * (S0 - 2) + 4) / 5);
                if (m == 5) assert_int_equal(t.S[k[i].main], S0 - 1);
                if (m == 6) assert_int_equal(t.S[k[i].main], 1 + (S0 - 2 + 1) / 2);
            }
        }
        assert_int_equal(segments, 2 * S[m] - 1);
        assert_int_equal(tips, S[m]);
        assert_int_equal(t.S[1], S[m]);
        free(k);
        tree_free(&t);
    }
}

/* d = k_d sqrt(S_0) on every segment; the trunk's is k_d sqrt(S). */
static void thickness_is_leonardo(void **state) {
    (void)state;
    Tree t = tree_of(MODEL(2500, "  thickness 0.02\n"), 0);
    assert_float_equal(2 * t.sk->nodes[1].radius, 0.02 * 50, 1e-6);
    for (size_t i = 1; i < t.sk->nnodes; i++)
        assert_float_equal(2 * t.sk->nodes[i].radius, 0.02 * sqrt((double)t.S[i]), 1e-6 * sqrt((double)t.S[i]));
    tree_free(&t);
}

/* The two sub-branches are alpha apart, the main one alpha_1 = k_c sqrt(S2/S0) alpha off its
 * parent, or on the trunk (k_c only there) off the vertical, whatever the phyllotaxis. */
static void branching_angles(void **state) {
    (void)state;
    Tree t = tree_of(MODEL(400, "  angle 40\n  gravicentralism 0.5\n  phyllotaxis 137\n"), 0);
    Kids *k = kids_of(t.sk);
    int forks = 0;
    for (size_t i = 1; i < t.sk->nnodes; i++) {
        if (k[i].count != 2) continue;
        double hp[3], hm[3], hl[3];
        heading(t.sk, i, hp);
        heading(t.sk, (size_t)k[i].main, hm);
        heading(t.sk, (size_t)k[i].lat, hl);
        assert_float_equal(angle_deg(hm, hl), 40, 1e-3);
        int trunk = t.sk->nodes[i].order == 0;
        double a1 = (trunk ? 0.5 : 1) * sqrt((double)t.S[k[i].lat] / (double)t.S[i]) * 40;
        static const double up[3] = {0, 1, 0};
        assert_float_equal(angle_deg(trunk ? up : hp, hm), a1, 1e-3); /* the trunk: off the vertical */
        forks++;
    }
    assert_int_equal(forks, 399);
    free(k);
    tree_free(&t);
}

static double seg_length(const SylSkeleton *sk, size_t i) {
    const SylNode *n = &sk->nodes[i], *p = &sk->nodes[n->parent];
    return sqrt(pow(n->pos[0] - p->pos[0], 2) + pow(n->pos[1] - p->pos[1], 2) + pow(n->pos[2] - p->pos[2], 2));
}

/* l_1 = k_l max(min(sqrt(S1/S0), M), m) L_0 and likewise for the lateral with its own bounds:
 * the trunk's first fork, L_0 = 1. */
static void lengths_clamped(void **state) {
    (void)state;
    Tree t = tree_of(MODEL(1000, "  trunk_length 3\n  split_ratio 0.9\n  length_max 0.92\n  length_min 0.5\n"
                                 "  length_scale 2\n  lateral_length_min 0.4\n  lateral_length_scale 1.5\n"),
                     0);
    Kids *k = kids_of(t.sk);
    assert_float_equal(seg_length(t.sk, 1), 3, 1e-5);
    double S0 = (double)t.S[1], S1 = (double)t.S[k[1].main], S2 = (double)t.S[k[1].lat];
    double r1 = fmax(fmin(sqrt(S1 / S0), 0.92), 0.5), r2 = fmax(fmin(sqrt(S2 / S0), 0.92), 0.4);
    assert_true(sqrt(S1 / S0) > 0.92 && sqrt(S2 / S0) < 0.4); /* both bounds bite */
    assert_float_equal(seg_length(t.sk, (size_t)k[1].main), 2 * r1, 1e-5);
    assert_float_equal(seg_length(t.sk, (size_t)k[1].lat), 1.5 * r2, 1e-5);
    free(k);
    tree_free(&t);
}

/* With no branching angle beyond the trunk, a horizontal branch turns down by alpha_m at
 * every fork: its first children point 30 degrees below the horizon. */
static void gravimorphism_bends_down(void **state) {
    (void)state;
    Tree t = tree_of(MODEL(300, "  curve a = (0, 90), (1, 0)\n  curve m = (0, 0), (1, 30)\n  angle a\n"
                                "  gravimorphism m\n  gravicentralism 0\n"),
                     0);
    Kids *k = kids_of(t.sk);
    int seen = 0;
    for (size_t i = 1; i < t.sk->nnodes; i++) {
        double h[3];
        heading(t.sk, i, h);
        if (t.sk->nodes[i].order == 0) assert_float_equal(h[1], 1, 1e-6); /* the trunk: straight up */
        if (t.sk->nodes[i].order != 1 || t.sk->nodes[t.sk->nodes[i].parent].order != 0) continue;
        assert_float_equal(h[1], 0, 1e-6); /* alpha_2 = 90: level */
        if (k[i].count == 2) {
            double hm[3];
            heading(t.sk, (size_t)k[i].main, hm);
            assert_float_equal(hm[1], -0.5, 1e-5);
            seen++;
        }
    }
    assert_true(seen > 10);
    free(k);
    tree_free(&t);
}

/* However strongly the branches droop, the trunk stands: its continuation is never bent by
 * gravimorphism and turns alpha_1 off the vertical, so every trunk segment is within alpha_1
 * of it; and no node, branch or leaf goes below the ground (hanging twigs trail on it). */
static void trunk_stands_nothing_below_ground(void **state) {
    (void)state;
    Tree t = tree_of("strands T {\n  strands 1500\n  trunk_length 1\n  angle 30\n  gravicentralism 0.8\n"
                     "  gravimorphism 90\n  length_max 1.8\n  leaves coniferous\n  leaf_size 0.3\n}\n",
                     0);
    int hanging = 0;
    for (size_t i = 1; i < t.sk->nnodes; i++) {
        const SylNode *n = &t.sk->nodes[i];
        assert_true(n->pos[1] >= -1e-5f);
        double h[3];
        heading(t.sk, i, h);
        if (n->order == 0) assert_true(acos(h[1]) * 180 / M_PI <= 0.8 * 30 + 1e-3);
        hanging += h[1] < -0.99;
    }
    for (size_t i = 0; i < t.sk->norgans; i++) assert_true(t.sk->organs[i].pos[1] >= -1e-5f);
    assert_true(hanging > 100); /* the droop is real: many twigs hang straight down */
    tree_free(&t);
}

/* S' = t^2 S and l_0' = t^2 l_0: at t = 0.5 a quarter of the strands and of the trunk. */
static void age_scales(void **state) {
    (void)state;
    Tree t = tree_of(MODEL(2500, "  trunk_length 4\n"), 0.5);
    assert_int_equal(t.S[1], 625);
    assert_int_equal(t.sk->nnodes, 2 * 625);
    assert_float_equal(seg_length(t.sk, 1), 1, 1e-6);
    tree_free(&t);
}

/* rho_l leaves on every tip, needles for coniferous, each on a tip node. */
static void leaves_on_tips(void **state) {
    (void)state;
    static const char *types[] = {"stacked", "staggered", "spiral", "bunched", "coniferous"};
    for (int k = 0; k < 5; k++) {
        char text[256];
        snprintf(text, sizeof text, "strands T {\n  strands 50\n  leaves %s\n  leaf_density 7\n"
                                    "  leaf_size 0.2\n}\n", types[k]);
        Tree t = tree_of(text, 0);
        assert_int_equal(t.sk->norgans, 50 * 7);
        for (size_t i = 0; i < t.sk->norgans; i++) {
            const SylOrgan *o = &t.sk->organs[i];
            assert_int_equal(o->kind, k == 4 ? SYL_KIND_NEEDLE : SYL_KIND_LEAF);
            assert_int_equal(t.S[o->node], 1);
            assert_float_equal(o->size, 0.2, 1e-7);
        }
        tree_free(&t);
    }
}

static char *csv_of(const char *text, int threads) {
    SylProgram *p = unit_compile(text, NULL, NULL);
    assert_non_null(p);
    SylTreeOptions o = {.threads = threads, .diag = stderr};
    SylSkeleton *sk = NULL;
    assert_int_equal(syl_strands_build(p, &o, &sk), SYL_OK);
    char *out = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&out, &len);
    syl_skeleton_write_csv(sk, mem);
    fclose(mem);
    syl_skeleton_free(sk);
    syl_program_free(p);
    return out;
}

static void same_for_any_threads(void **state) {
    (void)state;
    const char *text = "strands T {\n  strands 3000\n  seed 7\n  leaves spiral\n  gravimorphism 20\n}\n";
    char *a = csv_of(text, 1), *b = csv_of(text, 4);
    assert_string_equal(a, b);
    free(a);
    free(b);
}

/* Bad parameters: counted, each reported at its value with a caret. */
static void bad_parameters(void **state) {
    (void)state;
    char *diag = NULL;
    int st;
    SylProgram *p = unit_compile("strands T {\n  strands 0\n  split_ratio 0.3\n  angel 30\n"
                                 "  leaves spiraal\n  angle nocurve\n}\n",
                                 &diag, &st);
    assert_null(p);
    assert_non_null(strstr(diag, "test.syl:2:11: error: strands (S) is 0: it must be a whole number from 1"));
    assert_non_null(strstr(diag, "test.syl:3:15: error: split_ratio: the Gravelius factor k_s^g is 0.3: it must be "
                                 "from 0.5 to 1"));
    assert_non_null(strstr(diag, "test.syl:4:3: error: a strands block has no parameter 'angel' (did you mean "
                                 "'angle'?)"));
    assert_non_null(strstr(diag, "(did you mean 'spiral'?)"));
    assert_non_null(strstr(diag, "test.syl:6:9: error: angle: no curve 'nocurve'"));
    assert_non_null(strstr(diag, "\n      |               ^"));
    free(diag);
}

/* The rows of the table under "### Parameters" in docs/strands.md: their first cells. */
static int doc_rows(char names[][64], int max) {
    FILE *f = fopen("docs/strands.md", "r");
    if (!f) fail_msg("cannot read docs/strands.md (run from the project's root)");
    char line[4096];
    int n = 0, in = 0;
    while (fgets(line, sizeof line, f)) {
        if (!strncmp(line, "### Parameters", 14)) in = 1;
        else if (in && !strncmp(line, "| `", 3) && n < max) {
            char *end = strchr(line + 3, '`');
            if (end) snprintf(names[n++], 64, "%.*s", (int)(end - line - 3), line + 3);
        } else if (in && n && line[0] != '|') break;
    }
    fclose(f);
    return n;
}

static void docs_list_every_parameter(void **state) {
    (void)state;
    const char *names[64], *symbols[64];
    int n = strands_param_names(names, symbols, 64);
    char rows[64][64];
    int nr = doc_rows(rows, 64);
    assert_int_equal(nr, n);
    for (int i = 0; i < n; i++) {
        int k = 0;
        while (k < nr && strcmp(rows[k], names[i])) k++;
        if (k == nr) fail_msg("docs/strands.md: no row for '%s' (%s)", names[i], symbols[i]);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(counts_and_conservation), cmocka_unit_test(thickness_is_leonardo),
        cmocka_unit_test(branching_angles),        cmocka_unit_test(lengths_clamped),
        cmocka_unit_test(gravimorphism_bends_down), cmocka_unit_test(trunk_stands_nothing_below_ground), cmocka_unit_test(age_scales),
        cmocka_unit_test(leaves_on_tips),          cmocka_unit_test(same_for_any_threads),
        cmocka_unit_test(bad_parameters),          cmocka_unit_test(docs_list_every_parameter),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
