/* The shadow-propagation grid: see shadow.h. */
#include "env/shadow.h"

enum { SHADOW_PAD = 8 };


#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void shadow_init(ShadowGrid *g, const ShadowParams *p, float ground_y) {
    memset(g, 0, sizeof *g);
    g->p = *p;
    if (g->p.depth < 0) g->p.depth = 0;
    if (g->p.depth > SHADOW_MAX_DEPTH) g->p.depth = SHADOW_MAX_DEPTH;
    g->inv = 1.0f / g->p.voxel;
    float sy = p->sun[1] > 0.2f ? p->sun[1] : 0.2f; /* a low sun: at most 5 voxels aside per level */
    int wide = 0;
    for (int q = 0; q <= g->p.depth; q++) {
        g->layer[q] = (int32_t)lround((double)p->a * pow(p->b, -q) * SHADOW_ONE);
        g->shift_x[q] = (int)lround(-q * p->sun[0] / sy);
        g->shift_z[q] = (int)lround(-q * p->sun[2] / sy);
        int w = abs(g->shift_x[q]) > abs(g->shift_z[q]) ? abs(g->shift_x[q]) : abs(g->shift_z[q]);
        if (w > wide) wide = w;
    }
    g->reach = g->p.depth + wide;
    double gy = floor((double)ground_y * g->inv) - 1;
    g->ymin = isfinite(gy) && gy > INT_MIN / 4 && gy < INT_MAX / 4 ? (int)gy : INT_MIN / 4;
    g->max_voxels = (size_t)1 << 27; /* 512 MB of shadow and as much of differences */
}

void shadow_free(ShadowGrid *g) {
    budget_release(g->mem, g->charged);
    g->charged = 0;
    free(g->s);
    free(g->d);
    free(g->row);
    free(g->pbox);
    g->s = NULL;
    g->d = g->row = NULL;
    g->pbox = NULL;
}

size_t shadow_voxels(const ShadowGrid *g) { return (size_t)g->nx * (size_t)g->ny * (size_t)g->nz; }

static inline int cell(float v, float inv) { return shadow_cell(v, inv); }

/* A plane's box of differences (x lo, x hi, z lo, z hi), empty. */
static inline void plane_box_clear(int32_t *b) { b[0] = b[2] = INT_MAX, b[1] = b[3] = INT_MIN; }

