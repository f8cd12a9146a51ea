/* A number written in a file (a DEM's token, a table's field): the one parser the readers
 * share, so that they take the same spellings. */
#ifndef SYL_UTIL_NUMBER_H
#define SYL_UTIL_NUMBER_H
#include <stdbool.h>
#include <stddef.h>

/* s[0..n) as a finite number, strtod's syntax: true only when all n bytes are the number
 * (no blank before it, none after; at most 63 bytes). NaN and infinities are refused. */
bool number_read(const char *s, size_t n, double *out);

/* v written so that strtod reads it back exactly, in as few digits as that takes (whole
 * numbers below 1e15 without a point; -0 as 0). */
void number_write(char *buf, size_t n, double v);

#endif
