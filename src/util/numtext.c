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
static const char pairs[] = "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
                            "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
                            "8081828384858687888990919293949596979899";

/* v's digits, written backwards so they end at end; returns how many. */
static int digits_before(char *end, uint64_t v) {
    char *q = end;
    while (v >= 1u << 31) {
        unsigned r = (unsigned)(v % 100);
        v /= 100;
        q -= 2;
        memcpy(q, pairs + 2 * r, 2);
    }
    uint32_t w = (uint32_t)v; /* 32-bit division: cheaper */
    while (w >= 100) {
        unsigned r = w % 100;
        w /= 100;
        q -= 2;
        memcpy(q, pairs + 2 * r, 2);
    }
    if (w >= 10) q -= 2, memcpy(q, pairs + 2 * w, 2);
    else *--q = (char)('0' + w);
    return (int)(end - q);
}

/* floor(log10(x)) or one less, from x's binary exponent (x a positive normal double). */
static int decimal_exponent_guess(double x) {
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    int e2 = (int)((bits >> 52) & 0x7ff) - 1023; /* 2^e2 <= x < 2^(e2+1) */
    return (e2 * 78913) >> 18;                   /* floor(e2 * log10(2)), exact for |e2| < 2^11 */
}

/* x (positive, a float's value) rounded to prec significant digits, ties to even: *n has
 * exactly prec digits and x ~ n * 10^(*exp - prec + 1). False when x is out of the exact range. */
static bool round_sig(double x, int prec, uint64_t *n, int *exp) {
    int E = decimal_exponent_guess(x);
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
    char d[24];
    digits_before(d + prec, n); /* exactly prec digits */
    int nd = prec;
    while (nd > 1 && d[nd - 1] == '0') nd--; /* %g drops trailing zeros */
    if (X < -4 || X >= prec) {               /* d.ddde+XX */
        *p++ = d[0];
        if (nd > 1) {
            *p++ = '.';
            memcpy(p, d + 1, (size_t)nd - 1);
            p += nd - 1;
        }
        *p++ = 'e';
        *p++ = X < 0 ? '-' : '+';
        unsigned a = (unsigned)(X < 0 ? -X : X);
        if (a >= 100) *p++ = (char)('0' + a / 100), a %= 100;
        memcpy(p, pairs + 2 * a, 2);
        return p + 2;
    }
    if (X < 0) { /* 0.000ddd */
        *p++ = '0', *p++ = '.';
        for (int i = -1; i > X; i--) *p++ = '0';
        memcpy(p, d, (size_t)nd);
        return p + nd;
    }
    int whole = X + 1; /* <= prec */
    memcpy(p, d, (size_t)whole);
    p += whole;
    if (nd > whole) {
        *p++ = '.';
        memcpy(p, d + whole, (size_t)(nd - whole));
        p += nd - whole;
    }
    return p;
}

/* thresholds[e + 4]: the doubles nearest 10^e, e = -4..9 (what the short form compares with) */
static const double thresholds[] = {1e-4, 1e-3, 1e-2, 1e-1, 1, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};

char *numtext_short(char *p, float xf, int sig) {
    double x = xf;
    if (!(x != 0 && isfinite(x))) {
        *p++ = '0';
        return p;
    }
    if (x < 0) *p++ = '-', x = -x;
    if (x >= 1e9 || x < 1e-4) return numtext_g(p, x, sig);
    /* e: digits before the point minus one, the largest e in [-4, 8] with x >= 10^e */
    int e = decimal_exponent_guess(x);
    if (e < -4) e = -4;
    if (e > 8) e = 8;
    while (e < 8 && x >= thresholds[e + 5]) e++;
    while (e > -4 && x < thresholds[e + 4]) e--;
    int dec = sig - 1 - e;
    if (dec < 0) dec = 0;
    if (dec > 9) dec = 9;
    double y = x * pow10d[dec]; /* exact (see the top): below 1e10 */
    uint64_t v = (uint64_t)(int64_t)y;
    if (y - (double)v >= 0.5) v++; /* half away from zero */
    /* digits right-aligned at d + 24, zero-padded to dec + 1; fixed-size copies out (the
     * caller's NUMTEXT_ROOM), then the end moved back over what is not part of the text */
    char d[48];
    char *end = d + 24;
    int n = digits_before(end, v);
    memset(end - 12, '0', 12 - (n < 12 ? n : 12)); /* padding for values below 1 */
    if (n < dec + 1) n = dec + 1;
    const char *s = end - n;
    int whole = n - dec;
    memcpy(p, s, 16); /* whole <= 10 */
    p += whole;
    int frac = dec;
    while (frac > 0 && s[whole + frac - 1] == '0') frac--;
    if (frac) {
        *p = '.';
        memcpy(p + 1, s + whole, 16); /* frac <= 9 */
        p += frac + 1;
    }
    return p;
}