/* Make the grid hold [lo, hi] (inclusive voxel coordinates), with room to spare. */
static bool reserve(ShadowGrid *g, const int lo[3], const int hi[3]) {
    int cur_lo[3] = {g->x0, g->y0, g->z0}, cur_hi[3] = {g->x0 + g->nx - 1, g->y0 + g->ny - 1, g->z0 + g->nz - 1};
    bool empty = g->s == NULL;
    if (!empty && lo[0] >= cur_lo[0] && lo[1] >= cur_lo[1] && lo[2] >= cur_lo[2] && hi[0] <= cur_hi[0] &&
        hi[1] <= cur_hi[1] && hi[2] <= cur_hi[2])
        return true;
    long nlo[3], nhi[3];
    for (int k = 0; k < 3; k++) {
        nlo[k] = empty ? lo[k] : lo[k] < cur_lo[k] ? lo[k] : cur_lo[k];
        nhi[k] = empty ? hi[k] : hi[k] > cur_hi[k] ? hi[k] : cur_hi[k];
        long size = nhi[k] - nlo[k] + 1, slack = size / 4 + 4; /* grow geometrically */
        if (empty || lo[k] < cur_lo[k]) nlo[k] -= slack;
        if (empty || hi[k] > cur_hi[k]) nhi[k] += slack;
    }
    if (nlo[1] < g->ymin) nlo[1] = g->ymin;
    if (nhi[1] < nlo[1]) nhi[1] = nlo[1];
    double total = (double)(nhi[0] - nlo[0] + 1) * (double)(nhi[1] - nlo[1] + 1) * (double)(nhi[2] - nlo[2] + 1);
    if (total > (double)g->max_voxels) return false;
    int nx = (int)(nhi[0] - nlo[0] + 1), ny = (int)(nhi[1] - nlo[1] + 1), nz = (int)(nhi[2] - nlo[2] + 1);
    uint64_t bytes = ((uint64_t)total * 2 + SHADOW_PAD + (uint64_t)nx + 4 * (uint64_t)ny) * sizeof(uint32_t);
    g->refused = !budget_resize(g->mem, g->charged, bytes);
    if (g->refused) return false;
    uint32_t *s = calloc((size_t)total + SHADOW_PAD, sizeof *s), *d = calloc((size_t)total, sizeof *d),
             *row = malloc((size_t)nx * sizeof *row);
    int32_t *pbox = malloc(4 * (size_t)ny * sizeof *pbox);
    if (!s || !d || !row || !pbox) {
        free(s), free(d), free(row), free(pbox);
        budget_resize(g->mem, bytes, g->charged);
        return false;
    }
    g->charged = bytes;
    if (!empty) {
        int dx = g->x0 - (int)nlo[0], dy = g->y0 - (int)nlo[1], dz = g->z0 - (int)nlo[2];
        for (int y = 0; y < g->ny; y++)
            for (int z = 0; z < g->nz; z++)
                memcpy(s + ((size_t)(y + dy) * (size_t)nz + (size_t)(z + dz)) * (size_t)nx + (size_t)dx,
                       g->s + ((size_t)y * (size_t)g->nz + (size_t)z) * (size_t)g->nx, (size_t)g->nx * sizeof *s);
    }
    free(g->s);
    free(g->d);
    free(g->row);
    free(g->pbox);
    for (int y = 0; y < ny; y++) plane_box_clear(pbox + 4 * y);
    g->s = (int32_t *)s;
    g->d = d;
    g->row = row;
    g->pbox = pbox;
    g->x0 = (int)nlo[0], g->y0 = (int)nlo[1], g->z0 = (int)nlo[2];
    g->nx = nx, g->ny = ny, g->nz = nz;
    return true;
}

/* Directly: each level's rows, 8 voxels at a time (lanes past a row's end add 0; the grid
 * has SHADOW_PAD spare voxels at its end, so the last row can be read whole). Cheaper than
 * the difference grid for a few casters spread over a large box. */
typedef uint32_t v8u __attribute__((vector_size(32)));
typedef uint32_t v4u __attribute__((vector_size(16)));
/* Lanes of a and b (4.. for b's) by index, in GCC's spelling or Clang's. */
#if defined(__clang__)
#define SHUFFLE4(a, b, i, j, k, l) __builtin_shufflevector(a, b, i, j, k, l)
#else
#define SHUFFLE4(a, b, i, j, k, l) __builtin_shuffle(a, b, (v4u){i, j, k, l})
#endif

static void cast_direct(ShadowGrid *g, int I, int J, int K, uint32_t weight) {
    uint32_t *s = (uint32_t *)g->s;
    const size_t nx = (size_t)g->nx, nz = (size_t)g->nz;
    for (int q = 0; q <= g->p.depth; q++) {
        int y = J - q;
        if (y < g->y0) break;
        uint32_t v = (uint32_t)g->layer[q];
        if (!v) break;
        v *= weight; /* wraps: adding and removing stay exact */
        int xs = I - q + g->shift_x[q] - g->x0, zs = K - q + g->shift_z[q] - g->z0, w = 2 * q + 1;
        uint32_t *plane = s + (size_t)(y - g->y0) * nz * nx;
        for (int x0 = 0; x0 < w; x0 += 8) {
            v8u add;
            for (int k = 0; k < 8; k++) add[k] = x0 + k < w ? v : 0;
            for (int z = zs; z < zs + w; z++) {
                uint32_t *row = plane + (size_t)z * nx + (size_t)xs + (size_t)x0;
                v8u cur;
                memcpy(&cur, row, sizeof cur);
                cur += add; /* wraps: adding and removing stay exact */
                memcpy(row, &cur, sizeof cur);
            }
        }
    }
}

