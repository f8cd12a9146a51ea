/* Yearly insolation with the terrain's own shadows. The sun's path: Cooper's (1969)
 * declination δ = 23.45° sin(360° (284 + day) / 365) on days sampled evenly through the
 * year, the hour angle ω every few minutes of solar time, and the sun's direction from the
 * latitude φ (east, north, up) = (−cos δ sin ω, sin δ cos φ − cos δ sin φ cos ω,
 * sin δ sin φ + cos δ cos φ cos ω), kept when above the horizon. Each cell adds
 * max(0, n·s) for every sun it sees — n its Horn normal — and a ray toward the sun from its
 * centre through the terrain's triangles (Embree) decides whether it sees it. The sum is
 * divided by what open flat ground gets (the sum of the sun's heights sin α), so 1 is "as
 * sunny as a flat field", a south slope in the north gets more, a shaded hollow less. Direct
 * light only: no atmosphere, no diffuse sky. */
#include "util/lazy_embree.h"
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>

#include "terrain/terrain.h"
#include "util/budget.h"
#include "util/parallel.h"

TerrainSun *terrain_suns(double latitude, int days, double minutes, size_t *n) {
    *n = 0;
    if (days < 1) days = 1;
    int per_day = (int)lround(1440 / (minutes > 0 ? minutes : 60));
    if (per_day < 1) per_day = 1;
    TerrainSun *s = malloc((size_t)days * (size_t)per_day * sizeof *s + 1);
    if (!s) return NULL;
    double phi = latitude * (M_PI / 180);
    /* Cooper's declination peaks on day 172.25 and is symmetric about it: days placed
     * symmetrically about it pair up (j and days − 1 − j), and each pair is traced once. */
    for (int j = 0; j < (days + 1) / 2; j++) {
        double day = 172.25 + (j + 0.5 - days / 2.0) * 365.0 / days;
        float weight = 2 * j + 1 == days ? 1 : 2; /* an odd count's middle day is alone */
        double dec = 23.45 * (M_PI / 180) * sin(2 * M_PI * (284 + day) / 365);
        for (int m = 0; m < per_day; m++) {
            double w = (-180 + (m + 0.5) * 360.0 / per_day) * (M_PI / 180);
            double east = -cos(dec) * sin(w);
            double north = sin(dec) * cos(phi) - cos(dec) * sin(phi) * cos(w);
            double up = sin(dec) * sin(phi) + cos(dec) * cos(phi) * cos(w);
            if (up <= 1e-6) continue;
            /* Sylva: x east, y up, z south */
            s[(*n)++] = (TerrainSun){{(float)east, (float)up, (float)-north}, weight};
        }
    }
    return s;
}

typedef struct Job {
    const Terrain *t;
    RTCScene scene;
    const TerrainSun *suns;
    const float *tan_sun; /* each sun's tan(altitude) */
    const float *bound;   /* each cell's horizon bounds, a grid per quadrant (horizon.c) */
    size_t nsuns;
    double ref, hmax;
    float *out;
    _Atomic uint64_t pairs, rays; /* counted for --stats */
} Job;

enum { LANES = 16 };

/* Cells of a row in packets of 16 rays toward one sun at a time: neighbours' rays toward
 * the same sun are coherent, which Embree traces together. */
static void rows(void *ctx, size_t lo, size_t hi, int thread) {
    (void)thread;
    Job *j = ctx;
    const Terrain *t = j->t;
    uint64_t pairs = 0, rays = 0;
    struct RTCIntersectContext rc;
    rtcInitIntersectContext(&rc);
    rc.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    float lift = (float)(1e-3 * t->cell);
    for (size_t k = lo; k < hi; k++)
        for (int i0 = 0; i0 < t->nx; i0 += LANES) {
            int m = t->nx - i0 < LANES ? t->nx - i0 : LANES;
            double nrm[LANES][3], sum[LANES] = {0};
            float oy[LANES], bound[4][LANES];
            for (int l = 0; l < m; l++) {
                double gx, gz;
                terrain_horn(t, i0 + l, (int)k, &gx, &gz);
                double len = sqrt(gx * gx + 1 + gz * gz);
                nrm[l][0] = -gx / len, nrm[l][1] = 1 / len, nrm[l][2] = -gz / len;
                size_t c = k * (size_t)t->nx + (size_t)(i0 + l);
                oy[l] = t->height[c] + lift;
                size_t n = (size_t)t->nx * (size_t)t->nz;
                for (int q = 0; q < 4; q++) /* float rounding kept on the safe side */
                    bound[q][l] = j->bound[q * n + c] * (1 + 1e-5f) + 1e-6f;
            }
            for (size_t s = 0; s < j->nsuns; s++) {
                const float *d = j->suns[s].dir;
                const float *qb = bound[(d[0] >= 0) | (d[2] >= 0) << 1];
                struct RTCRay16 ray;
                _Alignas(64) int valid[LANES]; /* Embree reads the mask of a packet of 16 aligned */
                int any = 0;
                double cosi[LANES];
                for (int l = 0; l < LANES; l++) {
                    valid[l] = 0;
                    if (l >= m) continue;
                    cosi[l] = nrm[l][0] * d[0] + nrm[l][1] * d[1] + nrm[l][2] * d[2];
                    if (cosi[l] <= 0) continue;
                    pairs++;
                    if (!j->scene || oy[l] >= j->hmax || j->tan_sun[s] > qb[l]) {
                        sum[l] += cosi[l] * j->suns[s].weight; /* nothing can be in the way */
                        continue;
                    }
                    valid[l] = -1, any = 1, rays++;
                    ray.org_x[l] = (float)((i0 + l + 0.5) * t->cell), ray.org_y[l] = oy[l];
                    ray.org_z[l] = (float)((k + 0.5) * t->cell);
                    ray.dir_x[l] = d[0], ray.dir_y[l] = d[1], ray.dir_z[l] = d[2];
                    ray.tnear[l] = 0, ray.time[l] = 0;
                    /* Beyond the height of the highest cell nothing can be in the way. */
                    ray.tfar[l] = (float)((j->hmax - oy[l]) / d[1]) * 1.001f + lift;
                    ray.mask[l] = 0xffffffffu, ray.id[l] = (unsigned)l, ray.flags[l] = 0;
                }
                if (!any) continue;
                rtcOccluded16(valid, j->scene, &rc, &ray);
                for (int l = 0; l < m; l++)
                    if (valid[l] && ray.tfar[l] >= 0) sum[l] += cosi[l] * j->suns[s].weight;
            }
            for (int l = 0; l < m; l++)
                j->out[k * (size_t)t->nx + (size_t)(i0 + l)] = j->ref > 0 ? (float)(sum[l] / j->ref) : 0;
        }
    j->pairs += pairs;
    j->rays += rays;
}

