/* Big arrays in whole 2 MB pages: one page fault fills 2 MB instead of 4 KB. */
#ifndef SYL_UTIL_PAGES_H
#define SYL_UTIL_PAGES_H
#include <stddef.h>

/* Arrays of PAGES_BIG bytes and more are mapped directly, aligned to 2 MB and marked for
 * transparent huge pages; smaller ones live in malloc. Whether an array is mapped follows
 * from its size alone, so the caller only keeps the size it asked for. */
enum { PAGES_BIG = 1 << 20 };

void *pages_alloc(size_t bytes);  /* zeroed when mapped; NULL when refused */
void pages_free(void *p, size_t bytes);
/* Grow an array of old_bytes (its first `used` bytes in use) to bytes; NULL if refused,
 * the old array then unchanged. */
void *pages_grow(void *old, size_t old_bytes, size_t used, size_t bytes);
/* Grow an array of old_bytes to bytes and move its first `used` bytes to offset `shift`
 * (shift + used <= bytes); NULL if refused, the old array then unchanged. When the array is
 * mapped and shift is a multiple of pages_shift_unit(bytes), whole pages are moved, not
 * copied. The bytes before shift are undefined. */
void *pages_grow_front(void *old, size_t old_bytes, size_t used, size_t shift, size_t bytes);
/* The shift that moves whole pages for an array of `bytes` (1: any shift copies). */
size_t pages_shift_unit(size_t bytes);

#endif
