#include "array.h"

#include <stdlib.h>

bool array_reserve(void *arrp, size_t *cap, size_t need, size_t elem) {
    void **arr = arrp;
    if (need <= *cap) return true;
    size_t c = *cap ? *cap * 2 : 1024;
    while (c < need) c *= 2;
    void *p = realloc(*arr, c * elem);
    if (!p) return false;
    *arr = p;
    *cap = c;
    return true;
}
