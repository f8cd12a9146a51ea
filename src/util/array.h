/* Growable arrays kept with realloc: one rule for every module that keeps a count and a
 * capacity beside a pointer. */
#ifndef SYL_ARRAY_H
#define SYL_ARRAY_H
#include <stdbool.h>
#include <stddef.h>

/* Make *arrp (a pointer to the array pointer) hold at least need elements of elem bytes,
 * doubling from 1024; false (the array unchanged) when out of memory or when need * elem
 * does not fit in size_t. */
bool array_reserve(void *arrp, size_t *cap, size_t need, size_t elem);

#endif
