/* The global marker cloud: see markers.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "env/markers.h"
#include "util/array.h"
#include "util/rng.h"

#define CELL_EMPTY UINT64_MAX

static inline uint64_t cell_key(int x, int y, int z) {
    return ((uint64_t)(uint32_t)(x + (1 << 20)) & 0x1fffff) | (((uint64_t)(uint32_t)(y + (1 << 20)) & 0x1fffff) << 21) |
           (((uint64_t)(uint32_t)(z + (1 << 20)) & 0x1fffff) << 42);
}

void markers_init(MarkerCloud *c, float cell, float density, float kill, float ground, uint64_t seed) {
    memset(c, 0, sizeof *c);
    c->cell = cell;
    c->inv = 1.0f / cell;
    c->per_cell = density * cell * cell * cell;
    c->kill = kill;
    c->ground = ground;
    c->seed = seed;
}

void markers_free(MarkerCloud *c) {
    budget_release(c->mem, c->charged);
    free(c->keys);
    free(c->slot_block);
    free(c->blocks);
    free(c->pos);
    free(c->alive);
    memset(c, 0, sizeof *c);
}

static size_t find_slot(const MarkerCloud *c, uint64_t key) {
    size_t h = (size_t)rng_mix(key) & c->mask;
    while (c->keys[h] != key && c->keys[h] != CELL_EMPTY) h = (h + 1) & c->mask;
    return h;
}

long markers_block(const MarkerCloud *c, int x, int y, int z) {
    if (!c->keys) return -1;
    size_t h = find_slot(c, cell_key(x, y, z));
    return c->keys[h] == CELL_EMPTY ? -1 : (long)c->slot_block[h];
}

static bool rehash(MarkerCloud *c) {
    size_t cap = c->keys ? 2 * (c->mask + 1) : 1024;
    uint64_t *keys = malloc(cap * sizeof *keys);
    uint32_t *sb = malloc(cap * sizeof *sb);
    if (!keys || !sb) {
        free(keys);
        free(sb);
        return false;
    }
    memset(keys, 0xff, cap * sizeof *keys);
    free(c->keys);
    free(c->slot_block);
    c->keys = keys;
    c->slot_block = sb;
    c->mask = cap - 1;
    for (size_t b = 0; b < c->nblocks; b++) {
        size_t h = find_slot(c, c->blocks[b].key);
        c->keys[h] = c->blocks[b].key;
        c->slot_block[h] = (uint32_t)b;
    }
    return true;
}

static bool make_cell(MarkerCloud *c, int x, int y, int z, const PointGrid *occupied) {
    if ((c->nblocks + 1) * 2 > c->mask + 1 && !rehash(c)) return false;
    uint64_t key = cell_key(x, y, z);
    Rng r = rng_stream(c->seed, key, 7, 0);
    /* a whole number of markers with the right mean */
    double want = c->per_cell;
    /* counted before they are made: a position and a flag each (density 1e4 with a perception
     * of 1e4 internodes asks for 1e16 a cell) */
    double need = (want + 1) * (double)(sizeof *c->pos + 1) + (double)sizeof *c->blocks;
    uint64_t bytes = need < 1e19 ? (uint64_t)need : UINT64_MAX;
    if (!budget_charge(c->mem, bytes)) return false;
    c->charged += bytes;
    /* a cell's markers are counted and indexed in 32 bits (and 1e16 is no uint32_t) */
    if (!(want < (double)UINT32_MAX - 1 - (double)c->n)) return false;
    uint32_t count = (uint32_t)want + (rng_unit(&r) < want - floor(want));
    size_t pcap = c->cap;
    if (!array_reserve(&c->pos, &pcap, c->n + count, sizeof *c->pos)) return false;
    size_t acap = c->cap;
    if (!array_reserve(&c->alive, &acap, c->n + count, 1)) return false;
    c->cap = pcap < acap ? pcap : acap;
    if (!array_reserve(&c->blocks, &c->bcap, c->nblocks + 1, sizeof *c->blocks)) return false;
    MarkerBlock *b = &c->blocks[c->nblocks];
    b->key = key;
    b->first = (uint32_t)c->n;
    b->count = count;
    for (uint32_t i = 0; i < count; i++) {
        float *p = c->pos[c->n + i];
        p[0] = ((float)x + (float)rng_unit(&r)) * c->cell;
        p[1] = ((float)y + (float)rng_unit(&r)) * c->cell;
        p[2] = ((float)z + (float)rng_unit(&r)) * c->cell;
        c->alive[c->n + i] = p[1] > c->ground && !(occupied && pgrid_any_within(occupied, p, c->kill, UINT32_MAX));
    }
    c->n += count;
    size_t h = find_slot(c, key);
    c->keys[h] = key;
    c->slot_block[h] = (uint32_t)c->nblocks++;
    return true;
}

bool markers_ensure(MarkerCloud *c, const float pos[3], float r, const PointGrid *occupied) {
    if (!c->keys && !rehash(c)) return false;
    int x0 = markers_coord(c, pos[0] - r), x1 = markers_coord(c, pos[0] + r);
    int y0 = markers_coord(c, pos[1] - r), y1 = markers_coord(c, pos[1] + r);
    int z0 = markers_coord(c, pos[2] - r), z1 = markers_coord(c, pos[2] + r);
    for (int x = x0; x <= x1; x++)
        for (int y = y0; y <= y1; y++)
            for (int z = z0; z <= z1; z++)
                if (markers_block(c, x, y, z) < 0 && !make_cell(c, x, y, z, occupied)) return false;
    return true;
}

void markers_kill_near(MarkerCloud *c, const float pos[3]) {
    float r = c->kill, r2 = r * r;
    int x0 = markers_coord(c, pos[0] - r), x1 = markers_coord(c, pos[0] + r);
    int y0 = markers_coord(c, pos[1] - r), y1 = markers_coord(c, pos[1] + r);
    int z0 = markers_coord(c, pos[2] - r), z1 = markers_coord(c, pos[2] + r);
    for (int x = x0; x <= x1; x++)
        for (int y = y0; y <= y1; y++)
            for (int z = z0; z <= z1; z++) {
                long b = markers_block(c, x, y, z);
                if (b < 0) continue;
                const MarkerBlock *blk = &c->blocks[b];
                for (uint32_t i = blk->first; i < blk->first + blk->count; i++) {
                    const float *p = c->pos[i];
                    float dx = p[0] - pos[0], dy = p[1] - pos[1], dz = p[2] - pos[2];
                    if (dx * dx + dy * dy + dz * dz < r2) c->alive[i] = 0;
                }
            }
}

size_t markers_alive(const MarkerCloud *c) {
    size_t n = 0;
    for (size_t i = 0; i < c->n; i++) n += c->alive[i];
    return n;
}
