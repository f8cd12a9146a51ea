/* The default memory budget's cgroup limit, read from a fake /proc/self/cgroup and cgroup tree
 * (the layouts of cgroup v2, v1 and a hybrid mount), and the budget's counting. */
#include "unit.h"
#include "util/budget.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char root[64];

static void put(const char *rel, const char *text) {
    char path[512], dir[512];
    snprintf(path, sizeof path, "%s/%s", root, rel);
    snprintf(dir, sizeof dir, "%s", path);
    for (char *p = dir + strlen(root) + 1; (p = strchr(p, '/')); p++) {
        *p = 0;
        mkdir(dir, 0755);
        *p = '/';
    }
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static int setup(void **state) {
    (void)state;
    snprintf(root, sizeof root, "/tmp/sylva-cgroup-XXXXXX");
    return mkdtemp(root) ? 0 : -1;
}

static int teardown(void **state) {
    (void)state;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", root);
    return system(cmd) == 0 ? 0 : -1;
}

static uint64_t limit(const char **which) {
    char proc[512], sys[512];
    snprintf(proc, sizeof proc, "%s/proc-cgroup", root);
    snprintf(sys, sizeof sys, "%s/sys", root);
    return budget_cgroup_limit(proc, sys, which);
}

/* v2: the process's own group says "max", its parent 300 MiB: the parent's limit holds */
static void v2_parent_limit_holds(void **state) {
    (void)state;
    put("proc-cgroup", "0::/user/job\n");
    put("sys/user/job/memory.max", "max\n");
    put("sys/user/memory.max", "314572800\n");
    const char *which = NULL;
    assert_int_equal(limit(&which), 314572800);
    assert_string_equal(which, "the cgroup's memory.max");
}

/* v1: the memory controller's line, the smaller of the group's and its parent's */
static void v1_smallest_of_chain(void **state) {
    (void)state;
    put("proc-cgroup", "4:memory:/a/b\n1:cpu:/\n0::/\n");
    put("sys/memory/a/b/memory.limit_in_bytes", "104857600\n");
    put("sys/memory/a/memory.limit_in_bytes", "209715200\n");
    put("sys/memory/memory.limit_in_bytes", "9223372036854771712\n"); /* "no limit" in v1 */
    const char *which = NULL;
    assert_int_equal(limit(&which), 104857600);
    assert_string_equal(which, "the cgroup's memory.limit_in_bytes");
}

/* a hybrid mount: v2 lives under unified/, and a smaller limit there wins over v1's */
static void hybrid_unified(void **state) {
    (void)state;
    put("proc-cgroup", "4:memory:/x\n0::/y\n");
    put("sys/memory/x/memory.limit_in_bytes", "104857600\n");
    put("sys/unified/y/memory.max", "52428800\n");
    const char *which = NULL;
    assert_int_equal(limit(&which), 52428800);
    assert_string_equal(which, "the cgroup's memory.max");
}

static void no_cgroup_no_limit(void **state) {
    (void)state;
    char proc[512];
    snprintf(proc, sizeof proc, "%s/absent", root);
    assert_true(budget_cgroup_limit(proc, root, NULL) == UINT64_MAX);
    put("proc-cgroup", "0::/\n"); /* a group with no memory.max file anywhere */
    assert_true(limit(NULL) == UINT64_MAX);
}

static void charges_count_and_refuse(void **state) {
    (void)state;
    Budget b;
    budget_init(&b, 1000);
    assert_true(budget_charge(&b, 600));
    assert_false(budget_charge(&b, 500)); /* 1100 > 1000: refused, nothing counted */
    assert_int_equal(atomic_load(&b.used), 600);
    assert_int_equal(atomic_load(&b.refused), 500);
    budget_release(&b, 600);
    assert_true(budget_charge(&b, 1000));
    assert_int_equal(atomic_load(&b.peak), 1000);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(v2_parent_limit_holds, setup, teardown),
        cmocka_unit_test_setup_teardown(v1_smallest_of_chain, setup, teardown),
        cmocka_unit_test_setup_teardown(hybrid_unified, setup, teardown),
        cmocka_unit_test_setup_teardown(no_cgroup_no_limit, setup, teardown),
        cmocka_unit_test(charges_count_and_refuse),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
