/* The shared memory budget (--max-memory): counting, refusing, releasing. */
#include "util/budget.h"

#include <stdlib.h>
#include <unistd.h>

uint64_t budget_default_limit(void) {
    long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    uint64_t half = pages > 0 && size > 0 ? (uint64_t)pages * (uint64_t)size / 2 : (4ull << 30);
    return half < (16ull << 30) ? half : (16ull << 30);
}

void budget_init(Budget *b, uint64_t limit) {
    atomic_init(&b->used, 0);
    atomic_init(&b->peak, 0);
    atomic_init(&b->refused, 0);
    b->limit = limit ? limit : budget_default_limit();
}

bool budget_charge(Budget *b, uint64_t bytes) {
    if (!b || !bytes) return true;
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
