/* The topographic wetness index of Beven & Kirkby (1979), ln(a / tan β): a the specific
 * catchment area, the upslope area per unit contour width (here the D8 accumulation times
 * the cell's area, over the cell's width), and β the local slope, whose tangent is kept at
 * least TERRAIN_MIN_TAN so that flats get a large finite value. */
#include <math.h>

#include "terrain/terrain.h"
#include "util/parallel.h"

typedef struct Job {
    const Terrain *t;
    const float *acc, *slope;
    float *out;
} Job;

static void rows(void *ctx, size_t lo, size_t hi, int thread) {
    (void)thread;
    const Job *j = ctx;
    size_t nx = (size_t)j->t->nx;
    for (size_t c = lo * nx; c < hi * nx; c++) {
        double tb = tan(j->slope[c] * (M_PI / 180));
        if (!(tb > TERRAIN_MIN_TAN)) tb = TERRAIN_MIN_TAN;
        j->out[c] = (float)log(j->acc[c] * j->t->cell / tb);
    }
}

void terrain_wetness(const Terrain *t, const float *acc, const float *slope, float *out, int threads) {
    Job j = {t, acc, slope, out};
    par_for(threads, (size_t)t->nz, 16, rows, &j);
}
