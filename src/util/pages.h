/* Big arrays in whole 2 MB pages: one page fault fills 2 MB instead of 4 KB. */
#ifndef SYL_UTIL_PAGES_H
#define SYL_UTIL_PAGES_H
#include <stddef.h>

/* Arrays of PAGES_BIG bytes and more are mapped directly, aligned to 2 MB and marked for
 * transparent huge pages; smaller ones live in malloc. Whether an array is mapped follows
 * from its size alone, so the caller only keeps the size it asked for. */
enum { PAGES_BIG = 1 << 20, PAGES_HUGE = 2 << 20 /* the huge page PAGES_BIG arrays are mapped in */ };

void *pages_alloc(size_t bytes);  /* zeroed when mapped; NULL when refused */
/* Zeroed, and for SPARSE_MIN bytes and more mapped in small pages, never huge ones: a page
 * exists only once written, and one only read is the shared zero page. For tables indexed by
 * module code of which a program uses a few entries (a rule table's dispatch). */
enum { SPARSE_MIN = 1 << 16 };
void *pages_alloc_sparse(size_t bytes);
void pages_free_sparse(void *p, size_t bytes);
void pages_free(void *p, size_t bytes);
/* Grow an array of old_bytes (its first `used` bytes in use) to bytes; NULL if refused,
 * the old array then unchanged. */
void *pages_grow(void *old, size_t old_bytes, size_t used, size_t bytes);
/* Grow an array of old_bytes to bytes and move its first `used` bytes to offset `shift`
 * (shift + used <= bytes); NULL if refused, the old array then unchanged. When the array is
 * mapped and shift is a multiple of pages_shift_unit(bytes), whole pages are moved, not
 * copied. The bytes before shift are undefined: the old array's pages past its contents, and
 * then those of donor (an array of donor_bytes, or NULL, freed by a call that succeeds), go
 * there when they fit, so that pages already written are not zeroed again when written. */
void *pages_grow_front(void *old, size_t old_bytes, size_t used, size_t shift, size_t bytes, void *donor,
                       size_t donor_bytes);
/* Memory that free() releases (and realloc grows), for an array that will mostly be written:
 * from huge_from bytes on, whole 2 MB pages, aligned and marked for transparent huge pages.
 * On a virtual machine a 4 KB page's first write costs about 18 us and a 2 MB page's 0.2 ms
 * (zeroing included), so from about 48 KB written one huge page is cheaper (docs/architecture.md,
 * "Memory"). But a huge page is resident whole: arrays that live on (a skeleton's, a mesh's:
 * a forest keeps many small ones) take it from PAGES_OWNED_KEPT, a generator's scratch arrays
 * from PAGES_OWNED_SCRATCH. NULL when refused; not zeroed. */
enum { PAGES_OWNED_SCRATCH = 1 << 16, PAGES_OWNED_KEPT = 1 << 19 };
void *pages_owned(size_t bytes, size_t huge_from);
/* The shift that moves whole pages for an array of `bytes` (1: any shift copies). */
size_t pages_shift_unit(size_t bytes);

#endif
