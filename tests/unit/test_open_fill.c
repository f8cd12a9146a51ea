/* The fast paths of open L-systems: a set of casters replaced step by step gives the shadow
 * of removing and adding every caster; the turtle's lazy frame (turns made only when read,
 * dropped in branches nobody reads) gives the frames of the skeleton's turtle; the compact
 * probes of scene/open.c are the probes of the plain reading. */
#include <math.h>

#include "unit.h"

#include "env/shadow.h"
#include "lsys/modstr.h"
#include "sylva/skeleton.h"
#include "turtle/turtle.h"
#include "util/rng.h"

/* ---- ShadowSet ---- */

static void same_grid(const ShadowGrid *a, const ShadowGrid *b) {
    assert_int_equal(a->x0, b->x0);
    assert_int_equal(a->y0, b->y0);
    assert_int_equal(a->z0, b->z0);
    assert_int_equal(a->nx, b->nx);
    assert_int_equal(a->ny, b->ny);
    assert_int_equal(a->nz, b->nz);
    if (!a->s) return;
    for (size_t i = 0; i < shadow_voxels(a); i++)
        if (a->s[i] != b->s[i]) fail_msg("voxel %zu: %d, expected %d", i, (int)b->s[i], (int)a->s[i]);
}

/* Steps of random ends, with repeats, ends below the ground, one far away (the grid grows),
 * an empty step and a step like the one before: the set's grid is the plain one. */
static void set_replace_is_remove_and_add(void **state) {
    (void)state;
    ShadowParams p = {.voxel = 0.5f, .full = 1, .a = 0.25f, .b = 2, .depth = 6, .sun = {0.3f, 0.9f, 0.1f}};
    ShadowGrid plain, fast;
    shadow_init(&plain, &p, 0);
    shadow_init(&fast, &p, 0);
    ShadowSet set = {0};
    const float off[3] = {0.25f, 0.1f, -3.3f};
    enum { MAX = 3000 };
    float(*ends)[3] = malloc(MAX * sizeof *ends), (*moved)[3] = malloc(MAX * sizeof *moved),
    (*old)[3] = malloc(MAX * sizeof *old);
    size_t nold = 0;
    Rng rng = rng_stream(7, 0, 0, 0);
    for (int step = 0; step < 12; step++) {
        size_t n = step == 5 ? 0 : step == 6 ? nold : (size_t)(rng_unit(&rng) * MAX);
        for (size_t i = 0; i < n; i++) {
            if (step == 6) {
                memcpy(ends[i], old[i], sizeof *ends);
                continue;
            }
            if (i && rng_unit(&rng) < 0.3) { /* several ends in one voxel */
                memcpy(ends[i], ends[(size_t)(rng_unit(&rng) * (double)i)], sizeof *ends);
                continue;
            }
            float spread = 2.0f + (float)step;
            for (int k = 0; k < 3; k++) ends[i][k] = (float)(rng_unit(&rng) * 2 - 1) * spread;
            ends[i][1] += 0.5f * spread; /* some below the ground */
        }
        if (step == 8 && n) ends[0][0] = 40, ends[0][1] = 12; /* far away */
        for (size_t i = 0; i < nold; i++) /* the plain way: the old ends out, the new in */
            for (int k = 0; k < 3; k++) moved[i][k] = old[i][k] + off[k];
        assert_true(shadow_cast(&plain, (const float(*)[3])moved, nold, -1));
        for (size_t i = 0; i < n; i++)
            for (int k = 0; k < 3; k++) moved[i][k] = ends[i][k] + off[k];
        assert_true(shadow_cast(&plain, (const float(*)[3])moved, n, 1));
        assert_true(shadow_set_replace(&fast, &set, (const float(*)[3])ends, n, off));
        same_grid(&plain, &fast);
        memcpy(old, ends, n * sizeof *ends);
        nold = n;
    }
    free(ends);
    free(moved);
    free(old);
    shadow_set_free(&set);
    shadow_free(&plain);
    shadow_free(&fast);
}

/* ---- the lazy frame ---- */

/* An axiom of many turns (more than 32 between segments, so that the frame is tidied on the
 * way), levels, half turns, headings, branches and branches that only turn and ask where
 * they are; after every segment the four queries. */
static char *random_axiom(uint64_t seed) {
    Rng rng = rng_stream(seed, 0, 0, 0);
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    static const char *turns[] = {"+", "-", "&", "^", "\\", "/"};
    int depth = 0;
    for (int i = 0; i < 400; i++) {
        double u = rng_unit(&rng);
        if (u < 0.45) {
            fprintf(f, "%s(%.3f) ", turns[(int)(rng_unit(&rng) * 6)], rng_unit(&rng) * 200 - 100);
        } else if (u < 0.47) {
            for (int k = 0; k < 40; k++) fprintf(f, "+(%.2f) &(%.2f) ", rng_unit(&rng) * 7, rng_unit(&rng) * 5);
        } else if (u < 0.5) {
            fputs(rng_unit(&rng) < 0.5 ? "| " : "$ ", f);
        } else if (u < 0.52) {
            fprintf(f, "@R(%.2f, %.2f, %.2f) ", rng_unit(&rng) - 0.5, rng_unit(&rng), rng_unit(&rng) - 0.5);
        } else if (u < 0.62) {
            fprintf(f, "[ +(%.1f) /(%.1f) A ?P(0, 0, 0) ] ", rng_unit(&rng) * 90, rng_unit(&rng) * 180);
        } else if (u < 0.7 && depth < 20) {
            fputs("[ ", f);
            depth++;
        } else if (u < 0.78 && depth > 0) {
            fputs("] ", f);
            depth--;
        } else if (u < 0.8) {
            fputs("f(0.5) ", f);
        } else {
            fprintf(f, "F(%.2f) ?P(0, 0, 0) ?H(0, 0, 0) ?L(0, 0, 0) ?U(0, 0, 0) ", 0.2 + rng_unit(&rng));
        }
    }
    while (depth--) fputs("] ", f);
    fclose(f);
    return text;
}

