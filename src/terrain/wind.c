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
    for (size_t k = lo; k < hi; k++)
        for (int i = 0; i < t->nx; i++) {
            double best = terrain_max_rise(t, (size_t)i, k, j->ux, j->uz, j->steps); /* one atan at the end */
            j->out[k * (size_t)t->nx + (size_t)i] = best == -INFINITY ? 0 : (float)(atan(best) * (180 / M_PI));
        }
}

void terrain_wind(const Terrain *t, double from, double dmax, float *out, int threads) {
    double a = from * (M_PI / 180);
    /* Azimuth a (clockwise from north) in x–z: east is +x, north is −z. */
    Job j = {t, sin(a), -cos(a), (int)floor(dmax / t->cell + 1e-9), out};
    if (j.steps > 1 << 20) j.steps = 1 << 20;
    par_for(threads, (size_t)t->nz, 8, rows, &j);
}
