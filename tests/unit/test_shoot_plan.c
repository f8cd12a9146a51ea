/* The shoot-plan reader (sot/shoot_rule.c) turns and moves as the drawing turtle does: on
 * random strings of turns (exact at multiples of 90 degrees, more than 32 between segments so
 * that the frame is tidied on the way), half turns, moves and nested branches, every twig of
 * the plan is the turtle's segment, to the bit; and it saves branches deeper than 64. */
#include "unit.h"

#include "sot/shoot_rule.h"
#include "sylva/skeleton.h"
#include "util/rng.h"

static SylProgram *compile(const char *text) {
    char *diag = NULL;
    SylProgram *p = unit_compile(text, &diag, NULL);
    if (!p) fail_msg("%s\n%s", diag, text);
    free(diag);
    return p;
}

/* The plan of a rule `shoot(...) -> I [ body ]`: one metamer, a branch on its end. */
static ShootPlan plan_of(const char *body) {
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    fprintf(f,
            "grow T {\n  years 1\n  internode 0.3\n  shoot relative max 3 rule R\n}\n"
            "lsystem R {\n  angle 90\n  module shoot(n, v, o, y)\n  axiom shoot(1, 1, 0, 0)\n"
            "  shoot(n, v, o, y) -> I [ %s ]\n}\n",
            body);
    fclose(f);
    SylProgram *g = compile(text);
    ShootRule *r = shoot_rule_new(g, "R");
    assert_non_null(r);
    ShootPlan plan = {0};
    const double args[4] = {1, 1, 0, 0};
    assert_int_equal(shoot_rule_plan(r, args, 1, &plan, stderr), SYL_OK);
    shoot_rule_free(r);
    syl_program_free(g);
    free(text);
    return plan;
}

/* The skeleton the turtle draws of `[ body ]`, from the plan's frame at a metamer's end. */
static SylSkeleton *skeleton_of(const char *body) {
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    fprintf(f, "lsystem L {\n  axiom @R(1, 0, 0, 0, 0, 1) [ %s ]\n}\n", body);
    fclose(f);
    UnitRun r = unit_run(text, (SylDeriveOptions){.steps = 0, .threads = 1});
    assert_int_equal(r.status, SYL_OK);
    SylSkeleton *sk = NULL;
    assert_int_equal(syl_turtle_draw(r.p, r.s, NULL, &sk), SYL_OK);
    unit_run_free(&r);
    free(text);
    return sk;
}

static char *random_body(uint64_t seed) {
    Rng rng = rng_stream(seed, 0, 0, 0);
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    static const char *turns[] = {"+", "-", "&", "^", "\\", "/"};
    int depth = 0;
    for (int i = 0; i < 400; i++) {
        double u = rng_unit(&rng);
        const char *turn = turns[(int)(rng_unit(&rng) * 6)];
        if (u < 0.35) {
            fprintf(f, "%s(%.3f) ", turn, rng_unit(&rng) * 200 - 100);
        } else if (u < 0.45) {
            fprintf(f, "%s(%d) ", turn, 90 * ((int)(rng_unit(&rng) * 9) - 4)); /* exact */
        } else if (u < 0.47) {
            for (int k = 0; k < 40; k++) fprintf(f, "+(%.2f) &(%.2f) ", rng_unit(&rng) * 7, rng_unit(&rng) * 5);
        } else if (u < 0.5) {
            fputs("| ", f);
        } else if (u < 0.6 && depth < 20) {
            fputs("[ ", f);
            depth++;
        } else if (u < 0.68 && depth > 0) {
            fputs("] ", f);
            depth--;
        } else if (u < 0.69 && depth > 0) {
            fputs("% ", f);
        } else if (u < 0.72) {
            fputs("f(0.5) ", f);
        } else {
            fprintf(f, "F(%.2f) ", 0.2 + rng_unit(&rng));
        }
    }
    while (depth--) fputs("] ", f);
    fclose(f);
    return text;
}

static void plan_frames_are_the_turtles(void **state) {
    (void)state;
    size_t all = 0;
    for (uint64_t seed = 1; seed <= 20; seed++) {
        char *body = random_body(seed);
        ShootPlan plan = plan_of(body);
        SylSkeleton *sk = skeleton_of(body);
        size_t node = 0, twigs = 0;
        for (size_t i = 0; i < plan.n; i++) {
            const Attach *a = &plan.a[i];
            if (a->kind != ATT_TWIG) continue;
            while (node < sk->nnodes && sk->nodes[node].kind != SYL_KIND_INTERNODE) node++;
            assert_true(node < sk->nnodes);
            const SylNode *nd = &sk->nodes[node++];
            const float *got[3] = {a->pos, a->h, a->l}, *want[3] = {nd->pos, nd->h, nd->l};
            for (int q = 0; q < 3; q++)
                for (int k = 0; k < 3; k++)
                    if (got[q][k] != want[q][k])
                        fail_msg("seed %llu, twig %zu, vector %d[%d]: %.9g, the turtle's %.9g",
                                 (unsigned long long)seed, twigs, q, k, got[q][k], want[q][k]);
            twigs++;
        }
        while (node < sk->nnodes && sk->nodes[node].kind != SYL_KIND_INTERNODE) node++;
        assert_int_equal(node, sk->nnodes); /* no segment left over */
        all += twigs;
        syl_skeleton_free(sk);
        shoot_plan_free(&plan);
        free(body);
    }
    assert_true(all > 400);
}

/* 70 branches deep: a branch ends there as anywhere (no cap on the saved states). */
static void deep_branches_are_saved(void **state) {
    (void)state;
    char body[1024] = "";
    for (int k = 0; k < 70; k++) strcat(body, "[ ");
    strcat(body, "[ +(10) ] F(1) ");
    for (int k = 0; k < 70; k++) strcat(body, "] ");
    ShootPlan plan = plan_of(body);
    assert_int_equal(plan.n, 1);
    assert_int_equal(plan.a[0].kind, ATT_TWIG);
    assert_true(plan.a[0].pos[0] == 1 && plan.a[0].pos[1] == 0 && plan.a[0].pos[2] == 0); /* not turned */
    shoot_plan_free(&plan);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(plan_frames_are_the_turtles),
        cmocka_unit_test(deep_branches_are_saved),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