/* A pyramid's levels as corners of squares in the difference grid; the box of the casters
 * of its plane (g->pbox, grid coordinates) grows to hold it, and ys, those planes' range. */
static void cast_one(ShadowGrid *g, int I, int J, int K, uint32_t weight, int ys[2]) {
    uint32_t *d = g->d;
    const size_t nx = (size_t)g->nx, nz = (size_t)g->nz;
    int32_t *bb = g->pbox + 4 * (size_t)(J - g->y0), i = I - g->x0, k = K - g->z0;
    if (i < bb[0]) bb[0] = i;
    if (i > bb[1]) bb[1] = i;
    if (k < bb[2]) bb[2] = k;
    if (k > bb[3]) bb[3] = k;
    if (J - g->y0 < ys[0]) ys[0] = J - g->y0;
    if (J - g->y0 > ys[1]) ys[1] = J - g->y0;
    for (int q = 0; q <= g->p.depth; q++) {
        int y = J - q;
        if (y < g->y0) break;
        uint32_t v = (uint32_t)g->layer[q];
        if (!v) break;
        v *= weight;
        int x0 = I - q + g->shift_x[q] - g->x0, z0 = K - q + g->shift_z[q] - g->z0, x1 = x0 + 2 * q + 1,
            z1 = z0 + 2 * q + 1, yy = y - g->y0; /* x1, z1: one past the square, inside the grid */
        uint32_t *plane = d + (size_t)yy * nz * nx;
        plane[(size_t)z0 * nx + (size_t)x0] += v; /* wraps: adding and removing stay exact */
        plane[(size_t)z0 * nx + (size_t)x1] -= v;
        plane[(size_t)z1 * nx + (size_t)x0] -= v;
        plane[(size_t)z1 * nx + (size_t)x1] += v;
    }
}

/* Sort by bits from..from+32 (a voxel index, below 2^33): three passes of an 11-bit radix
 * sort through tmp; stable. */
static void sort_bits(uint64_t *v, uint64_t *tmp, size_t n, int from) {
    for (int pass = 0; pass < 3; pass++) {
        size_t count[2049] = {0};
        int shift = from + 11 * pass;
        for (size_t i = 0; i < n; i++) count[((v[i] >> shift) & 2047) + 1]++;
        for (int b = 0; b < 2048; b++) count[b + 1] += count[b];
        for (size_t i = 0; i < n; i++) tmp[count[(v[i] >> shift) & 2047]++] = v[i];
        memcpy(v, tmp, n * sizeof *v);
    }
}

/* Sum the differences cast by the casters of planes ys[0]..ys[1] into the shadow and clear
 * them, each plane over its own box (beyond it the sums are zero: a crown's planes are
 * narrower than its box), made of the boxes of the casters above it that reach it: down each
 * plane, column sums along z (whole rows at a time), then a running sum along x. */
