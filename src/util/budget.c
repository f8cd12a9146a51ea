/* The shared memory budget (--max-memory): counting, refusing, releasing. */
#include "util/budget.h"
#include "util/parallel.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

/* A cgroup's limit in bytes from its file ("max" or a huge number: none, UINT64_MAX). */
static uint64_t cgroup_file(const char *dir, const char *sub, const char *name) {
    char path[3 * 4096]; /* dir, sub and name, each at most a line of /proc/self/cgroup */
    snprintf(path, sizeof path, "%s%s/%s", dir, sub, name);
    FILE *f = fopen(path, "re");
    if (!f) return UINT64_MAX;
    unsigned long long v;
    int got = fscanf(f, "%llu", &v);
    fclose(f);
    return got == 1 && v < (1ull << 62) ? (uint64_t)v : UINT64_MAX;
}

/* The smallest memory limit of the cgroup at sub (a path from /proc/self/cgroup) and of its
 * parents, whose limits hold for it too. */
static uint64_t cgroup_chain(const char *dir, char *sub, const char *name) {
    uint64_t least = UINT64_MAX;
    for (;;) {
        uint64_t v = cgroup_file(dir, sub, name);
        if (v < least) least = v;
        char *slash = strrchr(sub, '/');
        if (!slash) break;
        *slash = 0;
    }
    return least;
}

uint64_t budget_cgroup_limit(const char *proc_cgroup, const char *sys_root, const char **which) {
    FILE *f = fopen(proc_cgroup, "re");
    if (!f) return UINT64_MAX;
    char line[4096], v2[4096], v2u[4096], v1[4096];
    snprintf(v2, sizeof v2, "%s", sys_root);
    snprintf(v2u, sizeof v2u, "%s/unified", sys_root); /* v2 beside v1 (a hybrid mount) */
    snprintf(v1, sizeof v1, "%s/memory", sys_root);
    uint64_t least = UINT64_MAX;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = 0;
        char *c1 = strchr(line, ':'), *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
        if (!c2) continue;
        *c2 = 0;
        const char *ctrl = c1 + 1;
        for (int hybrid = 0; hybrid < 2; hybrid++) {
            const char *name, *dir;
            if (!*ctrl && line[0] == '0') dir = hybrid ? v2u : v2, name = "memory.max";
            else if (strstr(ctrl, "memory") && !hybrid) dir = v1, name = "memory.limit_in_bytes";
            else continue;
            char sub[4096];
            snprintf(sub, sizeof sub, "%s", c2 + 1);
            uint64_t v = cgroup_chain(dir, sub, name);
            if (v < least) {
                least = v;
                if (which) *which = !strcmp(name, "memory.max") ? "the cgroup's memory.max" : "the cgroup's memory.limit_in_bytes";
            }
        }
    }
    fclose(f);
    return least;
}

uint64_t budget_default_why(const char **why) {
    const char *which = "the machine's memory";
    long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    uint64_t least = pages > 0 && size > 0 ? (uint64_t)pages * (uint64_t)size : (8ull << 30);
    struct rlimit rl;
    /* the address space holds more than memory: the code, and each thread's stack and malloc
     * arena (8 + 64 MB), reserved whether used or not */
    uint64_t reserved = (192ull << 20) + (uint64_t)par_threads(0) * (72ull << 20); /* threads are at most that */
    if (!getrlimit(RLIMIT_AS, &rl) && rl.rlim_cur != RLIM_INFINITY) {
        uint64_t as = rl.rlim_cur > reserved ? rl.rlim_cur - reserved : (16ull << 20);
        if (as < least) least = as, which = "RLIMIT_AS, the address space (ulimit)";
    }
    if (!getrlimit(RLIMIT_DATA, &rl) && rl.rlim_cur != RLIM_INFINITY && rl.rlim_cur < least)
        least = rl.rlim_cur, which = "RLIMIT_DATA, the data segment (ulimit)";
    const char *cg = NULL;
    uint64_t c = budget_cgroup_limit("/proc/self/cgroup", "/sys/fs/cgroup", &cg);
    if (c < least) least = c, which = cg;
    uint64_t half = least / 2;
    if (half > (16ull << 30)) half = 16ull << 30, which = "the cap of 16 GiB";
    if (why) *why = which;
    return half;
}

uint64_t budget_default_limit(void) { return budget_default_why(NULL); }
void budget_init(Budget *b, uint64_t limit) {
    atomic_init(&b->used, 0);
    atomic_init(&b->peak, 0);
    atomic_init(&b->refused, 0);
    b->limit = limit ? limit : budget_default_limit();
}

Budget *budget_use(Budget *own, uint64_t limit, Budget *shared) {
    budget_init(own, limit ? limit : shared ? shared->limit : 0);
    return shared ? shared : own;
}

bool budget_charge(Budget *b, uint64_t bytes) {
    if (!b || !bytes) return true;
    if (bytes > b->limit) { /* and so never added, even for a moment, to what other threads see */
        uint64_t none = 0;
        atomic_compare_exchange_strong(&b->refused, &none, bytes);
        return false;
    }
    uint64_t now = atomic_fetch_add(&b->used, bytes) + bytes;
    if (now > b->limit || now < bytes) {
        atomic_fetch_sub(&b->used, bytes);
        uint64_t none = 0;
        atomic_compare_exchange_strong(&b->refused, &none, bytes);
        return false;
    }
    uint64_t peak = atomic_load(&b->peak);
    while (now > peak && !atomic_compare_exchange_weak(&b->peak, &peak, now)) {
    }
    return true;
}

void budget_release(Budget *b, uint64_t bytes) {
    if (b && bytes) atomic_fetch_sub(&b->used, bytes);
}

bool budget_resize(Budget *b, uint64_t old_bytes, uint64_t new_bytes) {
    if (new_bytes >= old_bytes) return budget_charge(b, new_bytes - old_bytes);
    budget_release(b, old_bytes - new_bytes);
    return true;
}

/* The public face (sylva.h): a budget the caller shares between engines. */
Budget *syl_budget_new(uint64_t max_bytes) {
    Budget *b = malloc(sizeof *b);
    if (b) budget_init(b, max_bytes);
    return b;
}

void syl_budget_free(Budget *b) { free(b); }
uint64_t syl_budget_used(const Budget *b) { return b ? atomic_load(&((Budget *)b)->used) : 0; }
uint64_t syl_budget_limit(const Budget *b) { return b ? b->limit : 0; }
