/* The readers' number parser (number.h). */
#include "util/number.h"

#include <math.h>
#include <stdio.h>
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

void number_write(char *buf, size_t n, double v) {
    if (v == (double)(long long)v && v > -1e15 && v < 1e15) {
        snprintf(buf, n, "%.0f", v == 0 ? 0.0 : v); /* -0 as 0 */
        return;
    }
    for (int prec = 1; prec <= 17; prec++) {
        snprintf(buf, n, "%.*g", prec, v);
        if (strtod(buf, NULL) == v) return;
    }
}
