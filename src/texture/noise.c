/* Perlin's gradient noise in two dimensions, periodic, and its sum of octaves. */

/* Periodic so that textures tile; the octaves as in Picek 2015, equations (2.16)-(2.18). Gradients come from a hash of the
 * lattice point, so there is no table to initialise and every call is reproducible. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "texture/texture.h"

static inline uint32_t hash3(uint32_t x, uint32_t y, uint32_t seed) {
    uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ seed * 0xcb1ab31fu;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}

/* Eight unit gradients, 45 degrees apart. */
static const float grad[8][2] = {
    {1, 0}, {0.70710678f, 0.70710678f}, {0, 1}, {-0.70710678f, 0.70710678f},
    {-1, 0}, {-0.70710678f, -0.70710678f}, {0, -1}, {0.70710678f, -0.70710678f},
};

static inline float fade(float t) { return t * t * t * (t * (t * 6 - 15) + 10); }

static inline int wrap(int i, int period) {
    if (period <= 0 || (unsigned)i < (unsigned)period) return i; /* the common case needs no division */
    i %= period;
    return i < 0 ? i + period : i;
}

static inline float corner(uint32_t hx, uint32_t hy, float dx, float dy, uint32_t seed) {
    const float *g = grad[hash3(hx, hy, seed) & 7];
    return g[0] * dx + g[1] * dy;
}

static inline float dot_grad(int k, float dx, float dy) { return grad[k][0] * dx + grad[k][1] * dy; }

/* g: the lattice's gradient indices (px * py, row by row), or NULL to hash each corner. */
static float noise_at(float x, float y, int px, int py, uint32_t seed, const uint8_t *g) {
    float fx = floorf(x), fy = floorf(y);
    int ix = (int)fx, iy = (int)fy;
    float dx = x - fx, dy = y - fy;
    int x0 = wrap(ix, px), y0 = wrap(iy, py);
    int x1 = px > 0 && x0 + 1 == px ? 0 : x0 + 1, y1 = py > 0 && y0 + 1 == py ? 0 : y0 + 1;
    float n00, n10, n01, n11;
    if (g) {
        n00 = dot_grad(g[y0 * px + x0], dx, dy), n10 = dot_grad(g[y0 * px + x1], dx - 1, dy);
        n01 = dot_grad(g[y1 * px + x0], dx, dy - 1), n11 = dot_grad(g[y1 * px + x1], dx - 1, dy - 1);
    } else {
        n00 = corner((uint32_t)x0, (uint32_t)y0, dx, dy, seed);
        n10 = corner((uint32_t)x1, (uint32_t)y0, dx - 1, dy, seed);
        n01 = corner((uint32_t)x0, (uint32_t)y1, dx, dy - 1, seed);
        n11 = corner((uint32_t)x1, (uint32_t)y1, dx - 1, dy - 1, seed);
    }
    float u = fade(dx), v = fade(dy);
    float a = n00 + u * (n10 - n00), b = n01 + u * (n11 - n01);
    return 1.41421356f * (a + v * (b - a)); /* 2D gradient noise peaks at 1/sqrt(2) */
}

float noise2(float x, float y, int px, int py, uint32_t seed) { return noise_at(x, y, px, py, seed, NULL); }

/* A texture asks one fbm at every pixel: its lattices' gradients are hashed once, not four
 * times a pixel and octave (the same indices, so the same values to the bit). */
void fbm_init(Fbm *f, int fx, int fy, float p, int octaves, uint32_t seed) {
    *f = (Fbm){.fx = fx, .fy = fy, .p = p, .octaves = octaves < FBM_OCTAVES ? octaves : FBM_OCTAVES, .seed = seed};
    for (int i = 0; i < f->octaves; i++) {
        int px = fx << i, py = fy << i;
        if (px <= 0 || py <= 0 || (size_t)px * (size_t)py > (1u << 20)) continue; /* not periodic: hashed */
        uint8_t *g = f->g[i] = malloc((size_t)px * (size_t)py);
        for (int y = 0; g && y < py; y++)
            for (int x = 0; x < px; x++) g[y * px + x] = hash3((uint32_t)x, (uint32_t)y, seed + (uint32_t)i * 101u) & 7;
    }
}

float fbm_at(const Fbm *f, float x, float y) {
    float sum = 0, norm = 0, a = 1;
    int fx = f->fx, fy = f->fy;
    for (int i = 0; i < f->octaves; i++) {
        sum += a * noise_at(x * (float)fx, y * (float)fy, fx, fy, f->seed + (uint32_t)i * 101u, f->g[i]);
        norm += a;
        a *= f->p;
        fx *= 2;
        fy *= 2;
    }
    return norm > 0 ? sum / norm : 0;
}

bool fbm_axis(const Fbm *f, int axis, const float *at, int n, FbmCell *cells) {
    int freq = axis ? f->fy : f->fx;
    for (int i = 0; i < f->octaves; i++, freq *= 2) {
        if (!f->g[i]) return false;
        for (int k = 0; k < n; k++) { /* noise_at's steps for this axis, in its order */
            float x = at[k] * (float)freq, fx = floorf(x), d = x - fx;
            int i0 = wrap((int)fx, freq);
            cells[i * n + k] = (FbmCell){i0, freq > 0 && i0 + 1 == freq ? 0 : i0 + 1, d, fade(d)};
        }
    }
    return true;
}

