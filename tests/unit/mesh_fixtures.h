/* Skeletons built by hand for the mesher and writer tests, and checks on meshes. */
#ifndef SYL_MESH_FIXTURES_H
#define SYL_MESH_FIXTURES_H
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sylva/mesh.h"

/* A node at (x, y, z), heading from its parent (or up for a root), L and U across it. */
static inline int32_t fx_node(SylSkeleton *s, int32_t parent, int32_t axis, float x, float y, float z, float r,
                              uint8_t mat) {
    SylNode n = {.pos = {x, y, z}, .radius = r, .parent = parent, .axis = axis, .material = mat,
                 .kind = parent < 0 ? SYL_KIND_ROOT : SYL_KIND_INTERNODE};
    float h[3] = {0, 1, 0};
    if (parent >= 0) {
        const float *p = s->nodes[parent].pos;
        float d[3] = {x - p[0], y - p[1], z - p[2]}, len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (len > 0)
            for (int k = 0; k < 3; k++) h[k] = d[k] / len;
        n.order = (uint16_t)(s->nodes[parent].order + (s->nodes[parent].axis != axis));
    }
    float a[3] = {1, 0, 0};
    if (fabsf(h[0]) > 0.9f) a[0] = 0, a[1] = 0, a[2] = 1;
    float l[3] = {h[1] * a[2] - h[2] * a[1], h[2] * a[0] - h[0] * a[2], h[0] * a[1] - h[1] * a[0]};
    float ll = sqrtf(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    for (int k = 0; k < 3; k++) l[k] /= ll;
    float u[3] = {h[1] * l[2] - h[2] * l[1], h[2] * l[0] - h[0] * l[2], h[0] * l[1] - h[1] * l[0]};
    memcpy(n.h, h, sizeof h);
    memcpy(n.l, l, sizeof l);
    memcpy(n.u, u, sizeof u);
    return syl_skeleton_add_node(s, &n);
}

static inline SylOrgan fx_organ(uint8_t kind, float x, float y, float z, float size, uint8_t mat) {
    SylOrgan o = {.pos = {x, y, z}, .h = {0, 1, 0}, .l = {1, 0, 0}, .u = {0, 0, 1}, .size = size,
                  .node = -1, .kind = kind, .material = mat};
    return o;
}

/* A tree: axes of nseg segments that bend a little, with a lateral axis at every node down
 * to depth levels; laterals get thinner. Deterministic. */
typedef struct FxTree {
    SylSkeleton *s;
    int32_t next_axis;
    int nseg;
} FxTree;

static inline void fx_grow(FxTree *t, int32_t parent, float px, float py, float pz, float dx, float dy, float dz,
                           float len, float r, int depth) {
    int32_t axis = t->next_axis++;
    float x = px, y = py, z = pz;
    for (int i = 0; i < t->nseg; i++) {
        float a = 0.3f * sinf((float)(axis * 7 + i)); /* bend */
        float nx = dx + 0.15f * cosf(a * 5), nz = dz + 0.15f * sinf(a * 3), ny = dy;
        float nl = sqrtf(nx * nx + ny * ny + nz * nz);
        dx = nx / nl, dy = ny / nl, dz = nz / nl;
        x += dx * len, y += dy * len, z += dz * len;
        float ri = r * (1.0f - 0.5f * (float)(i + 1) / (float)t->nseg);
        parent = fx_node(t->s, parent, axis, x, y, z, ri, 0);
        if (depth > 0 && i + 1 < t->nseg) {
            float phi = 2.39996f * (float)(axis + i), c = cosf(phi), sn = sinf(phi);
            float lx = 0.6f * dx + 0.8f * c, ly = 0.6f * dy + 0.3f, lz = 0.6f * dz + 0.8f * sn;
            float ll = sqrtf(lx * lx + ly * ly + lz * lz);
            fx_grow(t, parent, x, y, z, lx / ll, ly / ll, lz / ll, len * 0.6f, ri * 0.5f, depth - 1);
        }
    }
}

static inline SylSkeleton *fx_tree(int nseg, int depth) {
    FxTree t = {.s = syl_skeleton_new("fxtree"), .nseg = nseg};
    int32_t root = fx_node(t.s, -1, 0, 0, 0, 0, 0.5f, 0);
    t.next_axis = 0;
    fx_grow(&t, root, 0, 0, 0, 0, 1, 0, 1.0f, 0.5f, depth);
    return t.s;
}

/* ---- welding and edges: closedness of a set of triangles ---- */

typedef struct FxMap { /* open addressing: 64-bit key -> 32-bit value */
    uint64_t *keys;
    uint32_t *vals;
    size_t cap;
} FxMap;

static inline uint64_t fx_hash(uint64_t k) {
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdULL;
    k ^= k >> 33;
    return k;
}

static inline void fx_map_init(FxMap *m, size_t n) {
    m->cap = 16;
    while (m->cap < 2 * n + 16) m->cap *= 2;
    m->keys = malloc(m->cap * sizeof *m->keys);
    m->vals = calloc(m->cap, sizeof *m->vals);
    memset(m->keys, 0xff, m->cap * sizeof *m->keys);
}

/* The slot of key (inserting it with value 0 if new). */
static inline uint32_t *fx_map_slot(FxMap *m, uint64_t key) {
    size_t i = fx_hash(key) & (m->cap - 1);
    while (m->keys[i] != key && m->keys[i] != UINT64_MAX) i = (i + 1) & (m->cap - 1);
    m->keys[i] = key;
    return &m->vals[i];
}

/* The value of key, 0 when absent. */
static inline uint32_t fx_map_get(const FxMap *m, uint64_t key) {
    size_t i = fx_hash(key) & (m->cap - 1);
    while (m->keys[i] != key && m->keys[i] != UINT64_MAX) i = (i + 1) & (m->cap - 1);
    return m->keys[i] == key ? m->vals[i] : 0;
}

static inline void fx_map_free(FxMap *m) {
    free(m->keys);
    free(m->vals);
}

/* Weld vertices with the same position: weld[v] is the smallest vertex at v's place. */
static inline uint32_t *fx_weld(const SylMesh *m) {
    uint32_t *weld = malloc((m->nverts + 1) * sizeof *weld);
    /* hash of the 96 bits of position, then exact compare along the chain */
    FxMap map;
    fx_map_init(&map, m->nverts);
    uint32_t *next = malloc((m->nverts + 1) * sizeof *next);
    for (size_t v = 0; v < m->nverts; v++) {
        uint32_t b[3];
        memcpy(b, m->pos + 3 * v, sizeof b);
        uint64_t key = (((uint64_t)b[0] * 0x9E3779B97F4A7C15ULL) ^ ((uint64_t)b[1] << 21) ^ ((uint64_t)b[2] << 42) ^ b[2]) &
                       0x7fffffffffffffffULL;
        uint32_t *slot = fx_map_slot(&map, key), found = UINT32_MAX;
        for (uint32_t c = *slot; c; c = next[c - 1])
            if (!memcmp(m->pos + 3 * (c - 1), m->pos + 3 * v, 3 * sizeof(float))) {
                found = c - 1;
                break;
            }
        if (found != UINT32_MAX) weld[v] = weld[found];
        else {
            weld[v] = (uint32_t)v;
            next[v] = *slot;
            *slot = (uint32_t)v + 1;
        }
    }
    free(next);
    fx_map_free(&map);
    return weld;
}

typedef struct FxClosed {
    size_t edges, bad_edges; /* directed edges; those not used exactly once each way */
    size_t components;       /* connected sets of triangles */
    double volume;           /* signed: positive when the triangles face out */
} FxClosed;

static inline uint32_t fx_find(uint32_t *p, uint32_t x) {
    while (p[x] != x) x = p[x] = p[p[x]];
    return x;
}

/* Check triangles [first, first + count) of m.idx (count indices). */
static inline FxClosed fx_closed(const SylMesh *m, size_t first, size_t count) {
    FxClosed r = {0};
    uint32_t *weld = fx_weld(m);
    FxMap dir;
    fx_map_init(&dir, count);
    uint32_t *parent = malloc((m->nverts + 1) * sizeof *parent);
    for (size_t v = 0; v < m->nverts; v++) parent[v] = (uint32_t)v;
    bool *used = calloc(m->nverts + 1, 1);
    for (size_t t = first; t < first + count; t += 3) {
        uint32_t w[3];
        for (int k = 0; k < 3; k++) w[k] = weld[m->idx[t + (size_t)k]], used[w[k]] = true;
        for (int k = 0; k < 3; k++) {
            uint32_t a = w[k], b = w[(k + 1) % 3];
            (*fx_map_slot(&dir, (uint64_t)a << 32 | b))++;
            uint32_t ra = fx_find(parent, a), rb = fx_find(parent, b);
            if (ra != rb) parent[ra] = rb;
        }
        const float *p0 = m->pos + 3 * (size_t)w[0], *p1 = m->pos + 3 * (size_t)w[1], *p2 = m->pos + 3 * (size_t)w[2];
        r.volume += ((double)p0[0] * ((double)p1[1] * p2[2] - (double)p1[2] * p2[1]) -
                     (double)p0[1] * ((double)p1[0] * p2[2] - (double)p1[2] * p2[0]) +
                     (double)p0[2] * ((double)p1[0] * p2[1] - (double)p1[1] * p2[0])) / 6.0;
    }
    for (size_t i = 0; i < dir.cap; i++) {
        if (dir.keys[i] == UINT64_MAX) continue;
        uint32_t a = (uint32_t)(dir.keys[i] >> 32), b = (uint32_t)dir.keys[i];
        r.edges++;
        if (dir.vals[i] != 1 || fx_map_get(&dir, (uint64_t)b << 32 | a) != 1) r.bad_edges++;
    }
    for (size_t v = 0; v < m->nverts; v++)
        if (used[v] && fx_find(parent, (uint32_t)v) == v) r.components++;
    free(used);
    free(parent);
    fx_map_free(&dir);
    free(weld);
    return r;
}

#endif
