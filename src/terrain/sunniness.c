/* Zamuda's (2006) sunniness, his Algorithm 5 (Appendix B): one day's sun, N_l positions (odd)
 * on two straight segments of directions, from sunrise p_0 = east + 0.37 north through noon
 * p_mid = (0, sin e, cos e) toward the equator at the elevation e = 90° − latitude to sunset
 * p_{N−1} = west + 0.37 north (his eq. 4.11–4.13; 0.37 is his year's mean shift of sunrise
 * toward the pole at 46°, kept at every latitude; the afternoon segment starts at p_mid,
 * where his 4.13 prints p_0). Each sample gives the cosine between the patch's normal and the
 * sun, or l_ambient when the sun is behind the patch (4.15), times l_ambient again when the
 * terrain toward the sun rises above it (the march of his wind, one patch width a step, to
 * the edge), weighted from 1 at sunrise and sunset to 2 at noon (4.16); sunniness is the sum
 * over N_l (4.17). The normal is the patch's by Horn's window, as the slope's: Sylva's cells
 * are his vertices. Rows are independent, so the result does not depend on the threads. */
#include <math.h>

#include "terrain/terrain.h"
#include "util/parallel.h"

enum { MAX_SUNS = 1001 };

typedef struct Sun {
    double dir[3];   /* unit, y up */
    double flat_dx, flat_dz, tan_e; /* the horizontal direction toward it and its elevation's tangent */
    double weight;
    int quad;        /* horizon.c's quadrant of its direction */
} Sun;

typedef struct Job {
    const Terrain *t;
    const Sun *sun;
    int nsun;
    double ambient;
    const float *bound; /* horizon.c's tangent bounds, 4 grids */
    float *out;
} Job;

static bool shadowed(const Terrain *t, const Sun *s, int i, int k, double h) {
    if (!(s->flat_dx != 0 || s->flat_dz != 0)) return false; /* the zenith */
    double x = t->x0 + (i + 0.5) * t->cell, z = t->z0 + (k + 0.5) * t->cell;
    double xlo = t->x0 + t->cell / 2, xhi = t->x0 + (t->nx - 0.5) * t->cell;
    double zlo = t->z0 + t->cell / 2, zhi = t->z0 + (t->nz - 0.5) * t->cell, e = 1e-9 * t->cell;
    for (long step = 1;; step++) {
        double d = step * t->cell, sx = x + s->flat_dx * d, sz = z + s->flat_dz * d;
        if (sx < xlo - e || sx > xhi + e || sz < zlo - e || sz > zhi + e) return false; /* the edge: lit */
        if ((terrain_height_at(t, sx, sz) - h) / d > s->tan_e) return true;
    }
}

static void rows(void *ctx, size_t lo, size_t hi, int thread) {
    (void)thread;
    const Job *j = ctx;
    const Terrain *t = j->t;
    size_t n = (size_t)t->nx * (size_t)t->nz;
    for (size_t k = lo; k < hi; k++)
        for (int i = 0; i < t->nx; i++) {
            size_t c = k * (size_t)t->nx + (size_t)i;
            double gx, gz;
            terrain_horn(t, i, (int)k, &gx, &gz);
            double len = sqrt(gx * gx + 1 + gz * gz), nrm[3] = {-gx / len, 1 / len, -gz / len};
            double sum = 0;
            for (int s = 0; s < j->nsun; s++) {
                const Sun *S = &j->sun[s];
                double cosa = nrm[0] * S->dir[0] + nrm[1] * S->dir[1] + nrm[2] * S->dir[2];
                double l = cosa >= 0 ? cosa : j->ambient; /* (4.15) */
                double b = j->bound[(size_t)S->quad * n + c]; /* a float: a margin for its rounding */
                if (cosa >= 0 && !(S->tan_e >= b + fabs(b) * 1e-6) &&
                    shadowed(t, S, i, (int)k, t->height[c]))
                    l *= j->ambient;
                sum += l * S->weight;
            }
            j->out[c] = (float)(sum / j->nsun);
        }
}

int terrain_sunniness(Terrain *t, double latitude, int samples, double ambient, float *out, int threads, const SylSink *sink) {
    if (samples < 3 || samples > MAX_SUNS || samples % 2 == 0) {
        sink_error(sink, "Zamuda's sunniness takes an odd number of sun samples from 3 to %d, not %d",
                          MAX_SUNS, samples);
        return SYL_EUSAGE;
    }
    Sun sun[MAX_SUNS];
    /* Toward the equator: south (+z) in the north, north (−z) in the south. */
    double pole = latitude >= 0 ? -1 : 1, e = (90 - fabs(latitude)) * (M_PI / 180);
    const double p0[3] = {1, 0, 0.37 * pole}, mid[3] = {0, sin(e), -cos(e) * pole}, p1[3] = {-1, 0, 0.37 * pole};
    int half = (samples - 1) / 2;
    for (int s = 0; s < samples; s++) {
        double u = (double)s / half, p[3];
        for (int a = 0; a < 3; a++) p[a] = s <= half ? p0[a] + u * (mid[a] - p0[a]) : mid[a] + (u - 1) * (p1[a] - mid[a]);
        double len = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), flat = hypot(p[0], p[2]);
        Sun *S = &sun[s];
        for (int a = 0; a < 3; a++) S->dir[a] = p[a] / len;
        S->flat_dx = flat > 0 ? p[0] / flat : 0, S->flat_dz = flat > 0 ? p[2] / flat : 0;
        S->tan_e = flat > 0 ? p[1] / flat : INFINITY;
        S->weight = s <= half ? 1 + u : 3 - u; /* (4.16) */
        S->quad = (S->flat_dx > 0 ? 1 : 0) | (S->flat_dz > 0 ? 2 : 0);
    }
    float *bound = (float *)terrain_grid(t, 4 * sizeof(float), sink);
    float *scratch = bound ? (float *)terrain_grid(t, 2 * sizeof(float), sink) : NULL;
    if (!scratch) {
        terrain_grid_free(t, bound, 4 * sizeof(float));
        return SYL_ELIMIT;
    }
    terrain_horizon_bound(t, bound, scratch);
    terrain_grid_free(t, scratch, 2 * sizeof(float));
    Job j = {t, sun, samples, ambient, bound, out};
    par_for(threads, (size_t)t->nz, 4, rows, &j);
    terrain_grid_free(t, bound, 4 * sizeof(float));
    return SYL_OK;
}
