/* Growable arrays: the one overflow-checked reserve. */
#include "util/array.h"

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

bool array_reserve(void *arrp, size_t *cap, size_t need, size_t elem) {
    void **arr = arrp;
    if (need <= *cap) return true;
    /* no object is larger than PTRDIFF_MAX bytes (malloc refuses them too): checking that
     * first keeps c * elem from wrapping */
    if (!elem || need > PTRDIFF_MAX / elem) return false;
    size_t c = *cap ? *cap : 1024;
    while (c < need) c *= 2; /* cannot wrap: c < need <= PTRDIFF_MAX, so 2c <= SIZE_MAX */
    if (c > PTRDIFF_MAX / elem) c = need;
    void *p = realloc(*arr, c * elem);
    if (!p) return false;
    *arr = p;
    *cap = c;
    return true;
}
