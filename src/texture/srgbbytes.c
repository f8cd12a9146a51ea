/* sRGB bytes by table (srgbbytes.h). Positive floats order as their bits do, so the bytes
 * of (0, 1) are steps at 255 bit patterns, found by bisection on the formula. The formula is
 * increasing; were powf's last bit to make it step back and forth, that would be within a
 * few floats of a step, and those NEAR floats either side go to the formula itself
 * (tests/unit/test_srgbbytes.c checks every float of [0, 1] against it, strided, and all
 * near each step). */
#include "texture/srgbbytes.h"

#include <math.h>
#include <string.h>

#include "texture/texture.h"


static float of_bits(uint32_t u) {
    float v;
    memcpy(&v, &u, sizeof v);
    return v;
}

uint8_t srgb_byte_exact(float v) { return (uint8_t)lrintf(255 * linear_to_srgb(v)); }

void srgb_bytes_init(SrgbBytes *t) {
    const uint32_t one = 0x3f800000u; /* 1.0f: byte 255 */
    t->at[0] = 0;
    for (int b = 1; b < 256; b++) { /* the least u in [at[b - 1], one] with a byte >= b */
        uint32_t lo = t->at[b - 1], hi = one;
        while (lo < hi) {
            uint32_t mid = lo + (hi - lo) / 2;
            if (srgb_byte_exact(of_bits(mid)) >= b) hi = mid;
            else lo = mid + 1;
        }
        t->at[b] = lo;
    }
    t->at[256] = UINT32_MAX;
    for (uint32_t k = 0; k <= one >> 16; k++) t->first[k] = srgb_byte_exact(of_bits(k << 16));
}

