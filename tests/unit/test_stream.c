/* The stream writers (sylva/stream.h), which `sylva view` serves from memory: each writes the
 * same bytes as its file writer, and a failing stream is SYL_EIO. */
#include "unit.h"

#include <unistd.h>

#include "sylva/lod.h"
#include "sylva/plant.h"
#include "sylva/stream.h"
#include "sylva/texture.h"
#include "sylva/wind.h"

static const char *model = "lsystem P {\n derive 3\n angle 30\n width 0.1\n axiom A\n"
                           " A -> F[+A~leaf][-A]/(90)FA\n}\n";

static SylPlant build(const SylMeshOptions *mo) {
    SylProgram *p = unit_compile(model, NULL, NULL);
    assert_non_null(p);
    SylPlant pl;
    SylPlantOptions po = {.threads = 1, .mesh = mo};
    assert_int_equal(syl_plant_build(p, &po, &pl), SYL_OK);
    syl_program_free(p);
    return pl;
}

static char *slurp(const char *path, size_t *len) {
    char *s = syl_read_file(path, len);
    assert_non_null(s);
    return s;
}

/* The bytes of the file writer (into a temporary file) and of the stream writer agree. */
static void same(const char *file_bytes, size_t flen, const char *mem, size_t mlen) {
    assert_true(flen > 12);
    assert_int_equal(flen, mlen);
    assert_memory_equal(file_bytes, mem, flen);
}

static void glb_instanced_and_lods(void **state) {
    (void)state;
    SylMeshOptions mo = {.one_sided = 1, .leaves = SYL_LEAVES_INSTANCED, .threads = 1};
    SylPlant pl = build(&mo);
    SylInstances *sets = NULL;
    int nsets = 0;
    assert_int_equal(syl_instances_build(pl.skeleton, &mo, &sets, &nsets), SYL_OK);
    char path[] = "/tmp/sylva-test-stream-XXXXXX.glb";
    int fd = mkstemps(path, 4);
    assert_true(fd >= 0);
    close(fd);
    assert_int_equal(syl_mesh_write_glb_instanced(pl.mesh, sets, nsets, path, NULL), SYL_OK);
    char *mem = NULL;
    size_t mlen = 0, flen = 0;
    FILE *f = open_memstream(&mem, &mlen);
    assert_int_equal(syl_mesh_write_glb_instanced_stream(pl.mesh, sets, nsets, f, NULL), SYL_OK);
    fclose(f);
    char *file = slurp(path, &flen);
    same(file, flen, mem, mlen);
    free(file), free(mem);

    SylLodChain c = {0};
    assert_int_equal(syl_lod_build(pl.skeleton, &mo, pl.mesh, 2, &c), SYL_OK);
    assert_int_equal(syl_wind_write_glb_lods(&c, NULL, NULL, path, NULL), SYL_OK);
    f = open_memstream(&mem, &mlen);
    assert_int_equal(syl_wind_write_glb_lods_stream(&c, NULL, NULL, f, NULL), SYL_OK);
    fclose(f);
    file = slurp(path, &flen);
    same(file, flen, mem, mlen);
    free(file), free(mem);
    syl_lod_free(&c);
    syl_instances_free(sets, nsets);
    syl_plant_free(&pl);
    unlink(path);
}

static void glb_wind(void **state) {
    (void)state;
    SylMeshOptions mo = {.one_sided = 1, .vertex_nodes = 1, .threads = 1};
    SylPlant pl = build(&mo);
    assert_int_equal(syl_mesh_optimize(pl.mesh), SYL_OK);
    float *radius = malloc((pl.skeleton->nnodes + 1) * sizeof *radius);
    assert_int_equal(syl_mesh_radii(pl.skeleton, &mo, radius), SYL_OK);
    SylWind w = {0};
    assert_int_equal(syl_wind_build(pl.skeleton, radius, &(SylWindOptions){.speed = 8}, &w), SYL_OK);
    free(radius);
    char path[] = "/tmp/sylva-test-stream-XXXXXX.glb";
    int fd = mkstemps(path, 4);
    assert_true(fd >= 0);
    close(fd);
    assert_int_equal(syl_wind_write_glb(pl.mesh, NULL, 0, pl.skeleton, &w, path, NULL), SYL_OK);
    char *mem = NULL;
    size_t mlen = 0, flen = 0;
    FILE *f = open_memstream(&mem, &mlen);
    assert_int_equal(syl_wind_write_glb_stream(pl.mesh, NULL, 0, pl.skeleton, &w, f, NULL), SYL_OK);
    fclose(f);
    char *file = slurp(path, &flen);
    same(file, flen, mem, mlen);
    free(file), free(mem);
    syl_wind_free(&w);
    syl_plant_free(&pl);
    unlink(path);
}

