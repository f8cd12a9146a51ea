/* The allocators under requests that do not fit: util/array.h and util/arena.h must fail
 * cleanly (false or NULL, or a jump to the arena's target), never wrap, loop or abort. */
#include <limits.h>
#include <stdint.h>

#include "unit.h"

#include "util/arena.h"
#include "util/array.h"

static void array_refuses_more_than_half_of_size_max(void **state) {
    (void)state;
    char *a = NULL;
    size_t cap = 0;
    /* one byte per element: the doubling loop used to spin forever past SIZE_MAX / 2 */
    assert_false(array_reserve(&a, &cap, SIZE_MAX / 2 + 1, 1));
    assert_null(a);
    assert_int_equal(cap, 0);
    assert_false(array_reserve(&a, &cap, SIZE_MAX, 1));
}

static void array_refuses_a_byte_count_that_wraps(void **state) {
    (void)state;
    double *a = NULL;
    size_t cap = 0;
    /* 2^61 doubles are 2^64 bytes: c * elem wrapped to 0 and realloc "succeeded" */
    assert_false(array_reserve(&a, &cap, (size_t)1 << 61, sizeof *a));
    assert_false(array_reserve(&a, &cap, SIZE_MAX / sizeof *a + 1, sizeof *a));
    assert_int_equal(cap, 0);
    /* and the array still grows as before afterwards, keeping what it holds */
    assert_true(array_reserve(&a, &cap, 10, sizeof *a));
    assert_int_equal(cap, 1024);
    a[9] = 2.5;
    assert_true(array_reserve(&a, &cap, 3000, sizeof *a));
    assert_int_equal(cap, 4096);
    assert_true(a[9] == 2.5);
    free(a);
}

static void array_near_the_limit_does_not_wrap(void **state) {
    (void)state;
    /* doubling from a large capacity would pass SIZE_MAX: the request itself is taken (and
     * fails for want of memory, not by wrapping into a small block) */
    char *a = NULL;
    size_t cap = SIZE_MAX / 2 + 2; /* pretend: only the arithmetic runs, realloc refuses */
    assert_false(array_reserve(&a, &cap, SIZE_MAX - 1, 1));
    assert_int_equal(cap, SIZE_MAX / 2 + 2);
}

static void arena_returns_null_without_a_target(void **state) {
    (void)state;
    Arena a = {0};
    assert_null(arena_alloc(&a, SIZE_MAX));      /* size + 15 wrapped to a tiny block */
    assert_null(arena_alloc(&a, SIZE_MAX - 15));
    assert_null(arena_alloc(&a, SIZE_MAX / 2 + 1));
    assert_null(arena_strndup(&a, "x", SIZE_MAX));
    char *s = arena_strndup(&a, "leaf", 4); /* the arena still works */
    assert_string_equal(s, "leaf");
    assert_string_equal(arena_printf(&a, "%d-%s", 7, s), "7-leaf");
    arena_free(&a);
}

static void arena_vector_stops_at_int_max(void **state) {
    (void)state;
    Arena a = {0};
    int cap = INT_MAX / 2 + 1; /* doubling would overflow the int capacity */
    int n = cap;
    char *v = (char *)"not grown"; /* never read: growth fails before copying */
    assert_null(VEC_PUSH(&a, v, n, cap));
    assert_null(v);
    assert_int_equal(n, INT_MAX / 2 + 1);
    assert_int_equal(cap, INT_MAX / 2 + 1);
    /* elements so large that cap * 2 * elem wraps size_t */
    int bcap = 4;
    assert_null(arena_vec_grow(&a, NULL, &bcap, SIZE_MAX / 4));
    assert_int_equal(bcap, 4);
    /* and a normal vector grows 4, 8, 16 keeping its contents */
    int *iv = NULL, in = 0, icap = 0;
    for (int i = 0; i < 100; i++) *VEC_PUSH(&a, iv, in, icap) = i * i;
    assert_int_equal(in, 100);
    assert_int_equal(icap, 128);
    assert_int_equal(iv[99], 99 * 99);
    arena_free(&a);
}

