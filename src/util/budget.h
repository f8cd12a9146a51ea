/* A memory budget: the one --max-memory of a run, shared by every engine that holds large
 * arrays (derivation strings, growth, scenes, meshes, pictures). Engines charge an array
 * when it grows (per reallocation, never per element) and release it when freed; a charge
 * beyond the limit is refused and the engine stops with SYL_ELIMIT before it allocates.
 * Charges are atomic: threads may share one budget. */
#ifndef SYL_BUDGET_H
#define SYL_BUDGET_H
#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

struct SylBudget {
    _Atomic uint64_t used;  /* bytes charged now */
    _Atomic uint64_t peak;  /* the most ever charged */
    uint64_t limit;         /* bytes */
    _Atomic uint64_t refused; /* the size of the first charge refused; 0: none */
};
typedef struct SylBudget Budget;

/* The default of --max-memory: half the smallest of the machine's memory, RLIMIT_AS (less
 * 192 MB and 72 MB a core of code, stacks and malloc arenas), RLIMIT_DATA and the cgroup's
 * memory limit (v2 memory.max or v1 memory.limit_in_bytes, its
 * own or a parent's), at most 16 GiB; the half left covers what the budget does not count.
 * budget_default_why also says which of them set it. */
uint64_t budget_default_limit(void);
uint64_t budget_default_why(const char **why);
/* The smallest cgroup memory limit over the process's cgroups listed in proc_cgroup (the form
 * of /proc/self/cgroup) and their parents, read under sys_root (/sys/fs/cgroup: v2 memory.max
 * there or under unified/, v1 memory.limit_in_bytes under memory/); UINT64_MAX for none.
 * *which (when not NULL) names the file that set it. */
uint64_t budget_cgroup_limit(const char *proc_cgroup, const char *sys_root, const char **which);
/* A budget of limit bytes (0: the default), nothing charged. */
void budget_init(Budget *b, uint64_t limit);
/* The budget an engine charges: shared when the caller gives one (own is then set to its
 * limit without asking the system again: a scene of 10,000 plants asked 30,000 times), else
 * own, of limit bytes (0: the default). */
Budget *budget_use(Budget *own, uint64_t limit, Budget *shared);
/* Count bytes more; false (nothing counted, the refusal remembered) when the total would pass
 * the limit. b NULL: always true. */
bool budget_charge(Budget *b, uint64_t bytes);
void budget_release(Budget *b, uint64_t bytes);
/* Charge or release the difference when an array goes from old_bytes to new_bytes. */
bool budget_resize(Budget *b, uint64_t old_bytes, uint64_t new_bytes);
/* The public face, declared again in sylva.h. */
Budget *syl_budget_new(uint64_t max_bytes);
void syl_budget_free(Budget *b);
uint64_t syl_budget_used(const Budget *b);
uint64_t syl_budget_limit(const Budget *b);
static inline uint64_t budget_limit_mb(const Budget *b) { return b ? b->limit >> 20 : 0; }

#endif
