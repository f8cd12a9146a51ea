/* Zamuda's (2006) humidity, his Algorithm 3: every patch gets the same rain, 1 (plus 10 where
 * its normalised height is below the water level); then, highest patch first, each sheds
 * m · s · k_m of its water in equal parts to its lower 4-neighbours, s = 1 − n_y his slope;
 * then a 5-point average is applied 10 times. Sylva reads Δm as his Algorithm writes it, with
 * the patch's water m (his eq. 4.6 leaves m out): water is then conserved and never negative
 * (Sylva keeps the share shed, s · k_m, at most 1, so that any k_m
 * does). The blur repeats the edge cells (his stencil's m_{i,k+1} twice is read as a
 * misprint of m_{i,k−1}). Sequential by nature (each patch's water waits for the patches
 * above it), so the thread count has nothing to change. */
#include <math.h>
#include <stdlib.h>

#include "terrain/terrain.h"

typedef struct Order {
    float h;
    uint32_t k, i;
} Order;

/* Highest first; ties in grid order (a tie never exchanges water, so only the order of the
 * additions into a shared lower neighbour depends on it). */
static int higher_first(const void *a, const void *b) {
    const Order *x = a, *y = b;
    if (x->h != y->h) return x->h > y->h ? -1 : 1;
    if (x->k != y->k) return x->k < y->k ? -1 : 1;
    return (x->i > y->i) - (x->i < y->i);
}

int terrain_runoff(Terrain *t, const float *slope, double k_m, double water_level, float *out, const SylSink *sink) {
    int nx = t->nx, nz = t->nz;
    size_t n = (size_t)nx * (size_t)nz;
    double *m = (double *)terrain_grid(t, sizeof(double), sink);
    double *tmp = m ? (double *)terrain_grid(t, sizeof(double), sink) : NULL;
    Order *o = tmp ? (Order *)terrain_grid(t, sizeof(Order), sink) : NULL;
    if (!o) {
        terrain_grid_free(t, m, sizeof(double));
        terrain_grid_free(t, tmp, sizeof(double));
        return SYL_ELIMIT;
    }
    float lo = INFINITY, hi = -INFINITY;
    for (size_t c = 0; c < n; c++) lo = fminf(lo, t->height[c]), hi = fmaxf(hi, t->height[c]);
    for (int k = 0; k < nz; k++)
        for (int i = 0; i < nx; i++) {
            size_t c = (size_t)k * (size_t)nx + (size_t)i;
            double y = hi > lo ? (t->height[c] - lo) / (double)(hi - lo) : 0; /* his ȳ (4.2) */
            m[c] = 1 + (y < water_level ? 10 : 0);                             /* (4.5) */
            o[c] = (Order){t->height[c], (uint32_t)k, (uint32_t)i};
        }
    qsort(o, n, sizeof *o, higher_first);
    static const int di[4] = {1, -1, 0, 0}, dk[4] = {0, 0, 1, -1};
    for (size_t j = 0; j < n; j++) {
        int i = (int)o[j].i, k = (int)o[j].k;
        size_t c = (size_t)k * (size_t)nx + (size_t)i;
        size_t lower[4];
        int nl = 0;
        for (int d = 0; d < 4; d++) {
            int a = i + di[d], b = k + dk[d];
            if (a < 0 || a >= nx || b < 0 || b >= nz) continue;
            size_t e = (size_t)b * (size_t)nx + (size_t)a;
            if (t->height[e] < t->height[c]) lower[nl++] = e;
        }
        if (!nl) continue;
        double s = 1 - cos(slope[c] * (M_PI / 180)); /* his slope 1 − n_y (4.3) */
        double share = s * k_m < 1 ? s * k_m : 1;
        double dm = m[c] * share / nl;                /* (4.6) with m, as Algorithm 3 */
        for (int d = 0; d < nl; d++) m[lower[d]] += dm; /* (4.7) */
        m[c] -= nl * dm;                                /* (4.8) */
    }
    for (int pass = 0; pass < 10; pass++) { /* N_mblur */
        for (int k = 0; k < nz; k++)
            for (int i = 0; i < nx; i++) {
                size_t c = (size_t)k * (size_t)nx + (size_t)i;
                size_t w = i > 0 ? c - 1 : c, e = i + 1 < nx ? c + 1 : c;
                size_t nn = k > 0 ? c - (size_t)nx : c, s = k + 1 < nz ? c + (size_t)nx : c;
                tmp[c] = (m[c] + (m[w] + m[e]) + (m[nn] + m[s])) / 5;
            }
        double *sw = m;
        m = tmp, tmp = sw;
    }
    for (size_t c = 0; c < n; c++) out[c] = (float)m[c];
    terrain_grid_free(t, m, sizeof(double));
    terrain_grid_free(t, tmp, sizeof(double));
    terrain_grid_free(t, o, sizeof(Order));
    return SYL_OK;
}
