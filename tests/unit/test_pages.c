/* util/pages.c's pages_owned (memory free() and realloc take, on 2 MB pages past a size), the
 * skeleton's reserve that moves its nodes there, and a mesh whose arrays are one block
 * (SylMesh.block): appended to and freed like any other. Under the sanitizer build these also
 * check that every such array is released once, by the right call. */
#include <stdint.h>

#include "unit.h"
#include "mesh_fixtures.h"

#include "mesh/store.h"
#include "skeleton/store.h"
#include "util/pages.h"

static void owned_small_and_huge(void **state) {
    (void)state;
    unsigned char *a = pages_owned(1000, PAGES_OWNED_SCRATCH);
    assert_non_null(a);
    memset(a, 1, 1000);
    free(a);
    size_t n = 100000; /* past 64 KB: a whole 2 MB page, aligned */
    unsigned char *b = pages_owned(n, PAGES_OWNED_SCRATCH);
    assert_non_null(b);
    assert_int_equal((uintptr_t)b % PAGES_HUGE, 0);
    for (size_t i = 0; i < n; i++) b[i] = (unsigned char)(i * 7);
    unsigned char *c = realloc(b, 3 * (size_t)PAGES_HUGE); /* grows as malloc's memory does */
    assert_non_null(c);
    for (size_t i = 0; i < n; i++) assert_int_equal(c[i], (unsigned char)(i * 7));
    free(c);
    unsigned char *k = pages_owned(n, PAGES_OWNED_KEPT); /* kept arrays: small pages below 512 KB */
    assert_non_null(k);
    memset(k, 2, n);
    free(k);
}

/* Nodes added one by one, then room for many more reserved at once: the first ones move to
 * the huge pages intact, and the skeleton frees them. */
static void reserve_keeps_nodes(void **state) {
    (void)state;
    SylSkeleton *s = syl_skeleton_new("reserve");
    int32_t p = -1;
    for (int i = 0; i < 100; i++) p = fx_node(s, p, 0, 0, (float)i, 0, 0.5f, 0);
    size_t most = 20000; /* 20,000 nodes: past 512 KB */
    assert_true(most * sizeof *s->nodes >= PAGES_OWNED_KEPT);
    assert_true(skeleton_reserve_nodes(s, most));
    assert_int_equal((uintptr_t)s->nodes % PAGES_HUGE, 0);
    assert_int_equal(s->nnodes, 100);
    for (int i = 0; i < 100; i++) {
        assert_float_equal(s->nodes[i].pos[1], (float)i, 0);
        assert_int_equal(s->nodes[i].parent, i - 1);
    }
    for (int i = 100; i < 20000; i++) p = fx_node(s, p, 0, 0, (float)i, 0, 0.5f, 0);
    assert_int_equal(s->nnodes, 20000);
    syl_skeleton_free(s);
}

/* A straight tube of n nodes on one axis. */
static SylMesh *tube(int n, float x) {
    SylSkeleton *s = syl_skeleton_new("tube");
    int32_t p = -1;
    for (int i = 0; i < n; i++) p = fx_node(s, p, 0, x, (float)i, 0, 0.5f, 0);
    SylMesh *m = NULL;
    assert_int_equal(syl_mesh_build(s, &(SylMeshOptions){.threads = 1}, &m), SYL_OK);
    syl_skeleton_free(s);
    return m;
}

/* Appending keeps every vertex and triangle of both meshes (counts add up, positions as they
 * were, indices of the second shifted by the first's vertices), onto a block on huge pages,
 * a block in small pages, or arrays of their own. */
static void append_block(void **state) {
    (void)state;
    for (int order = 0; order < 2; order++) {
        SylMesh *big = tube(6000, 0), *small = tube(4, 10); /* 6000 x 9 vertices: past 512 KB */
        assert_non_null(big->store->block);
        assert_ptr_equal(big->pos, big->store->block);
        assert_non_null(small->store->block); /* a block too, in malloc's small pages */
        SylMesh *dst = order ? small : big, *src = order ? big : small;
        size_t nv = dst->nverts, ni = dst->nidx;
        float *want = malloc(3 * (nv + src->nverts) * sizeof *want);
        memcpy(want, dst->pos, 3 * nv * sizeof *want);
        memcpy(want + 3 * nv, src->pos, 3 * src->nverts * sizeof *want);
        uint32_t src_first = src->idx[0];
        assert_int_equal(syl_mesh_append(dst, src), SYL_OK);
        assert_null(dst->store->block);
        assert_int_equal(dst->nverts, nv + src->nverts);
        assert_int_equal(dst->nidx, ni + src->nidx);
        assert_memory_equal(dst->pos, want, 3 * dst->nverts * sizeof *want);
        bool found = false; /* src's first triangle, shifted */
        for (size_t i = 0; i < dst->nidx && !found; i++) found = dst->idx[i] == src_first + nv;
        assert_true(found);
        for (size_t i = 0; i < dst->nidx; i++) assert_true(dst->idx[i] < dst->nverts);
        free(want);
        SylMesh *more = tube(3, 20); /* onto the arrays append made, no block */
        size_t nv2 = dst->nverts, ni2 = dst->nidx;
        assert_int_equal(syl_mesh_append(dst, more), SYL_OK);
        assert_int_equal(dst->nverts, nv2 + more->nverts);
        assert_int_equal(dst->nidx, ni2 + more->nidx);
        syl_mesh_free(more);
        syl_mesh_free(big);
        syl_mesh_free(small);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(owned_small_and_huge),
        cmocka_unit_test(reserve_keeps_nodes),
        cmocka_unit_test(append_block),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