static void integrate(ShadowGrid *g, const int ys[2]) {
    const size_t nx = (size_t)g->nx, nz = (size_t)g->nz;
    uint32_t *s = (uint32_t *)g->s, *col = g->row;
    int reach = 0; /* the levels cast_one writes */
    while (reach < g->p.depth && g->layer[reach + 1]) reach++;
    for (int y = ys[0] - reach > 0 ? ys[0] - reach : 0; y <= ys[1]; y++) {
        int32_t bb[4] = {INT_MAX, INT_MIN, INT_MAX, INT_MIN};
        for (int q = 0; q <= reach && y + q <= ys[1]; q++) { /* level q of the casters q planes up */
            const int32_t *c = g->pbox + 4 * (size_t)(y + q);
            if (c[0] > c[1]) continue;
            int x0 = c[0] - q + g->shift_x[q], x1 = c[1] - q + g->shift_x[q] + 2 * q + 1;
            int z0 = c[2] - q + g->shift_z[q], z1 = c[3] - q + g->shift_z[q] + 2 * q + 1;
            if (x0 < bb[0]) bb[0] = x0;
            if (x1 > bb[1]) bb[1] = x1;
            if (z0 < bb[2]) bb[2] = z0;
            if (z1 > bb[3]) bb[3] = z1;
        }
        if (bb[0] > bb[1]) continue; /* nothing cast here */
        const size_t w = (size_t)(bb[1] - bb[0] + 1);
        memset(col, 0, w * sizeof *col);
        for (int z = bb[2]; z <= bb[3]; z++) {
            size_t at = ((size_t)y * nz + (size_t)z) * nx + (size_t)bb[0];
            uint32_t *dr = g->d + at, *sr = s + at, run = 0;
            size_t x = 0;
            for (; x + 4 <= w; x += 4) { /* 4 at a time: column sums, then their running sum */
                v4u c, d, sv, zero = {0, 0, 0, 0};
                memcpy(&c, col + x, sizeof c);
                memcpy(&d, dr + x, sizeof d);
                c += d;
                memcpy(col + x, &c, sizeof c);
                memcpy(dr + x, &zero, sizeof zero);
                v4u p = c + SHUFFLE4(c, zero, 4, 0, 1, 2); /* a prefix sum in two shifted adds */
                p += SHUFFLE4(p, zero, 4, 5, 0, 1);
                p += run;
                memcpy(&sv, sr + x, sizeof sv);
                sv += p;
                memcpy(sr + x, &sv, sizeof sv);
                run = p[3];
            }
            for (; x < w; x++) {
                col[x] += dr[x];
                dr[x] = 0;
                run += col[x];
                sr[x] += run;
            }
        }
    }
    for (int y = ys[0]; y <= ys[1]; y++) plane_box_clear(g->pbox + 4 * (size_t)y);
}

/* Make the grid hold the pyramids of casters at p(i) = base + i * stride (+ off, when
 * given; in float, as the caller would add it), i < n. *none: all are below the ground (the
 * grid is left as it is). False when the grid would need more than max_voxels. */
static bool reserve_casters(ShadowGrid *g, const float *base, size_t stride, size_t n, const float *off, int box[6],
                            bool *none) {
    *none = true;
    if (!n) return true;
    int lo[3] = {INT_MAX, INT_MAX, INT_MAX}, hi[3] = {INT_MIN, INT_MIN, INT_MIN};
    const float zero[3] = {0, 0, 0};
    if (!off) off = zero;
    /* cell() is monotonic, so the box of the cells is the cells of the box of the points
     * (not through NaN, nor with an infinite 1 / voxel: then point by point) */
    float x0 = INFINITY, y0 = INFINITY, z0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY, z1 = -INFINITY;
    bool nan = !isfinite(g->inv);
    for (size_t i = 0; i < n; i++) { /* in registers: three chains of min and max */
        const float *p = base + i * stride;
        float x = p[0] + off[0], y = p[1] + off[1], z = p[2] + off[2];
        x0 = x < x0 ? x : x0, y0 = y < y0 ? y : y0, z0 = z < z0 ? z : z0;
        x1 = x > x1 ? x : x1, y1 = y > y1 ? y : y1, z1 = z > z1 ? z : z1;
        nan |= (x != x) | (y != y) | (z != z);
    }
    const float mn[3] = {x0, y0, z0}, mx[3] = {x1, y1, z1};
    for (size_t i = 0; i < (nan ? n : 1); i++) {
        int c[2][3];
        for (int k = 0; k < 3; k++) {
            const float *p = base + i * stride;
            c[0][k] = cell(nan ? p[k] + off[k] : mn[k], g->inv);
            c[1][k] = cell(nan ? p[k] + off[k] : mx[k], g->inv);
        }
        /* + 1: a square's far corners lie one past it */
        int l[3] = {c[0][0] - g->reach, c[0][1] - g->p.depth, c[0][2] - g->reach},
            h[3] = {c[1][0] + g->reach + 1, c[1][1], c[1][2] + g->reach + 1};
        for (int k = 0; k < 3; k++) {
            if (l[k] < lo[k]) lo[k] = l[k];
            if (h[k] > hi[k]) hi[k] = h[k];
        }
    }
    if (lo[1] < g->ymin) lo[1] = g->ymin;
    *none = hi[1] < g->ymin;
    for (int k = 0; k < 3; k++) box[2 * k] = lo[k], box[2 * k + 1] = hi[k];
    return *none || reserve(g, lo, hi);
}