static void arena_jumps_to_its_target(void **state) {
    (void)state;
    Arena *a = calloc(1, sizeof *a); /* off the stack: it is read after longjmp */
    jmp_buf *jb = malloc(sizeof *jb);
    a->oom = jb;
    assert_non_null(arena_alloc(a, 100));
    int *reached = calloc(1, sizeof *reached);
    if (!setjmp(*jb)) {
        arena_alloc(a, SIZE_MAX - 8);
        *reached = 1; /* not reached: the arena jumped */
    }
    assert_int_equal(*reached, 0);
    assert_true(a->used >= 100);
    arena_free(a);
    free(reached);
    free(jb);
    free(a);
}

static void compile_after_the_guards(void **state) {
    (void)state;
    /* the compiler runs with the arena's target set and clears it after: a program compiles
     * and derives as ever, twice in a row (no stale target) */
    for (int k = 0; k < 2; k++) {
        char *s = unit_derive("lsystem A {\n axiom F\n F -> F+F\n}\n", 2, 1);
        assert_non_null(s);
        assert_string_equal(s, "F+F+F+F");
        free(s);
    }
}

/* A fixed arena (util/arena.h): one block, the last array grown in place, one that is not
 * the last moved with its contents, given back only when last, NULL (never another block,
 * never a jump) when full. */
static void fixed_arena_grows_in_place_and_stops_when_full(void **state) {
    (void)state;
    jmp_buf target;
    Arena a = {.oom = &target}; /* (a full fixed arena must not jump) */
    assert_true(arena_fix(&a, 1)); /* rounded up to one 2 MB page */
    assert_false(arena_fix(&a, 1)); /* only on an empty arena */
    int *x = arena_take(&a, 100 * sizeof *x);
    assert_non_null(x);
    assert_int_equal((uintptr_t)x % 64, 0);
    for (int i = 0; i < 100; i++) x[i] = i;
    assert_ptr_equal(arena_resize(&a, x, 100 * sizeof *x, 1000 * sizeof *x), x); /* the last: in place */
    char *y = arena_take(&a, 10);
    assert_true(arena_holds(&a, y) && !arena_holds(&a, &a));
    int *x2 = arena_resize(&a, x, 1000 * sizeof *x, 2000 * sizeof *x); /* no longer last: moved */
    assert_non_null(x2);
    assert_true(x2 != x);
    for (int i = 0; i < 100; i++) assert_int_equal(x2[i], i);
    arena_pop(&a, y, 10); /* not the last: nothing */
    size_t used = a.used;
    arena_pop(&a, x2, 2000 * sizeof *x);
    assert_true(a.used < used);
    assert_ptr_equal(arena_take(&a, 8), x2); /* its room again */
    char *z = arena_take(&a, 1000);
    arena_trim(&a, x2, 8, 4); /* not the last: nothing */
    assert_ptr_equal(arena_take(&a, 1), z + 1024);
    arena_trim(&a, z + 1024, 1, 0);
    arena_trim(&a, z, 1000, 100); /* the last: its room past 100 bytes (128 rounded) given back */
    assert_ptr_equal(arena_take(&a, 1), z + 128);
    assert_null(arena_take(&a, 4 << 20));    /* full: NULL, no other block */
    assert_null(arena_take(&a, SIZE_MAX));
    assert_null(arena_resize(&a, y, 10, SIZE_MAX - 8));
    arena_free(&a);
    assert_false(a.fixed);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(array_refuses_more_than_half_of_size_max),
        cmocka_unit_test(array_refuses_a_byte_count_that_wraps),
        cmocka_unit_test(array_near_the_limit_does_not_wrap),
        cmocka_unit_test(arena_returns_null_without_a_target),
        cmocka_unit_test(arena_vector_stops_at_int_max),
        cmocka_unit_test(arena_jumps_to_its_target),
        cmocka_unit_test(fixed_arena_grows_in_place_and_stops_when_full),
        cmocka_unit_test(compile_after_the_guards),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
