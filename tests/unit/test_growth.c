/* syl_growth_*: each frame of an animation is the plant syl_plant_build makes for that many
 * steps or years, whether the frames come from one derivation (L-systems) or from growing
 * again (grow blocks). */
#include "sylva/plant.h"
#include "unit.h"

/* Same nodes (positions, parents, orders) and the same mesh. */
static void assert_same_plant(const SylPlant *a, const SylPlant *b) {
    assert_int_equal(a->skeleton->nnodes, b->skeleton->nnodes);
    for (size_t i = 0; i < a->skeleton->nnodes; i++) {
        const SylNode *x = &a->skeleton->nodes[i], *y = &b->skeleton->nodes[i];
        assert_memory_equal(x->pos, y->pos, sizeof x->pos);
        assert_int_equal(x->parent, y->parent);
        assert_int_equal(x->order, y->order);
    }
    assert_int_equal(a->mesh->nverts, b->mesh->nverts);
    assert_int_equal(a->mesh->nidx, b->mesh->nidx);
    assert_memory_equal(a->mesh->pos, b->mesh->pos, a->mesh->nverts * 3 * sizeof(float));
}

static void check_frames(const char *text, int want, int first_label) {
    SylProgram *p = unit_compile(text, NULL, NULL);
    assert_non_null(p);
    SylPlantOptions opt = {.threads = 2};
    SylGrowth *g = NULL;
    assert_int_equal(syl_growth_new(p, &opt, &g), SYL_OK);
    assert_int_equal(syl_growth_count(g), want);
    /* the last frame first, as sylva animate asks for it, then the rest in order */
    for (int i = 0; i < want; i++) {
        int k = i == 0 ? want - 1 : i - 1;
        int label = syl_growth_label(g, k);
        assert_int_equal(label, first_label + k);
        SylPlant frame, alone;
        assert_int_equal(syl_growth_build(g, k, &frame), SYL_OK);
        SylPlantOptions o = {.threads = 1, .use_steps = 1, .steps = label};
        assert_int_equal(syl_plant_build(p, &o, &alone), SYL_OK);
        assert_same_plant(&frame, &alone);
        syl_plant_free(&frame);
        syl_plant_free(&alone);
    }
    SylPlant none;
    assert_int_equal(syl_growth_build(g, want, &none), SYL_EUSAGE);
    syl_growth_free(g);
    syl_program_free(p);
}

/* stochastic and branching: the kept strings are the strings of shorter derivations */
static void lsystem_steps_are_derivations(void **state) {
    (void)state;
    check_frames("lsystem S {\n  derive 5\n  seed 3\n  angle 30\n  axiom A\n"
                 "  A -> F[+A][-A] : 0.6\n  A -> F[/A]A : 0.4\n}\n",
                 6, 0);
}

static void grow_years_are_growths(void **state) {
    (void)state;
    check_frames("grow Sapling {\n  years 3\n  internode 0.3\n  buds opposite angle 50\n"
                 "  light shadow a 0.2 b 3 depth 4\n  shoot relative max 2\n}\n",
                 3, 1);
}

static void weber_has_no_growth(void **state) {
    (void)state;
    SylProgram *p = unit_compile("weber Aspen {\n  Shape 7\n}\n", NULL, NULL);
    assert_non_null(p);
    SylGrowth *g = (SylGrowth *)1;
    assert_int_equal(syl_growth_new(p, &(SylPlantOptions){0}, &g), SYL_EUSAGE);
    assert_null(g);
    syl_program_free(p);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(lsystem_steps_are_derivations),
        cmocka_unit_test(grow_years_are_growths),
        cmocka_unit_test(weber_has_no_growth),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