/* The cheaper way to cast n pyramids over a box (by measured costs per step): row by row, or
 * corners and one sum over the box. */
static bool cheaper_direct(const ShadowGrid *g, size_t n, const int box[6]) {
    double rows = 0, vol = (double)(box[1] - box[0] + 1) * (double)(box[3] - box[2] + 1) * (double)(box[5] - box[4] + 1);
    for (int q = 0; q <= g->p.depth; q++) rows += (2 * q + 1) * ((2 * q + 1 + 7) / 8);
    return 15.0 * (double)n * rows < 10.0 * (double)n * (g->p.depth + 1) + 8.0 * vol;
}

/* Voxel index (in the grid, which holds it) to coordinates. */
static inline void voxel_coords(const ShadowGrid *g, uint64_t at, int *I, int *J, int *K) {
    *I = (int)(at % (uint64_t)g->nx) + g->x0;
    *K = (int)(at / (uint64_t)g->nx % (uint64_t)g->nz) + g->z0;
    *J = (int)(at / (uint64_t)g->nx / (uint64_t)g->nz) + g->y0;
}

bool shadow_cast_strided(ShadowGrid *g, const float *base, size_t stride, size_t n, int sign) {
    if (!n) return true;
    int box[6];
    bool none;
    if (!reserve_casters(g, base, stride, n, NULL, box, &none)) return false;
    if (none) return true; /* all below the ground */
    bool direct = cheaper_direct(g, n, box);
    uint32_t weight = sign < 0 ? 0u - 1u : 1u;
    /* casters in grid order, so that neighbouring pyramids (or corners) share the cache */
    uint64_t *order = malloc(2 * n * sizeof *order);
    int ys[2] = {INT_MAX, INT_MIN};
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        const float *p = base + i * stride;
        int I = cell(p[0], g->inv), J = cell(p[1], g->inv), K = cell(p[2], g->inv);
        if (J < g->y0) continue;
        if (order)
            order[m++] = ((uint64_t)(J - g->y0) * (uint64_t)g->nz + (uint64_t)(K - g->z0)) * (uint64_t)g->nx +
                         (uint64_t)(I - g->x0);
        else if (direct) cast_direct(g, I, J, K, weight);
        else cast_one(g, I, J, K, weight, ys);
    }
    if (order) {
        sort_bits(order, order + n, m, 0);
        for (size_t i = 0, j; i < m; i = j) { /* casters in one voxel: one pyramid, weighted */
            for (j = i + 1; j < m && order[j] == order[i]; j++) {}
            int I, J, K;
            voxel_coords(g, order[i], &I, &J, &K);
            uint32_t w = weight * (uint32_t)(j - i); /* wraps: as j - i casts of weight */
            if (direct) cast_direct(g, I, J, K, w);
            else cast_one(g, I, J, K, w, ys);
        }
        free(order);
    }
    if (ys[0] <= ys[1]) integrate(g, ys);
    return true;
}

bool shadow_cast(ShadowGrid *g, const float (*pos)[3], size_t n, int sign) {
    return shadow_cast_strided(g, n ? pos[0] : NULL, 3, n, sign);
}

static inline float voxel_at(const ShadowGrid *g, int I, int J, int K) {
    I -= g->x0, J -= g->y0, K -= g->z0;
    if (I < 0 || J < 0 || K < 0 || I >= g->nx || J >= g->ny || K >= g->nz) return 0;
    return (float)g->s[((size_t)J * (size_t)g->nz + (size_t)K) * (size_t)g->nx + (size_t)I] * (1.0f / SHADOW_ONE);
}

float shadow_at(const ShadowGrid *g, const float pos[3]) {
    if (!g->s) return 0;
    return voxel_at(g, cell(pos[0], g->inv), cell(pos[1], g->inv), cell(pos[2], g->inv));
}

