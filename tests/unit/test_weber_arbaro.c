/* Arbaro's species against Arbaro 1.9.9 as measured (reference anchors §1.8, independent of
 * Sylva): stems per level, leaves, height and width at seed 13, and the mean stems and leaves
 * over seeds 1-10. Sylva does not replay Arbaro's random numbers past the tree's size, so one
 * seed's counts agree within a few percent, and their means over seeds closer. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "unit.h"

#include "sylva/trees.h"

typedef struct Counts {
    double level[5], stems, leaves, height, width;
} Counts;

static char *slurp(const char *path, size_t *len) {
    FILE *f = fopen(path, "rb");
    if (!f) fail_msg("cannot open %s", path);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)n + 1);
    assert_non_null(buf);
    assert_int_equal(fread(buf, 1, (size_t)n, f), (size_t)n);
    buf[n] = 0;
    fclose(f);
    *len = (size_t)n;
    return buf;
}

static SylProgram *species(const char *name) {
    char path[256];
    snprintf(path, sizeof path, "tests/weber/%s.syl", name);
    size_t len;
    char *text = slurp(path, &len);
    SylCompileOptions opt = {.diag = stderr, .validate = syl_validate};
    int st;
    SylProgram *p = syl_compile(path, text, len, &opt, &st);
    free(text);
    if (!p) fail_msg("%s does not compile", path);
    return p;
}

/* As Arbaro counts: stems (an axis with a drawn segment; a clone is a stem of its level),
 * leaves, the top of the stem axes and the farthest corner of their horizontal box. */
static Counts count(const SylProgram *p, uint64_t seed) {
    SylTreeOptions opt = {.use_seed = true, .seed = seed, .threads = 1, .diag = stderr};
    SylSkeleton *sk = NULL;
    assert_int_equal(syl_weber_build(p, &opt, &sk), SYL_OK);
    Counts c = {0};
    int32_t axes = 0;
    for (size_t i = 0; i < sk->nnodes; i++)
        if (sk->nodes[i].axis >= axes) axes = sk->nodes[i].axis + 1;
    unsigned char *seen = calloc((size_t)axes + 1, 1);
    assert_non_null(seen);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < sk->nnodes; i++) {
        const SylNode *n = &sk->nodes[i];
        for (int k = 0; k < 3; k++) lo[k] = fmin(lo[k], n->pos[k]), hi[k] = fmax(hi[k], n->pos[k]);
        if (n->kind != SYL_KIND_INTERNODE || n->axis < 0 || seen[n->axis]) continue;
        seen[n->axis] = 1;
        c.level[n->order < 4 ? n->order : 4]++;
        c.stems++;
    }
    free(seen);
    for (size_t i = 0; i < sk->norgans; i++) {
        const SylOrgan *o = &sk->organs[i];
        c.leaves += o->kind == SYL_KIND_LEAF;
        /* its frame orthonormal, u = h x l (leaves turn in floats: within 1e-5) */
        const float *h = o->h, *l = o->l, *u = o->u;
        float hl = h[0] * l[0] + h[1] * l[1] + h[2] * l[2];
        float cx = h[1] * l[2] - h[2] * l[1], cy = h[2] * l[0] - h[0] * l[2], cz = h[0] * l[1] - h[1] * l[0];
        float hh = h[0] * h[0] + h[1] * h[1] + h[2] * h[2], ll = l[0] * l[0] + l[1] * l[1] + l[2] * l[2];
        if (!(fabsf(hl) < 1e-5f && fabsf(hh - 1) < 1e-5f && fabsf(ll - 1) < 1e-5f && fabsf(cx - u[0]) < 1e-5f &&
              fabsf(cy - u[1]) < 1e-5f && fabsf(cz - u[2]) < 1e-5f))
            fail_msg("leaf %zu: its frame is not orthonormal", i);
        /* it hangs from a node of its own stem (the axis its module names) */
        if (o->node < 0 || (size_t)o->node >= sk->nnodes || sk->nodes[o->node].axis != (int32_t)o->module)
            fail_msg("leaf %zu: node %d is not on its stem %u", i, o->node, o->module);
    }
    c.height = hi[1];
    c.width = sqrt(fmax(lo[0] * lo[0] + lo[2] * lo[2], hi[0] * hi[0] + hi[2] * hi[2]));
    syl_skeleton_free(sk);
    return c;
}

