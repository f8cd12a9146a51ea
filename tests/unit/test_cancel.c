/* SylCancel (sylva.h): a build is asked whether to stop between its passes — before each
 * derivation step, every 65,536 modules of the turtle, before the mesher plans and before it
 * writes, before every year of a grown tree, each Weber-Penn trunk and main branch, every
 * 4,096 strands segments, Pafco's trunk and each whorl of its crown, a curvetree's trunk and each
 * first-level branch. Stopped at any of those asks it returns SYL_ECANCELED with nothing left in its
 * output (ASan's leak check in build-asan); never stopped, it builds the same mesh as
 * without a cancel. */
#include "unit.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sylva/mesh.h"
#include "sylva/plant.h"

/* Stops at its ask number `at` (counting from 0); counts every ask. */
typedef struct Asks {
    int asked, at;
} Asks;

static int stop_at(void *user) {
    Asks *a = user;
    return a->asked++ == a->at;
}

/* 2^17 modules once derived: the turtle asks twice (modules 0 and 65,536) */
static const char *const line = "lsystem Line {\n derive 17\n axiom F\n F -> FF\n}\n";
static const char *const bush = "lsystem Bush {\n derive 4\n angle 25\n axiom F\n F -> F[+F]F[-F]F\n}\n";

static int build(SylProgram *p, SylPlantStage until, Asks *a, SylPlant *pl) {
    SylCancel cancel = {.stop = stop_at, .user = a};
    SylMeshOptions mo = {.threads = 1, .sides = 3};
    SylPlantOptions po = {.threads = 1, .until = until, .mesh = &mo, .cancel = a ? &cancel : NULL, .scene = 1};
    return syl_plant_build(p, &po, pl);
}

static void assert_same_skeleton(const SylSkeleton *a, const SylSkeleton *b) {
    assert_int_equal(a->nnodes, b->nnodes);
    assert_int_equal(a->norgans, b->norgans);
    for (size_t i = 0; i < a->nnodes; i++) {
        assert_memory_equal(a->nodes[i].pos, b->nodes[i].pos, sizeof a->nodes[i].pos);
        assert_int_equal(a->nodes[i].parent, b->nodes[i].parent);
    }
    for (size_t i = 0; i < a->norgans; i++) assert_memory_equal(a->organs[i].pos, b->organs[i].pos, sizeof a->organs[i].pos);
}

/* p's skeleton built without a cancel, with one never stopping (asked at least `least` times: the
 * same skeleton), and stopped at each of its asks (SYL_ECANCELED at once, nothing left); the
 * number of asks */
static int stops_at_every_ask(SylProgram *p, const char *what, int least) {
    SylPlant plain, pl;
    assert_int_equal(build(p, SYL_PLANT_SKELETON, NULL, &plain), SYL_OK);
    if (strstr(what, "scene {")) assert_int_equal(plain.kind, SYL_MODEL_SCENE);
    Asks never = {.at = -1};
    assert_int_equal(build(p, SYL_PLANT_SKELETON, &never, &pl), SYL_OK);
    if (never.asked < least) fail_msg("%s: asked %d times, not at least %d", what, never.asked, least);
    assert_same_skeleton(pl.skeleton, plain.skeleton);
    syl_plant_free(&pl);
    for (int at = 0; at < never.asked; at++) {
        Asks a = {.at = at};
        assert_int_equal(build(p, SYL_PLANT_SKELETON, &a, &pl), SYL_ECANCELED);
        assert_int_equal(a.asked, at + 1); /* stopped at once */
        assert_null(pl.skeleton);
        assert_null(pl.string);
    }
    syl_plant_free(&plain);
    return never.asked;
}

/* derive 17 steps (17 asks), then the turtle's 2 */
static void every_pass_of_a_derivation_and_the_turtle_is_asked(void **state) {
    (void)state;
    SylProgram *p = unit_compile(line, NULL, NULL);
    assert_non_null(p);
    assert_int_equal(stops_at_every_ask(p, "line", 17 + 2), 17 + 2);
    SylPlant pl;
    assert_int_equal(build(p, SYL_PLANT_SKELETON, NULL, &pl), SYL_OK);
    assert_int_equal(pl.skeleton->nnodes, 131072 + 1);
    syl_plant_free(&pl);
    syl_program_free(p);
}

/* the mesher's two asks come after the derivation's and the turtle's; a build not stopped is
 * the same mesh as one without a cancel */