static double as_query(float v) { return fabsf(v) < 1e-6f ? 0.0 : (double)v; }

static void lazy_frame_is_the_turtles(void **state) {
    (void)state;
    for (uint64_t seed = 1; seed <= 20; seed++) {
        char *axiom = random_axiom(seed), *text = NULL;
        size_t len = 0;
        FILE *f = open_memstream(&text, &len);
        fprintf(f, "lsystem L {\n  axiom %s\n}\n", axiom);
        fclose(f);
        UnitRun r = unit_run(text, (SylDeriveOptions){.steps = 0, .threads = 1});
        assert_int_equal(r.status, SYL_OK);
        SylSkeleton *sk = NULL;
        assert_int_equal(syl_turtle_draw(r.p, r.s, NULL, &sk), SYL_OK);
        /* the k-th segment's node, and the queries after the k-th F */
        int F = syl_program_symbol_find(r.p, "F");
        const int Q[4] = {syl_program_symbol_find(r.p, "?P"), syl_program_symbol_find(r.p, "?H"),
                          syl_program_symbol_find(r.p, "?L"), syl_program_symbol_find(r.p, "?U")};
        size_t node = 0, segments = 0;
        for (size_t i = 0; i < syl_string_length(r.s); i++) {
            int na;
            const double *a;
            if (syl_string_module(r.s, i, &na, &a) != F) continue;
            while (node < sk->nnodes && sk->nodes[node].kind != SYL_KIND_INTERNODE) node++;
            assert_true(node < sk->nnodes);
            const SylNode *nd = &sk->nodes[node++];
            const float *want[4] = {nd->pos, nd->h, nd->l, nd->u};
            for (int q = 0; q < 4; q++) {
                assert_int_equal(syl_string_module(r.s, i + 1 + (size_t)q, &na, &a), Q[q]);
                for (int k = 0; k < 3; k++)
                    if (a[k] != as_query(want[q][k]))
                        fail_msg("seed %llu, segment %zu, query %d[%d]: %.9g, the turtle's %.9g",
                                 (unsigned long long)seed, segments, q, k, a[k], as_query(want[q][k]));
            }
            segments++;
        }
        assert_true(segments > 20);
        syl_skeleton_free(sk);
        unit_run_free(&r);
        free(text);
        free(axiom);
    }
}

/* ---- compact probes ---- */

static void compact_probes_are_the_probes(void **state) {
    (void)state;
    UnitRun r = unit_run("lsystem E {\n  derive 3\n  angle 30\n"
                         "  axiom F A ?E(0, 1)\n"
                         "  A -> F [ + A ?E(0, 1) ?E(1, 0, 2) ] [ - f A ?E(2, 0) ?E ?E(0) ?E(7, 1) ] & A ?E(0, 1, 5)\n}\n",
                         (SylDeriveOptions){.steps = -1, .threads = 1});
    assert_int_equal(r.status, SYL_OK);
    SylEnvFill plain = {0}, fast = {0};
    SylOpenFill open = {0};
    assert_int_equal(syl_turtle_query(r.p, r.s, &plain), SYL_OK);
    assert_int_equal(syl_turtle_fill(r.p, r.s, &fast, &open), SYL_OK);
    assert_int_equal(open.kinds, 7);
    assert_int_equal(fast.nends, plain.nends);
    assert_memory_equal(fast.ends, plain.ends, plain.nends * sizeof *plain.ends);
    size_t light = 0, other = 0;
    for (size_t i = 0; i < plain.nprobes; i++) {
        const SylEnvProbe *q = &plain.probes[i];
        double kind = r.s->par[q->par];
        if (q->na < 2) continue;
        if (kind == 0) {
            assert_true(light < open.nlight);
            const SylLightProbe *c = &open.light[light++];
            assert_memory_equal(c->pos, q->pos, sizeof c->pos);
            assert_int_equal(c->par & ~SYL_LIGHT_TIP, q->par);
            assert_int_equal((c->par & SYL_LIGHT_TIP) != 0, q->tip != 0);
        } else if (kind == 1 || kind == 2) {
            assert_true(other < fast.nprobes);
            const SylEnvProbe *c = &fast.probes[other++];
            assert_memory_equal(c->pos, q->pos, sizeof c->pos);
            assert_memory_equal(c->h, q->h, sizeof c->h);
            assert_int_equal(c->par, q->par);
            assert_int_equal(c->na, q->na);
            assert_int_equal(c->tip, q->tip);
        }
    }
    assert_int_equal(light, open.nlight);
    assert_int_equal(other, fast.nprobes);
    assert_true(light > 10 && other > 10);
    syl_env_fill_free(&plain), syl_env_fill_free(&fast), free(open.light);
    unit_run_free(&r);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(set_replace_is_remove_and_add),
        cmocka_unit_test(lazy_frame_is_the_turtles),
        cmocka_unit_test(compact_probes_are_the_probes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
