/* Big arrays in whole 2 MB pages, aligned and marked for transparent huge pages. */
#include "util/pages.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#define HUGE_PAGE ((size_t)2 << 20)

static size_t mapped_bytes(size_t bytes) { return bytes < PAGES_BIG ? 0 : (bytes + HUGE_PAGE - 1) & ~(HUGE_PAGE - 1); }

static void *map_big(size_t bytes) {
    size_t len = mapped_bytes(bytes);
    char *p = mmap(NULL, len + HUGE_PAGE, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) return NULL;
    char *a = (char *)(((uintptr_t)p + HUGE_PAGE - 1) & ~(uintptr_t)(HUGE_PAGE - 1));
    if (a > p) munmap(p, (size_t)(a - p));
    if (a + len < p + len + HUGE_PAGE) munmap(a + len, (size_t)(p + len + HUGE_PAGE - (a + len)));
    madvise(a, len, MADV_HUGEPAGE); /* a hint; harmless where transparent huge pages are off */
    return a;
}

void pages_free(void *p, size_t bytes) {
    if (!p) return;
    if (mapped_bytes(bytes)) munmap(p, mapped_bytes(bytes));
    else free(p);
}

void *pages_grow(void *old, size_t old_bytes, size_t used, size_t bytes) {
    if (!mapped_bytes(bytes)) return realloc(old, bytes);
#ifdef MREMAP_MAYMOVE /* Linux */
    size_t om = mapped_bytes(old_bytes);
    if (old && om) { /* moving the pages costs no copy and keeps the hint */
        void *p = mremap(old, om, mapped_bytes(bytes), MREMAP_MAYMOVE);
        if (p != MAP_FAILED) return p;
    }
#endif
    void *p = map_big(bytes);
    if (!p) return NULL;
    if (used) memcpy(p, old, used);
    pages_free(old, old_bytes);
    return p;
}

size_t pages_shift_unit(size_t bytes) { return mapped_bytes(bytes) ? HUGE_PAGE : 1; }

void *pages_grow_front(void *old, size_t old_bytes, size_t used, size_t shift, size_t bytes, void *donor,
                       size_t donor_bytes) {
    if (!mapped_bytes(bytes)) {
        char *p = realloc(old, bytes);
        if (p && used) memmove(p + shift, p, used);
        if (p) pages_free(donor, donor_bytes);
        return p;
    }
    char *p = map_big(bytes);
    if (!p) return NULL;
    size_t om = mapped_bytes(old_bytes), move = (used + HUGE_PAGE - 1) & ~(HUGE_PAGE - 1);
#ifdef MREMAP_FIXED /* Linux: the pages change address, their contents stay where they are */
    if (om && used && shift % HUGE_PAGE == 0 &&
        mremap(old, move, move, MREMAP_MAYMOVE | MREMAP_FIXED, p + shift) != MAP_FAILED) {
        /* the old pages past the contents go to the front, which is undefined: those already
         * written (an in-place pass's input, read and done with) need no zeroing again there */
        size_t rest = om - move, dm = mapped_bytes(donor_bytes);
        if (rest && (rest > shift || mremap((char *)old + move, rest, rest, MREMAP_MAYMOVE | MREMAP_FIXED, p) == MAP_FAILED))
            rest = 0, munmap((char *)old + move, om - move);
        /* and so do the donor's, after them */
        if (dm && rest + dm <= shift && mremap(donor, dm, dm, MREMAP_MAYMOVE | MREMAP_FIXED, p + rest) != MAP_FAILED)
            return p;
        pages_free(donor, donor_bytes);
        return p;
    }
#endif
    if (used) memcpy(p + shift, old, used);
    pages_free(old, old_bytes);
    pages_free(donor, donor_bytes);
    return p;
}

void *pages_owned(size_t bytes, size_t huge_from) {
    if (bytes < huge_from) return malloc(bytes ? bytes : 1);
    size_t round = (bytes + HUGE_PAGE - 1) & ~(HUGE_PAGE - 1);
    void *p = aligned_alloc(HUGE_PAGE, round);
    if (p) madvise(p, round, MADV_HUGEPAGE);
    return p;
}

void *pages_alloc(size_t bytes) { return mapped_bytes(bytes) ? map_big(bytes) : calloc(1, bytes ? bytes : 1); }

static size_t sparse_bytes(size_t bytes) { return bytes < SPARSE_MIN ? 0 : (bytes + 4095) & ~(size_t)4095; }

void *pages_alloc_sparse(size_t bytes) {
    size_t len = sparse_bytes(bytes);
    if (!len) return calloc(1, bytes ? bytes : 1);
    void *p = mmap(NULL, len, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) return NULL;
    madvise(p, len, MADV_NOHUGEPAGE); /* a page written costs 4 KB, not 2 MB zeroed */
    return p;
}

void pages_free_sparse(void *p, size_t bytes) {
    if (!p) return;
    if (sparse_bytes(bytes)) munmap(p, sparse_bytes(bytes));
    else free(p);
}
