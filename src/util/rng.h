/* Counter-based random streams. A stream is keyed by (seed, step, table, position), so a
 * module's draws never depend on which thread derived it or on what came before it. */
#ifndef SYL_RNG_H
#define SYL_RNG_H
#include <stdint.h>

typedef struct Rng {
    uint64_t key;
    uint64_t counter;
} Rng;

static inline uint64_t rng_mix(uint64_t z) { /* splitmix64 finaliser */
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* rng_stream in two halves: the part of a pass (seed, step), then each position's */
static inline uint64_t rng_pass(uint64_t seed, uint64_t step) { return rng_mix(rng_mix(seed) ^ step); }
static inline Rng rng_at(uint64_t pass, uint64_t table, uint64_t pos) {
    Rng r;
    r.key = rng_mix(pass ^ (table << 56 ^ pos));
    r.counter = 0;
    return r;
}

static inline Rng rng_stream(uint64_t seed, uint64_t step, uint64_t table, uint64_t pos) {
    return rng_at(rng_pass(seed, step), table, pos);
}

static inline uint64_t rng_next(Rng *r) { return rng_mix(r->key + 0x632be59bd9b4e019ull * ++r->counter); }

/* uniform in [0, 1) with 53 random bits */
static inline double rng_unit(Rng *r) { return (double)(rng_next(r) >> 11) * 0x1.0p-53; }

double rng_normal(Rng *r); /* standard normal, Box–Muller */

#endif
