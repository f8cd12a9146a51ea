/* Number text (util/numtext, and the OBJ writer's io_float): byte for byte what printf writes,
 * and every number reads back to the value it should (strtod/strtof), over edge values and
 * random floats. */
#include <limits.h>
#include <float.h>
#include <math.h>

#include "unit.h"
#include "io/io_internal.h"
#include "util/numcache.h"
#include "util/numtext.h"
#include "util/rng.h"

static float bits_float(uint32_t u) {
    float f;
    memcpy(&f, &u, 4);
    return f;
}

/* Edge values: zeros, denormals, the float range's ends, powers of ten 1e-7..1e7 and their
 * neighbours, exact decimal ties at several digits (1234.125, 0.5, 2.5, 8388607.5), whole
 * numbers near 2^24, values that round up to the next power (9.9999995), NaN, infinities. */
static size_t edge_values(float *v) {
    size_t n = 0;
    static const float fixed[] = {0.0f,        -0.0f,      1.0f,        -1.0f,      0.5f,       2.5f,      1.5f,
                                  1234.125f,   -1234.125f, 0.125f,      1e-7f,      1e7f,       9.9999995f, 0.99999994f,
                                  99999.95f,   999999.5f,  8388607.5f,  16777216.f, 16777215.f, 123456789.f, 1e9f,
                                  999999940.f, 1e-4f,      0.00009999f, FLT_MIN,    FLT_MAX,    -FLT_MAX,  FLT_TRUE_MIN,
                                  3.4e-39f,    0.1f,       0.2f,        0.3f,       1.0f / 3,   2.0f / 3,  1e-5f,
                                  1e-6f,       1e20f,      1e-20f,      65504.f,    0.0625f,    1e38f,     -2.5e-8f};
    for (size_t i = 0; i < sizeof fixed / sizeof *fixed; i++) v[n++] = fixed[i];
    for (int e = -7; e <= 9; e++) {
        float p = (float)pow(10, e);
        v[n++] = p, v[n++] = nextafterf(p, 0), v[n++] = nextafterf(p, INFINITY), v[n++] = -p;
        v[n++] = 5 * p, v[n++] = nextafterf(5 * p, 0), v[n++] = nextafterf(5 * p, INFINITY);
    }
    v[n++] = NAN, v[n++] = -NAN, v[n++] = INFINITY, v[n++] = -INFINITY;
    return n;
}

/* Random floats: raw bit patterns (every exponent, denormals, NaNs) and log-uniform values in
 * [1e-7, 1e7] with a random sign, the writers' usual range. */
static float random_value(Rng *r, uint64_t i) {
    uint64_t u = rng_next(r);
    if (i & 1) return bits_float((uint32_t)u);
    double mag = pow(10, -7 + 14 * ((double)(u >> 11) * 0x1p-53));
    return (float)((u & 1) ? -mag : mag);
}

#define RANDOM_COUNT 500000

static void g_is_printf_byte_for_byte(void **state) {
    (void)state;
    float edges[256];
    size_t ne = edge_values(edges);
    char want[64], got[64];
    Rng r = rng_stream(11, 0, 0, 0);
    for (uint64_t i = 0; i < ne + RANDOM_COUNT; i++) {
        float x = i < ne ? edges[i] : random_value(&r, i);
        for (int prec = (i < ne || i % 64 == 0) ? 0 : 6; prec <= ((i < ne || i % 64 == 0) ? 10 : 6); prec++) {
            snprintf(want, sizeof want, "%.*g", prec, (double)x);
            *numtext_g(got, x, prec) = 0;
            if (strcmp(want, got)) fail_msg("%%.%dg of %a: printf '%s', numtext '%s'", prec, (double)x, want, got);
            if (prec != 6) continue;
            *numtext_g6(got, x) = 0; /* its fast case for floats */
            if (strcmp(want, got)) fail_msg("%%.6g of %a: printf '%s', numtext_g6 '%s'", (double)x, want, got);
        }
    }
    /* doubles that are not floats go to printf: the same text */
    static const double d[] = {0.1, 1.0 / 3, 1e300, 5e-324, 123456789012.5};
    for (size_t i = 0; i < sizeof d / sizeof *d; i++) {
        snprintf(want, sizeof want, "%.6g", d[i]);
        *numtext_g(got, d[i], 6) = 0;
        assert_string_equal(want, got);
    }
}

/* Nine significant digits tell every float apart: strtof reads each one back, bit for bit. */
static void g9_reads_back_every_float(void **state) {
    (void)state;
    float edges[256];
    size_t ne = edge_values(edges);
    char s[64];
    Rng r = rng_stream(12, 0, 0, 0);
    for (uint64_t i = 0; i < ne + RANDOM_COUNT; i++) {
        float x = i < ne ? edges[i] : random_value(&r, i);
        *numtext_g(s, x, 9) = 0;
        float y = strtof(s, NULL);
        if (isnan(x)) {
            assert_true(isnan(y));
            continue;
        }
        if (memcmp(&x, &y, 4)) fail_msg("%a wrote '%s', read back %a", (double)x, s, (double)y);
    }
}

/* The OBJ writer's short form (io_float), checked against the definition rather than the code: the text reads back
 * within half a unit of its last place (10^(e - sig + 1), e = floor(log10 |x|), whole numbers
 * at least 1), never further, a tie going away from zero; no exponent in [1e-4, 1e9); zero
 * for -0, NaN and the infinities. */
/* numtext_int is "%lld" byte for byte: every power of ten and its neighbours, the ends of
 * the 32- and 64-bit ranges, and random values of every length. */
