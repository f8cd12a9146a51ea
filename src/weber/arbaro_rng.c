/* Arbaro's random numbers (java.util.Random: a 48-bit linear congruential generator), for
 * the few draws that set the size of the whole tree. With convention arbaro the tree size
 * (Scale +- ScaleV), the first trunk's placement and length and the length of its children
 * come from the streams Arbaro draws them from, so a seed gives the tree Arbaro's height
 * for it; every other draw is Sylva's own (per-stem streams). */
#include "weber/internal.h"

#define JMUL 0x5DEECE66Dull
#define JMASK ((1ull << 48) - 1)

void jrand_seed(JRand *r, int64_t seed) { r->s = ((uint64_t)seed ^ JMUL) & JMASK; }

static int32_t jnext(JRand *r, int bits) {
    r->s = (r->s * JMUL + 0xB) & JMASK;
    return (int32_t)(int64_t)(r->s >> (48 - bits));
}

int64_t jrand_long(JRand *r) {
    int64_t hi = jnext(r, 32), lo = jnext(r, 32);
    return (int64_t)((uint64_t)hi << 32) + lo;
}

double jrand_double(JRand *r) {
    int64_t a = jnext(r, 26), b = jnext(r, 27);
    return (double)((a << 27) + b) * 0x1.0p-53;
}

/* Arbaro's level streams: level 0 is seeded with the seed, level 1 with level 0's first
 * long; the tree size is level 0's first double after that. */
void jrand_tree(int64_t seed, JRand *level0, JRand *level1) {
    jrand_seed(level0, seed);
    int64_t l1 = jrand_long(level0);
    jrand_seed(level1, l1);
    (void)jrand_long(level1); /* level 2's seed */
}
