/* The sRGB bytes of linear values, lrintf(255 * linear_to_srgb(v)), by table: the same bytes
 * as the formula, without a powf a texel. */
#ifndef SYL_TEXTURE_SRGBBYTES_H
#define SYL_TEXTURE_SRGBBYTES_H
#include <stdint.h>
#include <string.h>

/* at[b]: the bits of the least float in (0, 1) whose byte is b or more (at[256]: above all);
 * first[k]: the byte of the float whose bits are k << 16, where a search for v starts. */
typedef struct SrgbBytes {
    uint32_t at[257];
    uint8_t first[(0x3f800000u >> 16) + 1];
} SrgbBytes;

/* lrintf(255 * linear_to_srgb(v)): the formula the table stands for. */
uint8_t srgb_byte_exact(float v);
/* Fill t (about 24,000 evaluations of the formula: once per texture, not once per texel). */
void srgb_bytes_init(SrgbBytes *t);
/* srgb_byte_exact(v), byte for byte: from the table, and from the formula within NEAR floats
 * of a step (where a last-bit error of powf could fall either side). */
static inline uint8_t srgb_byte(const SrgbBytes *t, float v) { /* inline: a texture asks it 786,432 times */
    enum { NEAR = 64 };
    if (!(v > 0) || !(v < 1)) return srgb_byte_exact(v); /* also NaN */
    uint32_t u;
    memcpy(&u, &v, sizeof u);
    int b = t->first[u >> 16];
    while (u >= t->at[b + 1]) b++;
    if (u < t->at[b] + NEAR || u + NEAR >= t->at[b + 1]) return srgb_byte_exact(v);
    return (uint8_t)b;
}

#endif