float fbm_grid_at(const Fbm *f, const FbmCell *cx, int nx, int kx, const FbmCell *cy, int ny, int ky) {
    float sum = 0, norm = 0, a = 1;
    int px = f->fx;
    for (int i = 0; i < f->octaves; i++, px *= 2) {
        const FbmCell *x = &cx[i * nx + kx], *y = &cy[i * ny + ky];
        const uint8_t *g = f->g[i];
        float dx = x->d, dy = y->d;
        float n00 = dot_grad(g[y->i0 * px + x->i0], dx, dy), n10 = dot_grad(g[y->i0 * px + x->i1], dx - 1, dy);
        float n01 = dot_grad(g[y->i1 * px + x->i0], dx, dy - 1), n11 = dot_grad(g[y->i1 * px + x->i1], dx - 1, dy - 1);
        float u = x->w, v = y->w;
        float lo = n00 + u * (n10 - n00), hi = n01 + u * (n11 - n01);
        sum += a * (1.41421356f * (lo + v * (hi - lo)));
        norm += a;
        a *= f->p;
    }
    return norm > 0 ? sum / norm : 0;
}

#ifdef __SSE2__
_Static_assert(sizeof(FbmCell) == 16 && offsetof(FbmCell, d) == 8 && offsetof(FbmCell, w) == 12, "fbm_grid_row loads cells as four floats");
#endif

void fbm_grid_row(const Fbm *f, const FbmCell *cx, int nx, const FbmCell *cy, int ny, int ky, float *out) {
    float norm = 0, a = 1;
    int px = f->fx;
    for (int x = 0; x < nx; x++) out[x] = 0; /* as sum = 0: 0 + the first octave, to the bit */
    for (int i = 0; i < f->octaves; i++, px *= 2) {
        const FbmCell *c = &cx[i * nx], *y = &cy[i * ny + ky];
        const uint8_t *r0 = f->g[i] + (size_t)y->i0 * (size_t)px, *r1 = f->g[i] + (size_t)y->i1 * (size_t)px;
        float dy = y->d, dy1 = dy - 1, v = y->w;
        for (int x0 = 0, x1; x0 < nx; x0 = x1) {
            int i0 = c[x0].i0, i1 = c[x0].i1; /* a run of columns in one lattice cell: its four gradients */
            for (x1 = x0 + 1; x1 < nx && c[x1].i0 == i0;) x1++;
            const float *g00 = grad[r0[i0]], *g10 = grad[r0[i1]], *g01 = grad[r1[i0]], *g11 = grad[r1[i1]];
            float t00 = g00[1] * dy, t10 = g10[1] * dy, t01 = g01[1] * dy1, t11 = g11[1] * dy1;
            int x = x0;
#ifdef __SSE2__
            /* four columns at a time: the same operations on each lane, so the same bits */
            const __m128 G00 = _mm_set1_ps(g00[0]), G10 = _mm_set1_ps(g10[0]), G01 = _mm_set1_ps(g01[0]);
            const __m128 G11 = _mm_set1_ps(g11[0]), T00 = _mm_set1_ps(t00), T10 = _mm_set1_ps(t10);
            const __m128 T01 = _mm_set1_ps(t01), T11 = _mm_set1_ps(t11), one = _mm_set1_ps(1);
            const __m128 A = _mm_set1_ps(a), R2 = _mm_set1_ps(1.41421356f), V = _mm_set1_ps(v);
            for (; x + 4 <= x1; x += 4) {
                const float *f = (const float *)&c[x]; /* four cells {i0, i1, d, w} (_mm_loadu_ps may alias) */
                __m128 c0 = _mm_loadu_ps(f), c1 = _mm_loadu_ps(f + 4), c2 = _mm_loadu_ps(f + 8), c3 = _mm_loadu_ps(f + 12);
                __m128 h01 = _mm_unpackhi_ps(c0, c1), h23 = _mm_unpackhi_ps(c2, c3); /* d0 d1 w0 w1, d2 d3 w2 w3 */
                __m128 dx = _mm_movelh_ps(h01, h23), u = _mm_movehl_ps(h23, h01);
                __m128 dx1 = _mm_sub_ps(dx, one);
                __m128 n00 = _mm_add_ps(_mm_mul_ps(G00, dx), T00), n10 = _mm_add_ps(_mm_mul_ps(G10, dx1), T10);
                __m128 n01 = _mm_add_ps(_mm_mul_ps(G01, dx), T01), n11 = _mm_add_ps(_mm_mul_ps(G11, dx1), T11);
                __m128 lo = _mm_add_ps(n00, _mm_mul_ps(u, _mm_sub_ps(n10, n00)));
                __m128 hi = _mm_add_ps(n01, _mm_mul_ps(u, _mm_sub_ps(n11, n01)));
                __m128 val = _mm_mul_ps(A, _mm_mul_ps(R2, _mm_add_ps(lo, _mm_mul_ps(V, _mm_sub_ps(hi, lo)))));
                _mm_storeu_ps(out + x, _mm_add_ps(_mm_loadu_ps(out + x), val));
            }
#endif
            for (; x < x1; x++) { /* fbm_grid_at's steps, in its order */
                float dx = c[x].d, dx1 = dx - 1, u = c[x].w;
                float n00 = g00[0] * dx + t00, n10 = g10[0] * dx1 + t10, n01 = g01[0] * dx + t01, n11 = g11[0] * dx1 + t11;
                float lo = n00 + u * (n10 - n00), hi = n01 + u * (n11 - n01);
                out[x] += a * (1.41421356f * (lo + v * (hi - lo)));
            }
        }
        norm += a;
        a *= f->p;
    }
    int x = 0;
#ifdef __SSE2__
    if (norm > 0)
        for (__m128 n = _mm_set1_ps(norm); x + 4 <= nx; x += 4) _mm_storeu_ps(out + x, _mm_div_ps(_mm_loadu_ps(out + x), n));
#endif
    for (; x < nx; x++) out[x] = norm > 0 ? out[x] / norm : 0;
}

void fbm_free(Fbm *f) {
    for (int i = 0; i < FBM_OCTAVES; i++) free(f->g[i]);
}
