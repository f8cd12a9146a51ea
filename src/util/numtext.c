/* Decimal text of a float, exact with integer arithmetic.
 *
 * Why it is exact: a float is m * 2^q with m < 2^24, and 10^k = 5^k * 2^k with 5^k < 2^29
 * for k <= 12, so x * 10^k (k <= 12) has a significand below 2^53: the double product is
 * the exact value, its integer part and fraction are exact, and the rounding decided on
 * them is the one the exact decimal expansion gives. Large values are split into their
 * whole part (an integer below 2^63) and fraction, both exact. Outside these ranges, and for
 * doubles that are not floats, printf writes the number. */
#include "util/numtext.h"

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

static const double pow10d[] = {1, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12};
static const uint64_t pow10u[] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000, 100000000, 1000000000};
const char numtext_pairs[] = "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
                             "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
                             "8081828384858687888990919293949596979899";

/* floor(log10(x)) or one less, from x's binary exponent (x a positive normal double). */
static int decimal_exponent_guess(double x) {
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    int e2 = (int)((bits >> 52) & 0x7ff) - 1023; /* 2^e2 <= x < 2^(e2+1) */
    return (e2 * 78913) >> 18;                   /* floor(e2 * log10(2)), exact for |e2| < 2^11 */
}

/* x (positive, a float's value) rounded to prec significant digits, ties to even: *n has
 * exactly prec digits and x ~ n * 10^(*exp - prec + 1). False when x is out of the exact range. */
static inline __attribute__((always_inline)) bool round_sig(double x, int prec, uint64_t *n, int *exp) {
    int E = decimal_exponent_guess(x);
    int k = prec - 1 - E;
    if (k >= 1 && k <= 12) { /* the writers' case, without a branch on the digits: */
        int up = x * pow10d[k] >= pow10d[prec]; /* floor(log10 x) is E or E + 1 */
        double y = x * pow10d[k - up];          /* exact (see the top) */
        uint64_t q = (uint64_t)y;
        double fr = y - (double)q;
        q += (uint64_t)((fr > 0.5) | ((fr == 0.5) & (int)(q & 1)));
        E += up;
        if (q == pow10u[prec]) q = pow10u[prec - 1], E++; /* 9.999995 -> 10.0000 */
        *n = q, *exp = E;
        return true;
    }
    for (int tries = 0; tries < 3; tries++) {
        int k = prec - 1 - E;
        uint64_t q;
        if (k > 12) return false;
        if (k >= 0) {
            double y = x * pow10d[k]; /* exact (see the top) */
            if (y < pow10d[prec - 1]) {
                E--;
                continue;
            }
            if (y >= pow10d[prec]) {
                E++;
                continue;
            }
            q = (uint64_t)y;
            double fr = y - (double)q;
            if (fr > 0.5 || (fr == 0.5 && (q & 1))) q++;
        } else {
            if (-k > 9 || x >= 0x1p63) return false;
            double whole = floor(x);
            uint64_t w = (uint64_t)whole, d = pow10u[-k];
            q = w / d;
            if (q < pow10u[prec - 1]) {
                E--;
                continue;
            }
            if (q >= pow10u[prec]) {
                E++;
                continue;
            }
            double rest = (double)(w % d) + (x - whole); /* below 2^30 plus a fraction: exact */
            double half = 0.5 * (double)d;
            if (rest > half || (rest == half && (q & 1))) q++;
        }
        if (q == pow10u[prec]) q = pow10u[prec - 1], E++; /* 9.999995 -> 10.0000 */
        *n = q, *exp = E;
        return true;
    }
    return false;
}

#ifdef NUMTEXT_WORDS
/* n < 1000 as three ASCII digits, the first in the low byte: %.6g's six digits are two of
 * these, two loads where numtext_word8's three rounds of multiplies are a longer chain. */
#define NT_E(n) ((uint32_t)('0' + (n) / 100) | (uint32_t)('0' + (n) / 10 % 10) << 8 | (uint32_t)('0' + (n) % 10) << 16)
#define NT_R10(n) NT_E(n), NT_E(n + 1), NT_E(n + 2), NT_E(n + 3), NT_E(n + 4), NT_E(n + 5), NT_E(n + 6), NT_E(n + 7), \
                  NT_E(n + 8), NT_E(n + 9)
#define NT_R100(n) NT_R10(n), NT_R10(n + 10), NT_R10(n + 20), NT_R10(n + 30), NT_R10(n + 40), NT_R10(n + 50), \
                   NT_R10(n + 60), NT_R10(n + 70), NT_R10(n + 80), NT_R10(n + 90)
static const uint32_t thousands[1000] = {NT_R100(0),   NT_R100(100), NT_R100(200), NT_R100(300), NT_R100(400),
                                         NT_R100(500), NT_R100(600), NT_R100(700), NT_R100(800), NT_R100(900)};