static void near(const char *sp, const char *what, double got, double want, double pct) {
    double off = want != 0 ? fabs(got - want) / want * 100 : (got != 0) * 100.0;
    if (off > pct) fail_msg("%s: %s %.6g is %.1f%% from Arbaro's %.6g (more than %g%%)", sp, what, got, off, want, pct);
}

/* Arbaro at seed 13 (§1.8): stems per level, leaves, height x width (m). */
static const struct {
    const char *name;
    double level[4], leaves, height, width;
} seed13[] = {
    {"quaking_aspen", {1, 50, 1171, 0}, 21988, 14.79, 5.44},
    {"black_tupelo", {1, 50, 976, 8290}, 37248, 26.77, 12.53},
    {"ca_black_oak", {23, 200, 4385, 0}, 73109, 10.61, 9.74},
    {"weeping_willow", {5, 400, 1224, 23262}, 232620, 13.63, 8.42},
    {"sassafras", {1, 15, 221, 4862}, 54565, 23.29, 11.58},
    {"lombardy_poplar", {1, 40, 899, 0}, 8116, 25.68, 4.72},
    {"palm", {1, 33, 0, 0}, 8147, 12.98, 6.31},
    {"european_larch", {1, 60, 4525, 0}, 161600, 14.22, 6.78},
};

/* One seed: each level within 6% (the willow's second level, pruned to its envelope, is the
 * widest), leaves within 6%, height within 5%; the width is the extreme of a few random stems
 * and within 12%. */
static void per_level_at_seed_13(void **state) {
    (void)state;
    for (size_t i = 0; i < sizeof seed13 / sizeof *seed13; i++) {
        SylProgram *p = species(seed13[i].name);
        Counts c = count(p, 13);
        for (int l = 0; l < 4; l++) {
            char what[32];
            snprintf(what, sizeof what, "level %d stems", l);
            near(seed13[i].name, what, c.level[l], seed13[i].level[l], 6);
        }
        assert_true(c.level[4] == 0);
        near(seed13[i].name, "leaves", c.leaves, seed13[i].leaves, 6);
        near(seed13[i].name, "height", c.height, seed13[i].height, 5);
        near(seed13[i].name, "width", c.width, seed13[i].width, 12);
        syl_program_free(p);
    }
}

/* Arbaro's means over seeds 1-10 (§1.8). */
static const struct {
    const char *name;
    double stems, leaves;
} means[] = {
    {"quaking_aspen", 1226, 22053},   {"black_tupelo", 9311, 37224},     {"ca_black_oak", 4615, 73216},
    {"weeping_willow", 27326, 255877}, {"sassafras", 5113, 54724},       {"lombardy_poplar", 941, 8122},
    {"european_larch", 4586, 161600}, {"tamarack", 2288, 82908},         {"eastern_cottonwood", 1244, 36035},
};

/* The mean stems and leaves within 3% of Arbaro's means over seeds 1-10: the weeping willow's
 * over the same ten seeds (from seed to seed it varies by 6%, as Arbaro's does); the others
 * vary by under 1% from seed to seed (Arbaro's too), so seeds 1-3 stand for them (the test
 * stays within a few seconds under the sanitizers). */
static void means_over_seeds(void **state) {
    (void)state;
    for (size_t i = 0; i < sizeof means / sizeof *means; i++) {
        SylProgram *p = species(means[i].name);
        const uint64_t seeds = strcmp(means[i].name, "weeping_willow") ? 3 : 10;
        double stems = 0, leaves = 0;
        for (uint64_t seed = 1; seed <= seeds; seed++) {
            Counts c = count(p, seed);
            stems += c.stems / (double)seeds, leaves += c.leaves / (double)seeds;
        }
        near(means[i].name, "mean stems over seeds", stems, means[i].stems, 3);
        near(means[i].name, "mean leaves over seeds", leaves, means[i].leaves, 3);
        syl_program_free(p);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(per_level_at_seed_13),
        cmocka_unit_test(means_over_seeds),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
