/* Numbers written as text at the speed of the disk: printf's %.Ng of a float, exact and
 * without printf (docs/mesh.md#number-text). */
#ifndef SYL_UTIL_NUMTEXT_H
#define SYL_UTIL_NUMTEXT_H

#include <stdint.h>
#include <string.h>

extern const char numtext_pairs[200]; /* "00" "01" ... "99" */

/* Exactly n digits of v (zero-padded on the left) so that they end at end, two at a time.
 * Written where they stay: copying digits once more costs a stalled load (store forwarding). */
static inline void numtext_digits(char *end, uint32_t v, int n) {
    for (; n >= 2; n -= 2) {
        end -= 2;
        memcpy(end, numtext_pairs + 2 * (v % 100), 2);
        v /= 100;
    }
    if (n) end[-1] = (char)('0' + v % 10);
}

/* How many digits v has (1 to 10). */
static inline int numtext_ndigits(uint32_t v) {
    int n = 1;
    for (uint32_t t = 10; n < 10 && v >= t; t *= 10) n++;
    return n;
}

/* Exactly what sprintf(p, "%.*g", prec, x) writes (glibc: the exact value rounded to prec
 * significant digits, ties to even; "-0", "nan", "inf" as printf spells them). Fast when x
 * is a float's value and 1 <= prec <= 9, the writers' case; otherwise printf itself.
 * Writes no terminating zero; returns the end (it may write scratch up to 32 bytes from p). */
char *numtext_g(char *p, double x, int prec);

/* v in decimal, as "%lld" writes it; returns the end (at most 20 bytes, no terminating zero). */
char *numtext_int(char *p, long long v);

#endif
