/* The readers' number parser (number.h). */
#include "util/number.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

bool number_read(const char *s, size_t n, double *out) {
    char buf[64];
    if (n == 0 || n >= sizeof buf || strchr(" \t\r\n\v\f", s[0])) return false; /* strtod would skip blanks */
    memcpy(buf, s, n);
    buf[n] = 0;
    char *e;
    *out = strtod(buf, &e);
    return *e == 0 && isfinite(*out);
}