int terrain_insolation(Terrain *t, const TerrainSun *suns, size_t nsuns, float *out, int threads, const SylSink *sink) {
    size_t nx = (size_t)t->nx, nz = (size_t)t->nz, n = nx * nz;
    size_t ntri = nx > 1 && nz > 1 ? 2 * (nx - 1) * (nz - 1) : 0;
    uint64_t bytes = (uint64_t)(3 * n + 4) * sizeof(float) + (uint64_t)ntri * 3 * sizeof(uint32_t);
    if (!budget_charge(terrain_budget(t), bytes)) {
        sink_error(sink, "the terrain's triangles for its shadows need more than the memory "
                                "limit (--max-memory)\n");
        return SYL_ELIMIT;
    }
    float *v = malloc((3 * n + 4) * sizeof *v); /* Embree reads 16 bytes at the last vertex */
    uint32_t *tri = malloc(ntri * 3 * sizeof *tri + 1);
    RTCDevice dev = NULL;
    RTCScene scene = NULL;
    int st = SYL_OK;
    if (!v || !tri) {
        sink_error(sink, "out of memory for the terrain's shadows");
        st = SYL_ELIMIT;
        goto done;
    }
    double hmax = -INFINITY;
    /* In the grid's own frame (corner at 0): Embree works in float, a DEM may lie far out. */
    for (size_t k = 0; k < nz; k++)
        for (size_t i = 0; i < nx; i++) {
            size_t c = k * nx + i;
            v[3 * c] = (float)((i + 0.5) * t->cell);
            v[3 * c + 1] = t->height[c];
            v[3 * c + 2] = (float)((k + 0.5) * t->cell);
            if (t->height[c] > hmax) hmax = t->height[c];
        }
    size_t q = 0;
    for (size_t k = 0; k + 1 < nz; k++)
        for (size_t i = 0; i + 1 < nx; i++) {
            uint32_t a = (uint32_t)(k * nx + i), b = a + 1, c = a + (uint32_t)nx, d = c + 1;
            uint32_t *p = tri + 6 * q++;
            p[0] = a, p[1] = c, p[2] = b, p[3] = b, p[4] = c, p[5] = d;
        }
    if (ntri) {
        char config[64];
        snprintf(config, sizeof config, "threads=%d,verbose=0", par_threads(threads));
        dev = rtcNewDevice(config);
        if (!dev) {
            sink_error(sink, "cannot start Embree");
            st = SYL_ELIMIT;
            goto done;
        }
        scene = rtcNewScene(dev);
        rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
        RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, v, 0, 3 * sizeof(float), n);
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, tri, 0, 3 * sizeof(uint32_t), ntri);
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene, g);
        rtcReleaseGeometry(g);
        rtcCommitScene(scene);
        if (rtcGetDeviceError(dev) != RTC_ERROR_NONE) {
            sink_error(sink, "cannot build the terrain's ray-tracing scene");
            st = SYL_ELIMIT;
            goto done;
        }
    }
    double ref = 0;
    for (size_t s = 0; s < nsuns; s++) ref += suns[s].dir[1] * suns[s].weight;
    float *bound = terrain_grid(t, 4 * sizeof(float), sink), *scratch = bound ? terrain_grid(t, 2 * sizeof(float), sink) : NULL;
    float *tan_sun = malloc(nsuns * sizeof *tan_sun + 1);
    if (!scratch || !tan_sun) {
        terrain_grid_free(t, bound, 4 * sizeof(float));
        terrain_grid_free(t, scratch, 2 * sizeof(float));
        free(tan_sun);
        st = SYL_ELIMIT;
        goto done;
    }
    for (size_t s = 0; s < nsuns; s++) {
        const float *d = suns[s].dir;
        tan_sun[s] = (float)(d[1] / sqrt((double)d[0] * d[0] + (double)d[2] * d[2] + 1e-30));
    }
    terrain_horizon_bound(t, bound, scratch);
    terrain_grid_free(t, scratch, 2 * sizeof(float));
    Job j = {t, scene, suns, tan_sun, bound, nsuns, ref, hmax, out, 0, 0};
    par_for(threads, nz, 4, rows, &j);
    t->sun_pairs = j.pairs, t->rays = j.rays;
    terrain_grid_free(t, bound, 4 * sizeof(float));
    free(tan_sun);
done:
    if (scene) rtcReleaseScene(scene);
    if (dev) rtcReleaseDevice(dev);
    free(v);
    free(tri);
    budget_release(terrain_budget(t), bytes);
    return st;
}
