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
#include <embree3/rtcore.h>
#include <math.h>
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
    for (int j = 0; j < days; j++) {
        double day = (j + 0.5) * 365.0 / days;
        double dec = 23.45 * (M_PI / 180) * sin(2 * M_PI * (284 + day) / 365);
        for (int m = 0; m < per_day; m++) {
            double w = (-180 + (m + 0.5) * 360.0 / per_day) * (M_PI / 180);
            double east = -cos(dec) * sin(w);
            double north = sin(dec) * cos(phi) - cos(dec) * sin(phi) * cos(w);
            double up = sin(dec) * sin(phi) + cos(dec) * cos(phi) * cos(w);
            if (up <= 1e-6) continue;
            /* Sylva: x east, y up, z south */
            s[(*n)++] = (TerrainSun){{(float)east, (float)up, (float)-north}};
        }
    }
    return s;
}

typedef struct Job {
    const Terrain *t;
    RTCScene scene;
    const TerrainSun *suns;
    size_t nsuns;
    double ref, hmax;
    float *out;
} Job;

static void rows(void *ctx, size_t lo, size_t hi, int thread) {
    (void)thread;
    const Job *j = ctx;
    const Terrain *t = j->t;
    struct RTCIntersectContext rc;
    rtcInitIntersectContext(&rc);
    rc.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    float lift = (float)(1e-3 * t->cell);
    for (size_t k = lo; k < hi; k++)
        for (int i = 0; i < t->nx; i++) {
            size_t c = k * (size_t)t->nx + (size_t)i;
            double gx, gz;
            terrain_horn(t, i, (int)k, &gx, &gz);
            double len = sqrt(gx * gx + 1 + gz * gz), nx = -gx / len, ny = 1 / len, nz = -gz / len;
            float ox = (float)((i + 0.5) * t->cell), oz = (float)((k + 0.5) * t->cell);
            float oy = t->height[c] + lift;
            double sum = 0;
            for (size_t s = 0; s < j->nsuns; s++) {
                const float *d = j->suns[s].dir;
                double cosi = nx * d[0] + ny * d[1] + nz * d[2];
                if (cosi <= 0) continue;
                /* Beyond the height of the highest cell nothing can be in the way. */
                if (j->scene && oy < j->hmax) {
                    struct RTCRay ray = {.org_x = ox, .org_y = oy, .org_z = oz, .tnear = 0,
                                         .dir_x = d[0], .dir_y = d[1], .dir_z = d[2], .time = 0,
                                         .tfar = (float)((j->hmax - oy) / d[1]) * 1.001f + lift,
                                         .mask = 0xffffffffu, .id = 0, .flags = 0};
                    rtcOccluded1(j->scene, &rc, &ray);
                    if (ray.tfar < 0) continue; /* Embree marks a blocked ray with tfar = −inf */
                }
                sum += cosi;
            }
            j->out[c] = j->ref > 0 ? (float)(sum / j->ref) : 0;
        }
}

int terrain_insolation(Terrain *t, const TerrainSun *suns, size_t nsuns, float *out, int threads, FILE *diag) {
    size_t nx = (size_t)t->nx, nz = (size_t)t->nz, n = nx * nz;
    size_t ntri = nx > 1 && nz > 1 ? 2 * (nx - 1) * (nz - 1) : 0;
    uint64_t bytes = (uint64_t)(3 * n + 4) * sizeof(float) + (uint64_t)ntri * 3 * sizeof(uint32_t);
    if (!budget_charge(t->budget, bytes)) {
        if (diag) fprintf(diag, "sylva: error: the terrain's triangles for its shadows need more than the memory "
                                "limit (--max-memory)\n");
        return SYL_ELIMIT;
    }
    float *v = malloc((3 * n + 4) * sizeof *v); /* Embree reads 16 bytes at the last vertex */
    uint32_t *tri = malloc(ntri * 3 * sizeof *tri + 1);
    RTCDevice dev = NULL;
    RTCScene scene = NULL;
    int st = SYL_OK;
    if (!v || !tri) {
        if (diag) fprintf(diag, "sylva: error: out of memory for the terrain's shadows\n");
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
            if (diag) fprintf(diag, "sylva: error: cannot start Embree\n");
            st = SYL_ELIMIT;
            goto done;
        }
        scene = rtcNewScene(dev);
        rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
        RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, v, 0, 3 * sizeof(float), n);
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, tri, 0, 3 * sizeof(uint32_t), ntri);
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene, g);
        rtcReleaseGeometry(g);
        rtcCommitScene(scene);
        if (rtcGetDeviceError(dev) != RTC_ERROR_NONE) {
            if (diag) fprintf(diag, "sylva: error: cannot build the terrain's ray-tracing scene\n");
            st = SYL_ELIMIT;
            goto done;
        }
    }
    double ref = 0;
    for (size_t s = 0; s < nsuns; s++) ref += suns[s].dir[1];
    Job j = {t, scene, suns, nsuns, ref, hmax, out};
    par_for(threads, nz, 4, rows, &j);
done:
    if (scene) rtcReleaseScene(scene);
    if (dev) rtcReleaseDevice(dev);
    free(v);
    free(tri);
    budget_release(t->budget, bytes);
    return st;
}
