/* Slope and aspect by Horn's (1981) 3×3 window, in degrees, as `gdaldem slope` and
 * `gdaldem aspect` compute them: slope = atan |∇h|, aspect = the azimuth (clockwise from
 * north) of the downhill direction −∇h, −1 where the window is flat. Border cells read their
 * missing neighbours as copies of the nearest edge cell. */
#include <math.h>

#include "terrain/terrain.h"
#include "util/parallel.h"

typedef struct Job {
    const Terrain *t;
    float *slope, *aspect;
} Job;

static void rows(void *ctx, size_t lo, size_t hi, int thread) {
    (void)thread;
    const Job *j = ctx;
    const Terrain *t = j->t;
    const double deg = 180 / M_PI;
    for (size_t k = lo; k < hi; k++)
        for (int i = 0; i < t->nx; i++) {
            double gx, gz;
            terrain_horn(t, i, (int)k, &gx, &gz);
            size_t c = k * (size_t)t->nx + (size_t)i;
            j->slope[c] = (float)(atan(sqrt(gx * gx + gz * gz)) * deg);
            if (gx == 0 && gz == 0) {
                j->aspect[c] = -1;
                continue;
            }
            /* The downhill direction is (−gx east, −gz south), i.e. (−gx, +gz) in east–north;
             * its azimuth from north, clockwise, is atan2(east, north). */
            double a = atan2(-gx, gz) * deg + 0.0; /* + 0.0: never -0 */
            if (a < 0) a += 360;
            float f = (float)a;
            j->aspect[c] = f >= 360 ? 0 : f; /* 359.99999999 rounds to 360 in float */
        }
}

void terrain_slope_aspect(const Terrain *t, float *slope, float *aspect, int threads) {
    Job j = {t, slope, aspect};
    par_for(threads, (size_t)t->nz, 16, rows, &j);
}
