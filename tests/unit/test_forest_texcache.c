/* A forest's .glb with the run's texture cache (glb_write_forest, which `sylva ecosystem
 * --glb` uses for every year's file): the same bytes as without it, the first time (the
 * textures made and kept) and the next ones (copied from the cache), whatever the leaves. */
#include "unit.h"

#include <unistd.h>

#include "io/glb.h"
#include "sylva/plant.h"
#include "sylva/stream.h"

static const char *model = "lsystem P {\n derive 3\n angle 30\n width 0.1\n axiom A\n"
                           " A -> F[+A~leaf][-A]/(90)FA\n}\n";

static SylPlant build(int leaves) {
    SylProgram *p = unit_compile(model, NULL, NULL);
    assert_non_null(p);
    SylPlant pl;
    SylMeshOptions mo = {.leaves = leaves, .threads = 1};
    SylPlantOptions po = {.threads = 1, .mesh = &mo};
    assert_int_equal(syl_plant_build(p, &po, &pl), SYL_OK);
    syl_program_free(p);
    return pl;
}

static char *write_forest(const SylMesh *proto, SylTextureCache *tc, const char *path, size_t *len) {
    float t[6] = {0, 0, 0, 3, 0, 1}, r[8] = {0, 0, 0, 1, 0, 0, 0, 1}, s[6] = {1, 1, 1, 2, 2, 2};
    SylInstances set = {.proto = (SylMesh *)proto, .count = 2, .t = t, .r = r, .s = s, .name = "plant"};
    int st = glb_write_forest(NULL, &set, NULL, 1, tc, path, NULL);
    assert_int_equal(st, SYL_OK);
    char *bytes = syl_read_file(path, len);
    assert_non_null(bytes);
    return bytes;
}

static void forest_from_the_cache(void **state) {
    (void)state;
    char dir[] = "/tmp/sylva-forest-texcache-XXXXXX";
    assert_non_null(mkdtemp(dir));
    char path[64];
    snprintf(path, sizeof path, "%s/f.glb", dir);
    SylTextureCache *tc = syl_texture_cache_new();
    assert_non_null(tc);
    const int modes[] = {SYL_LEAVES_MESH, SYL_LEAVES_CARDS, SYL_LEAVES_CLUSTERS};
    for (int k = 0; k < 3; k++) {
        SylPlant pl = build(modes[k]);
        for (int again = 0; again < 2; again++) { /* again: every texture from the cache */
            size_t n0, n1;
            char *plain = write_forest(pl.mesh, NULL, path, &n0), *cached = write_forest(pl.mesh, tc, path, &n1);
            assert_true(n0 > 1000);
            assert_int_equal(n0, n1);
            assert_memory_equal(plain, cached, n0);
            assert_non_null(memmem(plain, n0, "image/png", 9)); /* it has textures to cache */
            free(plain), free(cached);
        }
        syl_plant_free(&pl);
    }
    syl_texture_cache_free(tc);
    unlink(path);
    rmdir(dir);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(forest_from_the_cache),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
