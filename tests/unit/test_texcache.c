/* The texture cache of the .glb writers (sylva/stream.h, kept by sylva view's server): a
 * write from the cache — the first, which fills it, and the next ones, which take its PNGs —
 * is byte for byte the write without it, for bark, leaves, leaf cards and clusters, one plant,
 * levels of detail and wind. */
#include "unit.h"

#include "sylva/lod.h"
#include "sylva/plant.h"
#include "sylva/stream.h"
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
        cmocka_unit_test(plants_from_the_cache),
        cmocka_unit_test(wind_from_the_cache),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
