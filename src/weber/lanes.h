/* Four lanes of single-precision maths (GCC and Clang vector extensions): the sines and
 * arctangents of four leaves at once, without calls or branches. A leaf's frame is stored
 * in floats and nothing grows from it, so float precision is all it needs (the willow's
 * leaf axes within 2e-6 of those turned in doubles). */
#ifndef WEBER_LANES_H
#define WEBER_LANES_H
#include <math.h>
#include <stdint.h>
#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

typedef float v4f __attribute__((vector_size(16)));
typedef int32_t v4i __attribute__((vector_size(16)));
typedef uint32_t v4u __attribute__((vector_size(16))); /* for the bits */

static inline v4f v4_set(float a) { return (v4f){a, a, a, a}; }
/* m ? a : b per lane, m a comparison's mask */
static inline v4f v4_sel(v4i m, v4f a, v4f b) { return (v4f)((m & (v4i)a) | (~m & (v4i)b)); }
static inline v4f v4_abs(v4f a) { return (v4f)((v4u)a & 0x7fffffffu); }

static inline v4f v4_sqrt(v4f a) {
#if defined(__SSE__) || defined(__x86_64__)
    return (v4f)_mm_sqrt_ps((__m128)a);
#else
    return (v4f){sqrtf(a[0]), sqrtf(a[1]), sqrtf(a[2]), sqrtf(a[3])};
#endif
}

/* sin and cos: x = k pi/2 + r, |r| <= pi/4, pi/2 in three parts (Cody and Waite: k times
 * the first two is exact for |k| < 2^8), Taylor polynomials to r^9 and r^10 (error under
 * 2e-9), then the quadrant. */
static inline void v4_sincos(v4f x, v4f *c, v4f *s) {
    const v4f round = v4_set(0x1.8p23f); /* adding and taking it away rounds to an integer */
    v4f k = (x * v4_set((float)(2 / M_PI)) + round) - round;
    v4f r = ((x - k * 1.5703125f) - k * 4.837512969970703125e-4f) - k * 7.54978995489188216e-8f, z = r * r;
    v4f sn = r + r * z * (-1.0f / 6 + z * (1.0f / 120 + z * (-1.0f / 5040 + z * (1.0f / 362880))));
    v4f cs = 1 + z * (-0.5f + z * (1.0f / 24 + z * (-1.0f / 720 + z * (1.0f / 40320 + z * (-1.0f / 3628800)))));
    v4i q = __builtin_convertvector(k, v4i), odd = (q & 1) != 0;
    v4f ss = v4_sel(odd, cs, sn), cc = v4_sel(odd, sn, cs);
    v4u uq = (v4u)q;
    *s = (v4f)((v4u)ss ^ ((uq & 2) << 30));       /* quadrants 2 and 3: -sin */
    *c = (v4f)((v4u)cc ^ (((uq + 1) & 2) << 30)); /* quadrants 1 and 2: -cos */
}

/* atan2(y, x): atan t / t as a polynomial in t^2 over [0, 1] (Chebyshev interpolation, degree
 * 9: within 2e-9 in doubles), t the smaller coordinate over the larger, then the octant */
static inline v4f v4_atan2(v4f y, v4f x) {
    v4f ax = v4_abs(x), ay = v4_abs(y);
    v4i xbig = ax > ay;
    v4f hi = v4_sel(xbig, ax, ay), lo = v4_sel(xbig, ay, ax);
    v4f t = v4_sel(hi > 0, lo / v4_sel(hi > 0, hi, v4_set(1)), v4_set(0)), z = t * t, z2 = z * z, z4 = z2 * z2;
    v4f p = (0.999999997160544f + -0.33333276291968977f * z) + z2 * (0.1999807528082414f + -0.14260016079705623f * z) +
            z4 * ((0.10932341485896302f + -0.083497249245010619f * z) +
                  z2 * (0.057089555186985316f + -0.030351864043404932f * z)) +
            z4 * z4 * (0.010487648853086284f + -0.0017011699732393027f * z);
    v4f r = t * p;
    r = v4_sel(ay > ax, (float)(M_PI / 2) - r, r);
    r = v4_sel((v4i)x < 0, (float)M_PI - r, r);
    return (v4f)(((v4u)r & 0x7fffffffu) | ((v4u)y & 0x80000000u)); /* copysign */
}

#endif