float shadow_light(const ShadowGrid *g, const float pos[3]) {
    float q = g->p.full - shadow_at(g, pos) + g->p.a;
    return q > 0 ? q : 0;
}

void shadow_gradient(const ShadowGrid *g, const float pos[3], float out[3]) {
    out[0] = out[1] = out[2] = 0;
    if (!g->s) return;
    int I = cell(pos[0], g->inv), J = cell(pos[1], g->inv), K = cell(pos[2], g->inv);
    int i = I - g->x0, j = J - g->y0, k = K - g->z0;
    if (i > 0 && j > 0 && k > 0 && i < g->nx - 1 && j < g->ny - 1 && k < g->nz - 1) { /* inside: no test per voxel */
        const size_t nx = (size_t)g->nx, plane = nx * (size_t)g->nz;
        const int32_t *c = g->s + (size_t)j * plane + (size_t)k * nx + (size_t)i;
        const float u = 1.0f / SHADOW_ONE;
        out[0] = 0.5f * ((float)c[-1] * u - (float)c[1] * u);
        out[1] = 0.5f * ((float)c[-(ptrdiff_t)plane] * u - (float)c[plane] * u);
        out[2] = 0.5f * ((float)c[-(ptrdiff_t)nx] * u - (float)c[nx] * u);
        return;
    }
    out[0] = 0.5f * (voxel_at(g, I - 1, J, K) - voxel_at(g, I + 1, J, K));
    out[1] = 0.5f * (voxel_at(g, I, J - 1, K) - voxel_at(g, I, J + 1, K));
    out[2] = 0.5f * (voxel_at(g, I, J, K - 1) - voxel_at(g, I, J, K + 1));
}

/* ---- a set of casters replaced as a whole ---- */

static inline size_t set_slot(const ShadowSet *set, uint64_t key) {
    size_t mask = set->cap - 1, i = (size_t)((key * 0x9E3779B97F4A7C15u) >> 32) & mask;
    while (set->key[i] && set->key[i] != key) i = (i + 1) & mask;
    return i;
}

/* Move the set into cap slots, its keys into the grid's layout now, dropping voxels that
 * neither hold nor will hold a caster. */
static bool set_rebuild(ShadowSet *set, const ShadowGrid *g, size_t cap) {
    uint64_t *key = calloc(cap, sizeof *key);
    uint32_t *count = calloc(cap, sizeof *count), *want = calloc(cap, sizeof *want);
    if (!key || !count || !want) {
        free(key), free(count), free(want);
        return false;
    }
    ShadowSet old = *set;
    set->key = key, set->count = count, set->want = want, set->cap = cap, set->n = 0;
    for (size_t i = 0; i < old.cap; i++) {
        if (!old.key[i] || (!old.count[i] && !old.want[i])) continue;
        uint64_t at = old.key[i] - 1, nx = (uint64_t)old.nx, nz = (uint64_t)old.nz;
        long x = (long)(at % nx) + old.x0, z = (long)(at / nx % nz) + old.z0, y = (long)(at / nx / nz) + old.y0;
        uint64_t k = ((uint64_t)(y - g->y0) * (uint64_t)g->nz + (uint64_t)(z - g->z0)) * (uint64_t)g->nx +
                     (uint64_t)(x - g->x0) + 1;
        size_t j = set_slot(set, k);
        set->key[j] = k, set->count[j] = old.count[i], set->want[j] = old.want[i];
        set->n++;
    }
    set->x0 = g->x0, set->y0 = g->y0, set->z0 = g->z0, set->nx = g->nx, set->nz = g->nz;
    free(old.key), free(old.count), free(old.want);
    return true;
}