static void int_is_printf_byte_for_byte(void **state) {
    (void)state;
    long long v[200];
    int n = 0;
    long long t = 1;
    for (int e = 0; e < 19; e++, t *= e < 19 ? 10 : 1)
        for (int d = -1; d <= 1; d++) v[n++] = t + d, v[n++] = -(t + d);
    long long ends[] = {0, INT32_MAX, INT32_MIN, UINT32_MAX, (long long)UINT32_MAX + 1, -(long long)UINT32_MAX,
                        LLONG_MAX, LLONG_MIN, LLONG_MIN + 1};
    for (size_t i = 0; i < sizeof ends / sizeof *ends; i++) v[n++] = ends[i];
    uint64_t r = 88172645463325252ull;
    for (int i = 0; i < 200000; i++) {
        r ^= r << 13, r ^= r >> 7, r ^= r << 17;
        long long x = (long long)(r >> (r % 64));
        char want[32], got[32];
        snprintf(want, sizeof want, "%lld", i < n ? v[i] : x);
        *numtext_int(got, i < n ? v[i] : x) = 0;
        if (strcmp(want, got)) fail_msg("%%lld of %s: numtext '%s'", want, got);
    }
}

static void check_short(float x, int sig) {
    char s[64];
    *io_float(s, x, sig) = 0;
    if (!isfinite(x) || x == 0) {
        assert_string_equal(s, "0");
        return;
    }
    double ax = fabs((double)x);
    char e_text[64];
    snprintf(e_text, sizeof e_text, "%.20e", ax); /* exact digits: floor(log10) is its exponent */
    int e = atoi(strchr(e_text, 'e') + 1);
    if (ax >= 1e9 || ax < 1e-4) {
        char want[64];
        snprintf(want, sizeof want, "%.*g", sig, (double)x);
        assert_string_equal(s, want);
        return;
    }
    assert_null(strpbrk(s, "eE"));
    size_t len = strlen(s); /* the shortest text: no trailing zeros after a point, no bare point, one leading 0 at most */
    if (strchr(s, '.') && (s[len - 1] == '0' || s[len - 1] == '.')) fail_msg("short(%a, %d) = '%s': not trimmed", (double)x, sig, s);
    if (s[s[0] == '-'] == '0' && s[(s[0] == '-') + 1] != '.' && s[(s[0] == '-') + 1]) fail_msg("short(%a, %d) = '%s': leading zero", (double)x, sig, s);
    int dec = sig - 1 - e;
    if (dec < 0) dec = 0;
    if (dec > 9) dec = 9;
    double unit = pow(10, -dec), back = strtod(s, NULL);
    /* |back - x| in units, from exact decimal text: x * 10^dec is exact (a float times a
     * power of ten up to 1e9), and so is the read text's scaled value for up to 15 digits. */
    double want_scaled = ax * pow(10, dec), got_scaled = round(fabs(back) / unit);
    double off = got_scaled - want_scaled;
    if (!(fabs(off) <= 0.5) || (off == -0.5) || (back < 0) != (x < 0))
        fail_msg("short(%a, %d) = '%s': %g units from x (unit 1e-%d)", (double)x, sig, s, off, dec);
    (void)e_text;
}

static void short_reads_back_to_the_rounded_value(void **state) {
    (void)state;
    float edges[256];
    size_t ne = edge_values(edges);
    Rng r = rng_stream(13, 0, 0, 0);
    for (uint64_t i = 0; i < ne + RANDOM_COUNT; i++) {
        float x = i < ne ? edges[i] : random_value(&r, i);
        check_short(x, 6);
        check_short(x, 7);
        if (i % 16 == 0)
            for (int sig = 1; sig <= 9; sig++) check_short(x, sig);
    }
}

static char *g6(char *p, float x, int sig) { return numtext_g(p, x, sig); }

/* The per-write cache (util/numcache) gives each value the formatter's own text: values drawn
 * from a small pool (hits), edge values, random ones (misses and slots taken over), -0 beside
 * 0 (another key, another text), in a stream of 200 000. */
static void cache_gives_the_formatters_text(void **state) {
    (void)state;
    float pool[512];
    size_t n = edge_values(pool);
    Rng r = rng_stream(14, 0, 0, 0);
    while (n < 512) pool[n] = random_value(&r, n), n++;
    static NumCache obj[2], g; /* one cache for each precision */
    numcache_init(&obj[0], "0", 1), numcache_init(&obj[1], "0", 1), numcache_init(&g, "0", 1);
    for (int i = 0; i < 200000; i++) {
        uint64_t u = rng_next(&r);
        float x = u % 3 ? pool[(u >> 8) % 512] : random_value(&r, (uint64_t)i);
        int sig = 6 + (int)(u >> 40) % 2;
        char want[64], got[64];
        *io_float(want, x, sig) = 0;
        *numcache_put(&obj[sig - 6], got, x, sig, io_float) = 0;
        if (strcmp(want, got)) fail_msg("OBJ: %a (%d digits): '%s', cached '%s'", (double)x, sig, want, got);
        *g6(want, x, 6) = 0;
        *numcache_put(&g, got, x, 6, g6) = 0;
        if (strcmp(want, got)) fail_msg("%%.6g: %a: '%s', cached '%s'", (double)x, want, got);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(g_is_printf_byte_for_byte),
        cmocka_unit_test(g9_reads_back_every_float),
        cmocka_unit_test(short_reads_back_to_the_rounded_value),
        cmocka_unit_test(int_is_printf_byte_for_byte),
        cmocka_unit_test(cache_gives_the_formatters_text),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
