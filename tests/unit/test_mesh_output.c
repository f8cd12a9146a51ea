/* syl_mesh_write_output, the one place that chooses how a plant's mesh is written to a file:
 * what the file's format cannot hold is refused with nothing written, and each kind of
 * output is the bytes of the writer it stands for. */
#include <sys/stat.h>
#include <unistd.h>

#include "sylva/lod.h"
#include "sylva/wind.h"
#include "unit.h"
#include "mesh_fixtures.h"

static bool exists(const char *path) {
    struct stat st;
    return stat(path, &st) == 0;
}

/* The bytes at path, then the file removed (with an OBJ's .mtl beside it): the next writer
 * writes the same name, which an OBJ names in its mtllib line. */
static char *take(const char *path, size_t *len) {
    char *t = syl_read_file(path, len);
    assert_non_null(t);
    unlink(path);
    char mtl[160];
    snprintf(mtl, sizeof mtl, "%.*s.mtl", (int)(strrchr(path, '.') - path), path);
    unlink(mtl);
    return t;
}

static void assert_same(char *a, size_t na, char *b, size_t nb) {
    assert_int_equal(na, nb);
    assert_memory_equal(a, b, na);
    free(a), free(b);
}

typedef struct Dir {
    char path[64];
} Dir;

static Dir make_dir(void) {
    Dir d;
    snprintf(d.path, sizeof d.path, "/tmp/sylva-test-mesh-output-XXXXXX");
    assert_non_null(mkdtemp(d.path));
    return d;
}

/* OBJ and PLY hold neither levels, nor wind, nor instances: refused, no file, said why. */
static void refuses_what_the_format_cannot_hold(void **state) {
    (void)state;
    SylSkeleton *s = fx_tree(4, 1);
    SylMesh *m = NULL;
    assert_int_equal(syl_mesh_build(s, NULL, &m), SYL_OK);
    Dir d = make_dir();
    SylLodChain chain = {0};
    SylWind wind = {0};
    const SylMeshOutput outs[] = {
        {.mesh = m, .lods = &chain},
        {.mesh = m, .skeleton = s, .wind = &wind},
        {.mesh = m, .instanced = true},
    };
    const char *what[] = {"levels of detail", "a skinned mesh", "instanced leaves"};
    const char *ext[] = {"obj", "ply"};
    for (int e = 0; e < 2; e++)
        for (int i = 0; i < 3; i++) {
            char path[128], *msg = NULL;
            size_t len = 0;
            snprintf(path, sizeof path, "%s/plant.%s", d.path, ext[e]);
            FILE *diag = open_memstream(&msg, &len);
            assert_int_equal(syl_mesh_write_output(&outs[i], path, &(SylSink){syl_diagnostic_print, diag}), SYL_EUSAGE);
            fclose(diag);
            assert_non_null(strstr(msg, what[i]));
            assert_false(exists(path));
            free(msg);
        }
    char path[128];
    snprintf(path, sizeof path, "%s/plant.usd", d.path); /* no such format */
    assert_int_equal(syl_mesh_write_output(&(SylMeshOutput){.mesh = m}, path, NULL), SYL_EUSAGE);
    assert_false(exists(path));
    rmdir(d.path);
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

/* Each output is its writer's bytes: the plain mesh in every format, instanced leaves, a
 * chain of levels. */
static void writes_as_its_writer(void **state) {
    (void)state;
    SylSkeleton *s = fx_tree(5, 2);
    SylMesh *m = NULL;
    assert_int_equal(syl_mesh_build(s, NULL, &m), SYL_OK);
    Dir d = make_dir();
    char path[128];
    size_t na, nb;
    const char *ext[] = {"glb", "obj", "ply"};
    for (int e = 0; e < 3; e++) {
        snprintf(path, sizeof path, "%s/plant.%s", d.path, ext[e]);
        assert_int_equal(syl_mesh_write_output(&(SylMeshOutput){.mesh = m}, path, &(SylSink){syl_diagnostic_print, stderr}), SYL_OK);
        char *a = take(path, &na), *b;
        assert_int_equal(syl_mesh_write(m, path, &(SylSink){syl_diagnostic_print, stderr}), SYL_OK);
        b = take(path, &nb);
        assert_same(a, na, b, nb);
    }
    snprintf(path, sizeof path, "%s/plant.glb", d.path);
    assert_int_equal(syl_mesh_write_output(&(SylMeshOutput){.mesh = m, .instanced = true}, path, &(SylSink){syl_diagnostic_print, stderr}), SYL_OK);
    char *a = take(path, &na), *b;
    assert_int_equal(syl_mesh_write_glb_instanced(m, NULL, 0, path, &(SylSink){syl_diagnostic_print, stderr}), SYL_OK);
    b = take(path, &nb);
    assert_same(a, na, b, nb);
    SylLodChain chain = {0};
    assert_int_equal(syl_lod_build(s, &(SylMeshOptions){0}, m, 2, &chain), SYL_OK);
    assert_int_equal(chain.n, 3);
    assert_int_equal(syl_mesh_write_output(&(SylMeshOutput){.mesh = m, .lods = &chain}, path, &(SylSink){syl_diagnostic_print, stderr}), SYL_OK);
    a = take(path, &na);
    assert_int_equal(syl_lod_write_glb(&chain, path, &(SylSink){syl_diagnostic_print, stderr}), SYL_OK);
    b = take(path, &nb);
    assert_same(a, na, b, nb);
    const char *textures[] = {"bark", "leaf", "flower"}; /* the OBJ's */
    for (int t = 0; t < 3; t++) {
        snprintf(path, sizeof path, "%s/plant_%s.png", d.path, textures[t]);
        unlink(path);
    }
    rmdir(d.path);
    syl_lod_free(&chain); /* its level 0 is m, the caller's */
    syl_mesh_free(m);
    syl_skeleton_free(s);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(refuses_what_the_format_cannot_hold),
        cmocka_unit_test(writes_as_its_writer),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
