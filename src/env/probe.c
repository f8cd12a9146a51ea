/* ?E answers: see probe.h. */
#include "env/probe.h"

#include <math.h>

#include "util/rng.h"

unsigned probe_kinds(const SylEnvFill *fill, const double *par) {
    unsigned kinds = 0;
    for (size_t i = 0; i < fill->nprobes; i++) {
        const SylEnvProbe *q = &fill->probes[i];
        kinds |= syl_env_kind_bit(q->na ? par + q->par : NULL, q->na);
    }
    return kinds;
}

/* Points within r of c, but not within r/1000 of the turtle (its own segment's end). */
static double count_near(const PointGrid *g, const float c[3], float r, const float self[3]) {
    double n = 0;
    float r2 = r * r, e2 = r2 * 1e-6f;
    PGRID_FOR_CELLS(g, c, r, X, Y, Z) {
        uint32_t first, cnt = pgrid_cell(g, X, Y, Z, &first);
        for (uint32_t i = first; i < first + cnt; i++) {
            const float *q = g->pts[i];
            float d2 = 0, s2 = 0;
            for (int k = 0; k < 3; k++) d2 += (q[k] - c[k]) * (q[k] - c[k]), s2 += (q[k] - self[k]) * (q[k] - self[k]);
            n += d2 < r2 && s2 > e2;
        }
    }
    return n;
}

static double distance(const ProbeWorld *w, const float pos[3], const float h[3]) {
    float far = (float)PROBE_FAR;
    if (h[1] < 0 && pos[1] > w->ground) far = (w->ground - pos[1]) / h[1];
    if (w->obstacles && obstacles_any(w->obstacles)) far = obstacles_distance(w->obstacles, pos, h, far);
    return far;
}

void probe_answer(const ProbeWorld *w, const SylEnvFill *fill, int step, double *par) {
    static const float up[3] = {0, 1, 0};
    for (size_t i = 0; i < fill->nprobes; i++) {
        const SylEnvProbe *q = &fill->probes[i];
        if (q->na < 2) continue; /* nowhere to answer */
        double *a = par + q->par;
        float pos[3];
        for (int k = 0; k < 3; k++) pos[k] = q->pos[k] + w->at[k];
        if (a[0] == PROBE_LIGHT) a[1] = w->shadow ? probe_light(w->shadow, pos, q->tip) : 1;
        else if (a[0] == PROBE_SPACE) {
            float r = q->na >= 3 && a[2] > 0 && isfinite(a[2]) ? (float)a[2] : w->voxel, c[3];
            for (int k = 0; k < 3; k++) c[k] = pos[k] + r * q->h[k];
            a[1] = w->occ ? count_near(w->occ, c, r, pos) : 0;
        } else if (a[0] == PROBE_DISTANCE) a[1] = distance(w, pos, q->h);
        else if (a[0] == PROBE_SKY) {
            int rays = q->na >= 3 && a[2] >= 1 && a[2] <= 4096 ? (int)a[2] : 16;
            Rng r = rng_stream((uint64_t)step, 0x5c7, 0, i);
            /* rays start beyond the probe's own sphere (and its neighbours' along the shoot) */
            a[1] = w->sky ? sky_exposure(w->sky, pos, up, rays, &r, 2.5f * w->foliage) : 1;
        }
    }
}

int probe_sky_build(SkyScene *s, RTCDevice dev, const Obstacles *o, const float (*ends)[3], size_t n,
                    const float at[3], const float *others, size_t nothers, float r) {
    sky_reset(s);
    for (size_t i = 0; i < n; i++) {
        const float p[3] = {ends[i][0] + at[0], ends[i][1] + at[1], ends[i][2] + at[2]};
        if (!sky_add(s, p, r)) return SYL_ELIMIT;
    }
    for (size_t i = 0; i < nothers; i++)
        if (!sky_add(s, others + 3 * i, r)) return SYL_ELIMIT;
    return sky_commit(s, dev, o && obstacles_any(o) ? o : NULL) ? SYL_ELIMIT : SYL_OK;
}
