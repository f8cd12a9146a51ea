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

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ && defined(__GNUC__)
#define NUMTEXT_WORDS 1
/* The eight decimal digits of v < 10^8 (zero-padded) as ASCII in one word, the first digit in
 * its lowest byte: memory order once stored. Halves, then hundreds, then tens, each split in
 * every lane at once by a multiply and a shift (exact for these ranges). Text is built in a
 * register and stored once: reading back digits just stored stalls store forwarding. */
static inline uint64_t numtext_word8(uint32_t v) {
    uint64_t x = (uint64_t)(v / 10000) | ((uint64_t)(v % 10000) << 32);
    uint64_t h = ((x * 10486) >> 20) & 0x0000007F0000007Full; /* / 100, lanes < 10^4 */
    x = h | ((x - h * 100) << 16);
    h = ((x * 103) >> 10) & 0x000F000F000F000Full; /* / 10, lanes < 100 */
    x = h | ((x - h * 10) << 8);
    return x + 0x3030303030303030ull;
}

/* How many of the n digits in d (first in the low byte) are left without the trailing zeros
 * (not all of them zero). */
static inline int numtext_significant(uint64_t d, int n) {
    uint64_t z = (d ^ 0x3030303030303030ull) & (n >= 8 ? ~0ull : (1ull << (8 * n)) - 1);
    return (63 - __builtin_clzll(z)) / 8 + 1;
}
#endif

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

/* numtext_g(p, x, 6), the writers' case, a little faster. */
char *numtext_g6(char *p, float x);

/* v in decimal, as "%lld" writes it; returns the end (at most 20 bytes, no terminating zero). */
char *numtext_int(char *p, long long v);

#endif
