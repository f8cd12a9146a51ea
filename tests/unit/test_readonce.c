/* A block is read once on its way to its products (issue 28): the schema's count of full
 * reads and of `lod` scans of a program (lang/schema.h), along the path `sylva mesh -o x.glb`
 * takes for a weber block, and along an ecosystem run to its looks, whose models' reads count
 * on the ecosystem's program (sch_count_into). */
#include "unit.h"

#include <sys/stat.h>
#include <unistd.h>

#include "lang/program.h"
#include "lang/schema.h"
#include "sylva/ecosystem.h"
#include "sylva/forest.h"
#include "sylva/lod.h"
#include "sylva/plant.h"
#include "sylva/terrain.h"

static int validate(void *user, const SylProgram *p, FILE *diag) { return syl_validate(user, p, diag); }

static SylProgram *compile_file(const char *path) {
    SylCompileOptions opt = {.validate = validate};
    int st;
    SylProgram *p = syl_compile(path, NULL, 0, &opt, &st);
    assert_non_null(p);
    return p;
}

static char dir[] = "/tmp/sylva-readonce-XXXXXX";

static void put(const char *name, const char *text) { unit_write_file(dir, name, text); }

static const char weber[] = "weber W {\n  Levels 2\n  Branches 1 5\n  lod 2\n}\n";

/* what cmd_mesh does for -o x.glb: compile with the check, the lod the block asks for, the
 * plant and its mesh, the levels, the file */
static void mesh_to_glb_reads_a_weber_block_once(void **state) {
    (void)state;
    put("w.syl", weber);
    char path[256], out[256];
    snprintf(path, sizeof path, "%s/w.syl", dir);
    snprintf(out, sizeof out, "%s/w.glb", dir);
    SylProgram *p = compile_file(path);
    int lod = (int)syl_program_setting(p, "lod");
    assert_int_equal(lod, 2);
    SylMeshOptions mo = {.threads = 1};
    SylPlantOptions po = {.threads = 1, .until = SYL_PLANT_MESH, .mesh = &mo};
    SylPlant pl;
    assert_int_equal(syl_plant_build(p, &po, &pl), SYL_OK);
    SylLodChain chain = {0};
    assert_int_equal(syl_lod_build(pl.skeleton, &mo, pl.mesh, lod, &chain), SYL_OK);
    assert_int_equal(syl_lod_write_glb(&chain, out, NULL), SYL_OK);
    assert_int_equal((int)syl_program_setting(p, "lod"), 2); /* asked again: the kept value */
    assert_int_equal(sch_reads(p), 1);
    assert_int_equal(sch_lod_scans(p), 1);
    syl_lod_free(&chain);
    syl_plant_free(&pl);
    syl_program_free(p);
    unlink(out);
}

/* A 6 x 6 flat DEM, 10 m cells. */
static void put_terrain(void) {
    char text[512];
    int k = snprintf(text, sizeof text, "ncols 6\nnrows 6\nxllcorner 0\nyllcorner 0\ncellsize 10\n");
    for (int r = 0; r < 6; r++) k += snprintf(text + k, sizeof text - (size_t)k, "100 100 100 100 100 100\n");
    put("flat.asc", text);
}

/* the block, its terrain, the looks of its species (two name one weber model, one a strands
 * model): the ecosystem's block read once, each model's once */
static void an_ecosystem_run_reads_each_block_once(void **state) {
    (void)state;
    put_terrain();
    put("e.syl", "weber W {\n  Levels 2\n  Branches 1 4\n}\n"
                 "strands S {\n  strands 40\n}\n"
                 "ecosystem E {\n  terrain \"flat.asc\"\n  years 3\n"
                 "  species a\n    model W\n  species b\n    model W\n  species c\n    model S\n}\n");
    char path[256];
    snprintf(path, sizeof path, "%s/e.syl", dir);
    SylCompileOptions opt = {.model = "E", .validate = validate};
    int st;
    SylProgram *p = syl_compile(path, NULL, 0, &opt, &st);
    assert_non_null(p);
    assert_int_equal(sch_reads(p), 1); /* the check */
    SylEcoOptions eo = {.threads = 1};
    SylEcoModel m;
    SylTerrain *t = NULL;
    assert_int_equal(syl_ecosystem_load(p, &eo, &m, &t), SYL_OK);
    assert_int_equal(sch_reads(p), 1);
    SylForest *f = NULL;
    assert_int_equal(syl_forest_new(p, &m, t, &(SylForestOptions){.threads = 1}, &f), SYL_OK);
    /* + W once for species a and b, + S once for all its ages */
    assert_int_equal(sch_reads(p), 3);
    syl_forest_free(f);
    syl_terrain_free(t);
    syl_program_free(p);
}

static int setup(void **state) {
    (void)state;
    return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state) {
    (void)state;
    const char *const names[] = {"w.syl", "w.glb", "e.syl", "flat.asc"};
    return unit_remove_files(dir, names, sizeof names / sizeof *names);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(mesh_to_glb_reads_a_weber_block_once),
        cmocka_unit_test(an_ecosystem_run_reads_each_block_once),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