/* Count the casters per voxel into want (zero before); false when out of memory. */
static bool set_count(ShadowGrid *g, ShadowSet *set, const float (*pos)[3], size_t n, const float off[3]) {
    for (size_t i = 0; i < n; i++) {
        int I = cell(pos[i][0] + off[0], g->inv), J = cell(pos[i][1] + off[1], g->inv),
            K = cell(pos[i][2] + off[2], g->inv);
        if (J < g->y0) continue; /* below the ground: casts nothing (as in shadow_cast) */
        uint64_t k = ((uint64_t)(J - g->y0) * (uint64_t)g->nz + (uint64_t)(K - g->z0)) * (uint64_t)g->nx +
                     (uint64_t)(I - g->x0) + 1;
        /* a table at most a quarter full: most look-ups end at their first slot */
        if (4 * (set->n + 1) > set->cap && !set_rebuild(set, g, 2 * set->cap)) return false;
        size_t slot = set_slot(set, k);
        if (!set->key[slot]) set->key[slot] = k, set->n++;
        set->want[slot]++;
    }
    return true;
}

bool shadow_set_replace(ShadowGrid *g, ShadowSet *set, const float (*pos)[3], size_t n, const float off[3]) {
    /* the grid grows to hold the new casters first, as shadow_cast would grow it for them */
    int box[6];
    bool none = true;
    if (n && !reserve_casters(g, pos[0], 3, n, off, box, &none)) return false;
    if (!set->cap || set->x0 != g->x0 || set->y0 != g->y0 || set->z0 != g->z0 || set->nx != g->nx ||
        set->nz != g->nz) {
        if (!set_rebuild(set, g, set->cap ? set->cap : 1024)) return false;
    }
    bool ok = none || set_count(g, set, pos, n, off);
    if (ok && set->delta_cap < set->n) {
        uint64_t *d = realloc(set->delta, 2 * set->n * sizeof *d); /* and as much to sort through */
        if (d) set->delta = d, set->delta_cap = set->n;
        ok = d != NULL;
    }
    if (!ok) {
        memset(set->want, 0, set->cap * sizeof *set->want);
        return false;
    }
    /* the changed voxels, their index above 32 bits (grids hold fewer than 2^32 voxels) and
     * the change in count below */
    size_t nd = 0, dead = 0;
    int lo[3] = {INT_MAX, INT_MAX, INT_MAX}, hi[3] = {INT_MIN, INT_MIN, INT_MIN};
    for (size_t i = 0; i < set->cap; i++) {
        if (!set->key[i]) continue;
        uint32_t d = set->want[i] - set->count[i]; /* wraps: the shadow is kept modulo 2^32 too */
        set->count[i] = set->want[i];
        set->want[i] = 0;
        dead += set->count[i] == 0;
        if (!d) continue;
        uint64_t at = set->key[i] - 1;
        set->delta[nd++] = at << 32 | d;
        int c[3];
        voxel_coords(g, at, &c[0], &c[1], &c[2]);
        for (int k = 0; k < 3; k++) {
            if (c[k] < lo[k]) lo[k] = c[k];
            if (c[k] > hi[k]) hi[k] = c[k];
        }
    }
    if (nd) {
        /* the box as shadow_cast_strided measures it, for the cheaper way to cast */
        int vb[6] = {lo[0] - g->reach, hi[0] + g->reach + 1, lo[1] - g->p.depth, hi[1],
                     lo[2] - g->reach, hi[2] + g->reach + 1};
        if (vb[2] < g->ymin) vb[2] = g->ymin;
        bool direct = cheaper_direct(g, nd, vb);
        sort_bits(set->delta, set->delta + nd, nd, 32); /* grid order: pyramids share the cache */
        int ys[2] = {INT_MAX, INT_MIN};
        for (size_t i = 0; i < nd; i++) {
            int I, J, K;
            voxel_coords(g, set->delta[i] >> 32, &I, &J, &K);
            uint32_t w = (uint32_t)set->delta[i];
            if (direct) cast_direct(g, I, J, K, w);
            else cast_one(g, I, J, K, w, ys);
        }
        if (ys[0] <= ys[1]) integrate(g, ys);
    }
    /* voxels left without casters only lengthen the probes: drop them now and then */
    if (dead && 4 * dead > set->n) (void)set_rebuild(set, g, set->cap); /* kept as it is when out of memory */
    return true;
}

void shadow_set_free(ShadowSet *set) {
    free(set->key);
    free(set->count);
    free(set->want);
    free(set->delta);
    memset(set, 0, sizeof *set);
}