/* q has exactly prec <= 8 digits, x = q * 10^(X - prec + 1). */
static inline __attribute__((always_inline)) char *g_text(char *p, uint32_t q, int prec, int X) {
    uint64_t d = prec == 6 ? thousands[q / 1000] | (uint64_t)thousands[q % 1000] << 24
                           : numtext_word8(q) >> (8 * (8 - prec)); /* the prec digits */
    int nd = numtext_significant(d, prec);              /* %g drops trailing zeros */
    if (X < -4 || X >= prec) {                   /* d.ddde+XX */
        uint64_t first = (d & 0xff) | ((uint64_t)'.' << 8), rest = d >> 8;
        memcpy(p, &first, 8), memcpy(p + 2, &rest, 8);
        p += nd > 1 ? nd + 1 : 1;
        *p++ = 'e';
        *p++ = X < 0 ? '-' : '+';
        unsigned a = (unsigned)(X < 0 ? -X : X);
        if (a >= 100) *p++ = (char)('0' + a / 100), a %= 100;
        memcpy(p, numtext_pairs + 2 * a, 2);
        return p + 2;
    }
    if (X < 0) { /* 0.000ddd */
        memcpy(p, "0.000000", 8);
        memcpy(p + 1 - X, &d, 8);
        return p + 1 - X + nd;
    }
    int whole = X + 1; /* <= prec <= 8 */
    if (whole == prec) { /* a whole number: no point, and its zeros stay */
        memcpy(p, &d, 8);
        return p + prec;
    }
    uint64_t head = (d & ((1ull << (8 * whole)) - 1)) | ((uint64_t)'.' << (8 * whole)), tail = d >> (8 * whole);
    memcpy(p, &head, 8), memcpy(p + whole + 1, &tail, 8);
    return p + (nd > whole ? nd + 1 : whole);
}
#endif

/* end follows digits with a point among them: the fraction's trailing zeros and then a
 * bare point dropped, as %g does. */
static inline char *trim_zeros(char *end) {
    while (end[-1] == '0') end--;
    return end[-1] == '.' ? end - 1 : end;
}

char *numtext_g(char *p, double x, int prec) {
    if (prec == 0) prec = 1; /* as printf */
    if (!isfinite(x) || prec < 0 || prec > 9 || (double)(float)x != x) return p + sprintf(p, "%.*g", prec, x);
    if (signbit(x)) *p++ = '-', x = -x;
    if (x == 0) {
        *p++ = '0';
        return p;
    }
    uint64_t n;
    int X;
    if (!round_sig(x, prec, &n, &X)) return p + sprintf(p, "%.*g", prec, x);
    uint32_t q = (uint32_t)n;
#ifdef NUMTEXT_WORDS
    if (prec <= 8) return g_text(p, q, prec, X);
#endif
    /* prec 9 (or a big-endian machine): all prec digits written, then %g's trailing zeros
     * (and a bare point) dropped as characters */
    if (X < -4 || X >= prec) { /* d.ddde+XX */
        numtext_digits(p + 1 + prec, q, prec); /* then the first digit moved before the point */
        p[0] = p[1], p[1] = '.';
        p = trim_zeros(p + 1 + prec);
        *p++ = 'e';
        *p++ = X < 0 ? '-' : '+';
        unsigned a = (unsigned)(X < 0 ? -X : X);
        if (a >= 100) *p++ = (char)('0' + a / 100), a %= 100;
        memcpy(p, numtext_pairs + 2 * a, 2);
        return p + 2;
    }
    if (X < 0) { /* 0.000ddd */
        memcpy(p, "0.000", 5); /* "0." and the zeros before the digits (X >= -4: at most 3) */
        p += 1 - X;
        numtext_digits(p + prec, q, prec);
        return trim_zeros(p + prec);
    }
    int whole = X + 1; /* <= prec */
    if (whole == prec) { /* a whole number: no point, and its zeros stay */
        numtext_digits(p + prec, q, prec);
        return p + prec;
    }
    numtext_digits(p + 1 + prec, q, prec); /* then the whole part moved down before the point */
    for (int i = 0; i < whole; i++) p[i] = p[i + 1];
    p[whole] = '.';
    return trim_zeros(p + 1 + prec);
}

char *numtext_g6(char *p, float f) {
#ifdef NUMTEXT_WORDS
    double x = fabs((double)f);
    uint64_t n;
    int X;
    /* round_sig and g_text inlined with prec a constant: the fast case's branches fold */
    if (x != 0 && isfinite(x) && round_sig(x, 6, &n, &X)) {
        *p = '-';
        return g_text(p + (signbit(f) != 0), (uint32_t)n, 6, X);
    }
#endif
    return numtext_g(p, f, 6);
}

char *numtext_int(char *p, long long v) {
    unsigned long long u = (unsigned long long)v;
    if (v < 0) *p++ = '-', u = 0 - u;
    if (u < 10) {
        *p = (char)('0' + u);
        return p + 1;
    }
#ifdef NUMTEXT_WORDS
    if (u < 100000000) { /* one word, stored once; its leading zeros skipped */
        uint64_t d = numtext_word8((uint32_t)u);
        int lead = __builtin_ctzll(d ^ 0x3030303030303030ull) / 8;
        d >>= 8 * lead;
        memcpy(p, &d, 8);
        return p + 8 - lead;
    }
#endif
    if (u <= UINT32_MAX) { /* in place, two digits at a time */
        int n = numtext_ndigits((uint32_t)u);
        numtext_digits(p + n, (uint32_t)u, n);
        return p + n;
    }
    char d[24], *end = d + sizeof d, *q = end;
    do *--q = (char)('0' + u % 10), u /= 10;
    while (u);
    memcpy(p, q, (size_t)(end - q));
    return p + (end - q);
}
