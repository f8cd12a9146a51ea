/* util/lazylib: a library bound on first use. Its functions come from the library (the same
 * addresses dlsym gives), and one that cannot be loaded reaches the program's handler with its
 * name and the loader's reason: the load never returns with a half-filled table. */
#include <dlfcn.h>
#include <setjmp.h>
#include <string.h>

#include "unit.h"
#include "util/lazylib.h"

static jmp_buf back;
static char seen_soname[256], seen_what[256];
static int seen;

static void missing_library(const char *soname, const char *what, const char *why) {
    snprintf(seen_soname, sizeof seen_soname, "%s", soname);
    snprintf(seen_what, sizeof seen_what, "%s", what);
    seen++;
    assert_non_null(why);
    longjmp(back, 1);
}

/* libm's cos, through the loader, is libm's cos. */
static void test_loads_functions(void **state) {
    (void)state;
    static const char *const names[] = {"cos", "sqrt"};
    LazyLib lib = {"libm.so.6", "cosines", names, 2, false};
    void *table[2] = {0};
    seen = 0;
    if (!setjmp(back)) lazy_lib_load(&lib, table);
    assert_int_equal(seen, 0);
    void *h = dlopen("libm.so.6", RTLD_NOW);
    assert_non_null(h);
    assert_ptr_equal(table[0], dlsym(h, "cos"));
    assert_ptr_equal(table[1], dlsym(h, "sqrt"));
    double (*c)(double) = (double (*)(double))table[0];
    assert_true(c(0.0) == 1.0);
    dlclose(h);
}

static void test_missing_library(void **state) {
    (void)state;
    static const char *const names[] = {"f"};
    LazyLib lib = {"libsylva-no-such-library.so.9", "a test", names, 1, false};
    void *table[1] = {0};
    seen = 0;
    if (!setjmp(back)) lazy_lib_load(&lib, table);
    assert_int_equal(seen, 1);
    assert_string_equal(seen_soname, "libsylva-no-such-library.so.9");
    assert_string_equal(seen_what, "a test");
}

static void test_missing_function(void **state) {
    (void)state;
    static const char *const names[] = {"cos", "syl_no_such_function"};
    LazyLib lib = {"libm.so.6", "a test", names, 2, false};
    void *table[2] = {0};
    seen = 0;
    if (!setjmp(back)) lazy_lib_load(&lib, table);
    assert_int_equal(seen, 1);
    seen = 0;
    if (!setjmp(back)) assert_null(lazy_lib_sym(&lib, "syl_no_such_variable"));
    assert_int_equal(seen, 1);
}

int main(void) {
    syl_missing_library_set(missing_library);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_loads_functions),
        cmocka_unit_test(test_missing_library),
        cmocka_unit_test(test_missing_function),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
