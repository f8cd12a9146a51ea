/* Eight lanes of single-precision maths (GCC and Clang vector extensions): the sines and
 * arctangents of eight leaves at once, without calls or branches. A leaf's frame is stored
 * in floats and nothing grows from it, so float precision is all it needs (the willow's
 * leaf axes within 2e-6 of those turned in doubles). Compiled for the x86-64 baseline a
 * vector is two SSE registers; where AVX is enabled (leaf_turn_avx2.c), one. Each lane's
 * operations are the same either way (no fused multiply-add), so are its results. */
#ifndef WEBER_LANES_H
#define WEBER_LANES_H
#include <math.h>
#include <stdint.h>
#if defined(__x86_64__)
#include <immintrin.h>
#endif
/* (for the rest of the file that includes it: GCC warns of 32-byte vectors passed without AVX
 * enabled, reported at the file's end; these are static functions, no ABI crosses a file) */
#pragma GCC diagnostic ignored "-Wpsabi"

typedef float v8f __attribute__((vector_size(32)));
typedef int32_t v8i __attribute__((vector_size(32)));
typedef uint32_t v8u __attribute__((vector_size(32))); /* for the bits */

static inline v8f v8_set(float a) { return (v8f){a, a, a, a, a, a, a, a}; }
/* m ? a : b per lane, m a comparison's mask */
static inline v8f v8_sel(v8i m, v8f a, v8f b) { return (v8f)((m & (v8i)a) | (~m & (v8i)b)); }
static inline v8f v8_abs(v8f a) { return (v8f)((v8u)a & 0x7fffffffu); }

static inline v8f v8_sqrt(v8f a) {
#if defined(__AVX__)
    return (v8f)_mm256_sqrt_ps((__m256)a);
#elif defined(__x86_64__)
    typedef float v4f __attribute__((vector_size(16)));
    v4f lo = {a[0], a[1], a[2], a[3]}, hi = {a[4], a[5], a[6], a[7]};
    lo = (v4f)_mm_sqrt_ps((__m128)lo), hi = (v4f)_mm_sqrt_ps((__m128)hi);
    return (v8f){lo[0], lo[1], lo[2], lo[3], hi[0], hi[1], hi[2], hi[3]};
#else
    v8f r;
    for (int k = 0; k < 8; k++) r[k] = sqrtf(a[k]);
    return r;
#endif
}

/* sin and cos: x = k pi/2 + r, |r| <= pi/4, pi/2 in three parts (Cody and Waite: k times
 * the first two is exact for |k| < 2^8), Taylor polynomials to r^9 and r^10 (error under
 * 2e-9), then the quadrant. */
static inline void v8_sincos(v8f x, v8f *c, v8f *s) {
    const v8f round = v8_set(0x1.8p23f); /* adding and taking it away rounds to an integer */
    v8f k = (x * v8_set((float)(2 / M_PI)) + round) - round;
    v8f r = ((x - k * 1.5703125f) - k * 4.837512969970703125e-4f) - k * 7.54978995489188216e-8f, z = r * r;
    v8f sn = r + r * z * (-1.0f / 6 + z * (1.0f / 120 + z * (-1.0f / 5040 + z * (1.0f / 362880))));
    v8f cs = 1 + z * (-0.5f + z * (1.0f / 24 + z * (-1.0f / 720 + z * (1.0f / 40320 + z * (-1.0f / 3628800)))));
    v8i q = __builtin_convertvector(k, v8i), odd = (q & 1) != 0;
    v8f ss = v8_sel(odd, cs, sn), cc = v8_sel(odd, sn, cs);
    v8u uq = (v8u)q;
    *s = (v8f)((v8u)ss ^ ((uq & 2) << 30));       /* quadrants 2 and 3: -sin */
    *c = (v8f)((v8u)cc ^ (((uq + 1) & 2) << 30)); /* quadrants 1 and 2: -cos */
}

/* atan2(y, x): atan t / t as a polynomial in t^2 over [0, 1] (Chebyshev interpolation, degree
 * 9: within 2e-9 in doubles), t the smaller coordinate over the larger, then the octant */
static inline v8f v8_atan2(v8f y, v8f x) {
    v8f ax = v8_abs(x), ay = v8_abs(y);
    v8i xbig = ax > ay;
    v8f hi = v8_sel(xbig, ax, ay), lo = v8_sel(xbig, ay, ax);
    v8f t = v8_sel(hi > 0, lo / v8_sel(hi > 0, hi, v8_set(1)), v8_set(0)), z = t * t, z2 = z * z, z4 = z2 * z2;
    v8f p = (0.999999997160544f + -0.33333276291968977f * z) + z2 * (0.1999807528082414f + -0.14260016079705623f * z) +
            z4 * ((0.10932341485896302f + -0.083497249245010619f * z) +
                  z2 * (0.057089555186985316f + -0.030351864043404932f * z)) +
            z4 * z4 * (0.010487648853086284f + -0.0017011699732393027f * z);
    v8f r = t * p;
    r = v8_sel(ay > ax, (float)(M_PI / 2) - r, r);
    r = v8_sel((v8i)x < 0, (float)M_PI - r, r);
    return (v8f)(((v8u)r & 0x7fffffffu) | ((v8u)y & 0x80000000u)); /* copysign */
}

#endif
