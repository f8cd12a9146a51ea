/* A float's text formatted once per write: mesh files repeat their numbers (a leaf's four UVs,
 * a flat face's normal, a tube's seam), so a table keyed by the float's bits turns most of
 * them into a 16-byte copy (docs/mesh.md#number-text). */
#ifndef SYL_UTIL_NUMCACHE_H
#define SYL_UTIL_NUMCACHE_H

#include <stdint.h>
#include <string.h>

enum { NUMCACHE_BITS = 12, NUMCACHE_TEXT = 16 };

typedef struct NumCacheSlot {
    char text[NUMCACHE_TEXT];
    uint32_t bits, len;
} NumCacheSlot;

/* Direct mapped: a slot holds the last value that hashed to it. One cache per formatter and
 * precision: the text is keyed by the bits alone. */
typedef struct NumCache {
    NumCacheSlot slot[1 << NUMCACHE_BITS];
} NumCache;

/* Every slot: +0.0f, whose text zero (zlen bytes) the caller's formatter writes for it. */
static inline void numcache_init(NumCache *c, const char *zero, uint32_t zlen) {
    NumCacheSlot s = {.bits = 0, .len = zlen};
    memcpy(s.text, zero, zlen < NUMCACHE_TEXT ? zlen : NUMCACHE_TEXT);
    for (int i = 0; i < 1 << NUMCACHE_BITS; i++) c->slot[i] = s;
}

/* The text fmt(p, x, sig) writes for x: the slot's copy, or fmt's (kept when it fits 16 bytes).
 * Writes up to 16 bytes from p whatever the text's length; returns the text's end. */
static inline char *numcache_put(NumCache *c, char *p, float x, int sig, char *(*fmt)(char *, float, int)) {
    uint32_t b;
    memcpy(&b, &x, 4);
    NumCacheSlot *s = &c->slot[(b * 0x9E3779B1u) >> (32 - NUMCACHE_BITS)];
    if (s->bits == b) {
        memcpy(p, s->text, NUMCACHE_TEXT);
        return p + s->len;
    }
    char *e = fmt(p, x, sig);
    uint32_t n = (uint32_t)(e - p);
    if (n <= NUMCACHE_TEXT) memcpy(s->text, p, NUMCACHE_TEXT), s->bits = b, s->len = n;
    return e;
}

#endif
