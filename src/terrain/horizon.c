/* Upper bounds of the tangent of a cell's horizon in each quadrant of directions: what
 * spares the insolation most of its rays. A ray toward a sun whose direction has signs
 * (sx, sz) in x and z stays in that quadrant of the cell. W_L, the highest height at
 * offsets from −1 to 2^L cells toward the quadrant in both x and z, comes from W_{L−1} by
 * doubling (a separable max of two shifted copies). The terrain between cells is the
 * triangles through their centres, whose heights never pass their corners'; a point of a
 * square whose nearest corner is j ≥ 1 cells away (Chebyshev) is at least j cells away and
 * no higher than corners up to j + 1 away. So the points with j in [2^(L−1), 2^L − 1] rise
 * at most (W_L − h) / (2^(L−1) · cell) per distance, and those of the cell's own squares
 * (j = 0), whose heights are linear from the centre, at most (W_0 − h) / cell. The bound is
 * the largest of these. (The offset −1 keeps a ray along a row or column, which may touch
 * the squares on either side of it, inside the window.) */
#include <math.h>
#include <string.h>

#include "terrain/terrain.h"

/* out = max(in, in shifted by a and by b along x or z), indices clamped to the grid. */
static void shift_max(const Terrain *t, const float *in, float *out, int a, int b, int along_x) {
    int nx = t->nx, nz = t->nz;
    for (int k = 0; k < nz; k++)
        for (int i = 0; i < nx; i++) {
            const float *r = in + (size_t)k * nx;
            float m = r[i];
            if (along_x) {
                int p = i + a < 0 ? 0 : i + a >= nx ? nx - 1 : i + a;
                int q = i + b < 0 ? 0 : i + b >= nx ? nx - 1 : i + b;
                m = fmaxf(m, fmaxf(r[p], r[q]));
            } else {
                int p = k + a < 0 ? 0 : k + a >= nz ? nz - 1 : k + a;
                int q = k + b < 0 ? 0 : k + b >= nz ? nz - 1 : k + b;
                m = fmaxf(m, fmaxf(in[(size_t)p * nx + i], in[(size_t)q * nx + i]));
            }
            out[(size_t)k * nx + i] = m;
        }
}

void terrain_horizon_bound(const Terrain *t, float *bound, float *scratch) {
    size_t n = (size_t)t->nx * (size_t)t->nz;
    int side = t->nx > t->nz ? t->nx : t->nz;
    float *w = scratch, *tmp = scratch + n;
    for (int quad = 0; quad < 4; quad++) {
        int sx = quad & 1 ? 1 : -1, sz = quad & 2 ? 1 : -1;
        float *b = bound + (size_t)quad * n;
        shift_max(t, t->height, tmp, -sx, sx, 1); /* W_0: offsets −1..1 */
        shift_max(t, tmp, w, -sz, sz, 0);
        for (size_t c = 0; c < n; c++) b[c] = (float)((w[c] - t->height[c]) / t->cell);
        for (int L = 1; (1 << (L - 1)) < side; L++) {
            int s = 1 << (L - 1); /* W_L from W_{L−1}: offsets −1..2^L */
            shift_max(t, w, tmp, 0, sx * s, 1);
            shift_max(t, tmp, w, 0, sz * s, 0);
            double d = (double)s * t->cell;
            for (size_t c = 0; c < n; c++) {
                float r = (float)((w[c] - t->height[c]) / d);
                if (r > b[c]) b[c] = r;
            }
        }
    }
}
