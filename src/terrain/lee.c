/* Zamuda's (2006) windiness, his Algorithm 4: wind of strength 1 blows over the whole terrain
 * from one direction; from each patch's centre the terrain is sampled upwind, one patch width
 * apart, for N_w samples (stopping at the edge), and the lee angle φ is the steepest
 * angle up to a sample, atan((h_w − h) / d) (his eq. 4.9), at least 0. His printed rule
 * (4.10), "w = φ if φ ≤ Θ0, otherwise 1", uses an angle as a [0, 1] value and takes a minimum
 * that is never above 0; Sylva reads it as w = 1 − φ / Θ0 for φ ≤ Θ0 and 1 above Θ0 (the wind
 * comes back down behind a wall steeper than Θ0): 1 in the open, 0 fully sheltered. Unlike
 * Winstral's Sx (wind.c) the search is N_w patches however large a patch is, and terrain
 * falling away upwind makes a patch no windier than open ground. */
#include <math.h>

#include "terrain/terrain.h"
#include "util/parallel.h"

typedef struct Job {
    const Terrain *t;
    double ux, uz; /* unit vector toward the wind's origin */
    int samples;
    double theta0; /* radians */
    float *out;
} Job;

static void rows(void *ctx, size_t lo, size_t hi, int thread) {
    (void)thread;
    const Job *j = ctx;
    const Terrain *t = j->t;
    for (size_t k = lo; k < hi; k++)
        for (int i = 0; i < t->nx; i++) {
            /* the steepest rise per distance upwind, at least level */
            double phi = atan(fmax(0, terrain_max_rise(t, (size_t)i, k, j->ux, j->uz, j->samples)));
            j->out[k * (size_t)t->nx + (size_t)i] = phi <= j->theta0 ? (float)(1 - phi / j->theta0) : 1;
        }
}

void terrain_lee(const Terrain *t, double from, int samples, double theta0_deg, float *out, int threads) {
    double a = from * (M_PI / 180);
    /* Azimuth a (clockwise from north) in x–z: east is +x, north is −z. */
    Job j = {t, sin(a), -cos(a), samples, theta0_deg * (M_PI / 180), out};
    par_for(threads, (size_t)t->nz, 8, rows, &j);
}