static void a_mesh_stops_before_planning_and_writing_and_is_the_same_when_not_stopped(void **state) {
    (void)state;
    SylProgram *p = unit_compile(bush, NULL, NULL);
    assert_non_null(p);
    SylPlant plain, pl;
    assert_int_equal(build(p, SYL_PLANT_MESH, NULL, &plain), SYL_OK);
    Asks never = {.at = -1};
    assert_int_equal(build(p, SYL_PLANT_MESH, &never, &pl), SYL_OK);
    assert_int_equal(never.asked, 4 + 1 + 2);
    assert_int_equal(pl.mesh->nverts, plain.mesh->nverts);
    assert_int_equal(pl.mesh->nidx, plain.mesh->nidx);
    assert_memory_equal(pl.mesh->pos, plain.mesh->pos, plain.mesh->nverts * 3 * sizeof(float));
    assert_memory_equal(pl.mesh->idx, plain.mesh->idx, plain.mesh->nidx * sizeof(uint32_t));
    syl_plant_free(&pl);
    for (int at = 4 + 1; at < never.asked; at++) {
        Asks a = {.at = at};
        assert_int_equal(build(p, SYL_PLANT_MESH, &a, &pl), SYL_ECANCELED);
        assert_null(pl.mesh);
        assert_null(pl.skeleton);
    }
    syl_plant_free(&plain);
    syl_program_free(p);
}

/* The kinds built without a string ask too: a grown tree (a scene's forest) before every year, a Weber-Penn tree
 * before each trunk, each first-level branch, its nodes and its leaves, a strands tree before
 * every 4,096 segments, a Pafco tree before its trunk and each whorl of its crown. Stopped at any ask, the build says nothing and leaves nothing (ASan's
 * leak check in build-asan); never stopped, its skeleton is the one built without a cancel. */
static const char *const kinds[] = {
    ("grow Sapling {\n  years 4\n  internode 0.3\n  buds opposite angle 50\n  light shadow a 0.2 b 3 depth 4\n"
     "  shoot relative max 2\n}\n"),
    "weber W {\n  Levels 2\n  Branches 1 5\n  Leaves 4\n}\n",
    "strands S {\n  strands 5000\n}\n",
    /* Pafco's tree: before the trunk and before each whorl of the crown's trunk points */
    "pafco P {\n}\n",
    /* a scene: its forest's years (two trees growing together) */
    ("grow G {\n  years 3\n  internode 0.3\n  buds opposite angle 50\n  light shadow a 0.2 b 3 depth 4\n}\n"
     "scene {\n  plant G at (0, 0, 0)\n  plant G at (2, 0, 0)\n}\n"),
};

static void grown_weber_and_strands_trees_stop_at_every_ask(void **state) {
    (void)state;
    /* at least: the years; a trunk, 5 branches, the nodes and the leaves; 3 batches of segments;
     * Pafco's trunk and a whorl */
    const int least[] = {4, 1 + 5 + 2, 3, 2, 3};
    for (size_t k = 0; k < sizeof kinds / sizeof *kinds; k++) {
        SylProgram *p = unit_compile(kinds[k], NULL, NULL);
        assert_non_null(p);
        stops_at_every_ask(p, kinds[k], least[k]);
        syl_program_free(p);
    }
}

/* A curvetree (its crown envelope an OBJ box beside the model) asks before its trunk's nodes and
 * before each first-level branch's. */
static void a_curvetree_stops_at_every_ask(void **state) {
    (void)state;
    char dir[] = "/tmp/sylva-test-cancel-XXXXXX", path[64];
    assert_non_null(mkdtemp(dir));
    unit_write_file(dir, "crown.obj",
                    "v -3 2 -3\nv 3 2 -3\nv 3 2 3\nv -3 2 3\nv -3 9 -3\nv 3 9 -3\nv 3 9 3\nv -3 9 3\n"
                    "f 1 2 3\nf 1 3 4\nf 5 7 6\nf 5 8 7\nf 1 5 6\nf 1 6 2\nf 2 6 7\nf 2 7 3\nf 3 7 8\nf 3 8 4\n"
                    "f 4 8 5\nf 4 5 1\n");
    static const char text[] = "curvetree C {\n  trunk polyline (0,0,0) (0,8,0)\n  envelope \"crown.obj\"\n}\n";
    snprintf(path, sizeof path, "%s/c.syl", dir);
    int st;
    SylCompileOptions opt = {.validate = syl_validate};
    SylProgram *p = syl_compile(path, text, strlen(text), &opt, &st);
    assert_non_null(p);
    stops_at_every_ask(p, "curvetree", 1 + 2); /* the trunk and at least two branches */
    syl_program_free(p);
    snprintf(path, sizeof path, "%s/crown.obj", dir);
    unlink(path);
    rmdir(dir);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_pass_of_a_derivation_and_the_turtle_is_asked),
        cmocka_unit_test(a_mesh_stops_before_planning_and_writing_and_is_the_same_when_not_stopped),
        cmocka_unit_test(grown_weber_and_strands_trees_stop_at_every_ask),
        cmocka_unit_test(a_curvetree_stops_at_every_ask),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
