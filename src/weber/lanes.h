/* Lanes of single-precision maths (GCC and Clang vector extensions): the sines and
 * arctangents of several leaves at once, without calls or branches, four lanes (v4f: the
 * x86-64 baseline's SSE register) or eight (v8f: AVX's, in leaf_turn_avx2.c). A leaf's frame
 * is stored in floats and nothing grows from it, so float precision is all it needs (the
 * willow's leaf axes within 2e-6 of those turned in doubles). Both widths are one code
 * (lanes_math.h, once per width) and do the same operations in each lane (no fused
 * multiply-add), so give the same results. */
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

typedef float v4f __attribute__((vector_size(16)));
typedef int32_t v4i __attribute__((vector_size(16)));
typedef uint32_t v4u __attribute__((vector_size(16))); /* for the bits */
typedef float v8f __attribute__((vector_size(32)));
typedef int32_t v8i __attribute__((vector_size(32)));
typedef uint32_t v8u __attribute__((vector_size(32)));

static inline v4f v4_sqrt(v4f a) {
#if defined(__x86_64__)
    return (v4f)_mm_sqrt_ps((__m128)a);
#else
    return (v4f){sqrtf(a[0]), sqrtf(a[1]), sqrtf(a[2]), sqrtf(a[3])};
#endif
}
static inline v8f v8_sqrt(v8f a) {
#if defined(__AVX__)
    return (v8f)_mm256_sqrt_ps((__m256)a);
#else
    v8f r;
    for (int k = 0; k < 8; k++) r[k] = sqrtf(a[k]);
    return r;
#endif
}

#define LANES_F v4f
#define LANES_I v4i
#define LANES_U v4u
#define LANES(name) v4_##name
#include "weber/lanes_math.h"
#define LANES_F v8f
#define LANES_I v8i
#define LANES_U v8u
#define LANES(name) v8_##name
#include "weber/lanes_math.h"

#endif