static void png_and_a_failing_stream(void **state) {
    (void)state;
    uint8_t rgb[8 * 4 * 3];
    for (size_t i = 0; i < sizeof rgb; i++) rgb[i] = (uint8_t)(i * 7);
    char path[] = "/tmp/sylva-test-stream-XXXXXX.png";
    int fd = mkstemps(path, 4);
    assert_true(fd >= 0);
    close(fd);
    assert_int_equal(syl_png_write(path, rgb, 8, 4, NULL), SYL_OK);
    char *mem = NULL;
    size_t mlen = 0, flen = 0;
    FILE *f = open_memstream(&mem, &mlen);
    assert_int_equal(syl_png_write_stream(f, rgb, 8, 4, NULL), SYL_OK);
    fclose(f);
    char *file = slurp(path, &flen);
    same(file, flen, mem, mlen);
    free(file), free(mem);
    unlink(path);
    /* a stream that cannot be written: /dev/full fails every flush */
    FILE *full = fopen("/dev/full", "w");
    if (!full) skip();
    assert_int_equal(syl_png_write_stream(full, rgb, 8, 4, NULL), SYL_EIO);
    fclose(full);
    SylMeshOptions mo = {.one_sided = 1, .threads = 1};
    SylPlant pl = build(&mo);
    full = fopen("/dev/full", "w");
    assert_int_equal(syl_mesh_write_glb_instanced_stream(pl.mesh, NULL, 0, full, NULL), SYL_EIO);
    fclose(full);
    syl_plant_free(&pl);
}

/* The texture cache of the .glb writers (kept by sylva view's server): a write from the cache —
 * the first, which fills it, and the next ones, which take its PNGs — is byte for byte the
 * write without it, for bark, leaves, leaf cards and clusters, one plant, levels and wind. */
typedef struct Out {
    char *s;
    size_t n;
    FILE *f;
} Out;

static FILE *open_out(Out *o) {
    o->s = NULL, o->n = 0;
    o->f = open_memstream(&o->s, &o->n);
    assert_non_null(o->f);
    return o->f;
}

static void same_and_free(Out *a, Out *b) {
    fclose(a->f), fclose(b->f);
    assert_true(a->n > 1000);
    assert_int_equal(a->n, b->n);
    assert_memory_equal(a->s, b->s, a->n);
    free(a->s), free(b->s);
}

static void plants_from_the_cache(void **state) {
    (void)state;
    SylTextureCache *tc = syl_texture_cache_new();
    assert_non_null(tc);
    const int modes[] = {SYL_LEAVES_MESH, SYL_LEAVES_CARDS, SYL_LEAVES_CLUSTERS, SYL_LEAVES_MESH};
    for (int k = 0; k < 4; k++) { /* the last: bark and leaf again, from the cache */
        SylMeshOptions mo = {.one_sided = 1, .leaves = modes[k], .threads = 1};
        SylPlant pl = build(&mo);
        Out a, b;
        assert_int_equal(syl_mesh_write_glb_instanced_stream(pl.mesh, NULL, 0, open_out(&a), NULL), SYL_OK);
        assert_int_equal(syl_mesh_write_glb_instanced_cached(pl.mesh, NULL, 0, tc, open_out(&b), NULL), SYL_OK);
        same_and_free(&a, &b);
        SylLodChain c = {0};
        assert_int_equal(syl_lod_build(pl.skeleton, &mo, pl.mesh, 2, &c), SYL_OK);
        assert_int_equal(syl_wind_write_glb_lods_stream(&c, NULL, NULL, open_out(&a), NULL), SYL_OK);
        assert_int_equal(syl_wind_write_glb_lods_cached(&c, NULL, NULL, tc, open_out(&b), NULL), SYL_OK);
        same_and_free(&a, &b);
        syl_lod_free(&c);
        syl_plant_free(&pl);
    }
    syl_texture_cache_free(tc);
}

static void wind_from_the_cache(void **state) {
    (void)state;
    SylTextureCache *tc = syl_texture_cache_new();
    SylMeshOptions mo = {.one_sided = 1, .vertex_nodes = 1, .threads = 1};
    SylPlant pl = build(&mo);
    float *radius = malloc((pl.skeleton->nnodes + 1) * sizeof *radius);
    assert_int_equal(syl_mesh_radii(pl.skeleton, &mo, radius), SYL_OK);
    SylWind w = {0};
    assert_int_equal(syl_wind_build(pl.skeleton, radius, &(SylWindOptions){.speed = 8}, &w), SYL_OK);
    free(radius);
    for (int k = 0; k < 2; k++) {
        Out a, b;
        assert_int_equal(syl_wind_write_glb_stream(pl.mesh, NULL, 0, pl.skeleton, &w, open_out(&a), NULL), SYL_OK);
        assert_int_equal(syl_wind_write_glb_cached(pl.mesh, NULL, 0, pl.skeleton, &w, tc, open_out(&b), NULL), SYL_OK);
        same_and_free(&a, &b);
    }
    syl_wind_free(&w);
    syl_plant_free(&pl);
    syl_texture_cache_free(tc);
    syl_texture_cache_free(NULL);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(glb_instanced_and_lods),
        cmocka_unit_test(glb_wind),
        cmocka_unit_test(png_and_a_failing_stream),
        cmocka_unit_test(plants_from_the_cache),
        cmocka_unit_test(wind_from_the_cache),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
