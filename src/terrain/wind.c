/* Wind exposure: Winstral, Elder & Davis's (2002) maximum upwind slope Sx. From each cell's
 * centre the terrain is sampled every cell width toward where the wind comes from, up to the
 * search distance, and Sx is the largest angle up to a sample, atan((h_s − h) / distance):
 * positive behind a ridge (sheltered), negative where the terrain falls away upwind
 * (exposed), 0 where no sample lies on the grid. Heights between cell centres are bilinear. */
#include <math.h>

#include "terrain/terrain.h"
#include "util/parallel.h"

typedef struct Job {
    const Terrain *t;
    double ux, uz; /* unit vector toward the wind's origin */
    int steps;
    float *out;
} Job;

static void rows(void *ctx, size_t lo, size_t hi, int thread) {
    (void)thread;
    const Job *j = ctx;
    const Terrain *t = j->t;
    double xlo = t->x0 + t->cell / 2, xhi = t->x0 + (t->nx - 0.5) * t->cell;
    double zlo = t->z0 + t->cell / 2, zhi = t->z0 + (t->nz - 0.5) * t->cell;
    for (size_t k = lo; k < hi; k++)
        for (int i = 0; i < t->nx; i++) {
            size_t c = k * (size_t)t->nx + (size_t)i;
            double x = t->x0 + (i + 0.5) * t->cell, z = t->z0 + (k + 0.5) * t->cell, h = t->height[c];
            double best = -INFINITY; /* the largest rise per distance; one atan at the end */
            for (int s = 1; s <= j->steps; s++) {
                double d = s * t->cell, sx = x + j->ux * d, sz = z + j->uz * d;
                /* a little slack: a march along a row or column stays on it despite rounding */
                double e = 1e-9 * t->cell;
                if (sx < xlo - e || sx > xhi + e || sz < zlo - e || sz > zhi + e) break;
                double r = (terrain_height_at(t, sx, sz) - h) / d;
                if (r > best) best = r;
            }
            j->out[c] = best == -INFINITY ? 0 : (float)(atan(best) * (180 / M_PI));
        }
}

void terrain_wind(const Terrain *t, double from, double dmax, float *out, int threads) {
    double a = from * (M_PI / 180);
    /* Azimuth a (clockwise from north) in x–z: east is +x, north is −z. */
    Job j = {t, sin(a), -cos(a), (int)floor(dmax / t->cell + 1e-9), out};
    if (j.steps > 1 << 20) j.steps = 1 << 20;
    par_for(threads, (size_t)t->nz, 8, rows, &j);
}
