/* Light interception: the share of sky light that the crown keeps from the plane beneath
 * it, estimated with rays. Ray origins: a grid x grid of points at the centres of the cells
 * of the crown's footprint (the bounding rectangle in x and z of the mesh's vertices at or
 * above the crown base, all of them when there is none) on the plane y = crown base. Below
 * that plane a plant is a trunk, which says nothing about its crown, and measuring from it
 * keeps the figure from depending on how high the crown is carried.
 * Directions: `directions` of them over the upper hemisphere with density proportional to
 * the cosine of the zenith angle (a uniform overcast sky as seen by a horizontal surface): a
 * Fibonacci spiral on the unit disk lifted onto the hemisphere, turned by the golden angle
 * from one point to the next. The result is the share of these rays that hit a triangle of
 * the mesh from its front. Sylva's meshes are closed tubes and leaves with both sides made,
 * so every surface met from outside stops a ray, while a ray that starts inside wood (a point
 * inside a branch) is let out instead of counting as stopped. Embree answers the queries;
 * every ray is the same whatever the number of threads, and the hits are counted per point,
 * so the share is too. */
#include "util/lazy_embree.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "metrics/metrics_internal.h"
#include "mesh/store.h"
#include "util/coord.h"
#include "util/diag.h"
#include "util/parallel.h"

typedef struct Light {
    RTCScene scene;
    int grid, ndirs;
    double x0, z0, dx, dz;
    float y, tnear;
    uint32_t *hits; /* per point */
} Light;

static const double golden = 2.39996322972865332; /* pi (3 - sqrt 5) */

static void cast(void *ctx, size_t lo, size_t hi, int thread) {
    (void)thread;
    const Light *l = ctx;
    struct RTCIntersectContext ic;
    rtcInitIntersectContext(&ic);
    for (size_t pt = lo; pt < hi; pt++) {
        size_t gi = pt % (size_t)l->grid, gj = pt / (size_t)l->grid;
        float org[3] = {(float)(l->x0 + ((double)gi + 0.5) * l->dx), l->y,
                        (float)(l->z0 + ((double)gj + 0.5) * l->dz)};
        double turn = fmod((double)pt * golden, 2 * M_PI);
        uint32_t hits = 0;
        for (int k = 0; k < l->ndirs; k++) {
            double r = sqrt(((double)k + 0.5) / l->ndirs), phi = (double)k * golden + turn;
            struct RTCRay ray = {
                .org_x = org[0], .org_y = org[1], .org_z = org[2], .tnear = l->tnear,
                .dir_x = (float)(r * cos(phi)), .dir_y = (float)sqrt(1 - r * r), .dir_z = (float)(r * sin(phi)),
                .tfar = INFINITY, .mask = 0xffffffffu, .flags = 0,
            };
            rtcOccluded1(l->scene, &ic, &ray);
            hits += ray.tfar < 0;
        }
        l->hits[pt] = hits;
    }
}

/* Occlusion filter: a hit counts only on the side a triangle faces (counter-clockwise). */
static void front_only(const struct RTCFilterFunctionNArguments *a) {
    const SylMesh *m = a->geometryUserPtr;
    const float *ray = (const float *)a->ray;
    const unsigned *hit = (const unsigned *)a->hit;
    unsigned n = a->N;
    for (unsigned i = 0; i < n; i++) {
        if (!a->valid[i]) continue;
        const uint32_t *t = m->idx + 3 * (size_t)hit[5 * n + i];
        const float *p0 = m->pos + 3 * (size_t)t[0], *p1 = m->pos + 3 * (size_t)t[1], *p2 = m->pos + 3 * (size_t)t[2];
        float e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        float e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        float nx = e1[1] * e2[2] - e1[2] * e2[1], ny = e1[2] * e2[0] - e1[0] * e2[2];
        float nz = e1[0] * e2[1] - e1[1] * e2[0];
        if (nx * ray[4 * n + i] + ny * ray[5 * n + i] + nz * ray[6 * n + i] >= 0) a->valid[i] = 0;
    }
}

static void embree_error(void *user, enum RTCError code, const char *msg) {
    sink_error((const SylSink *)user, "metrics: embree: %s (code %d)", msg ? msg : "error", (int)code);
}

int metrics_light(const SylMesh *m, double base, const SylMetricsOptions *opt, double *fraction) {
    *fraction = 0;
    SylSink text;
    const SylSink *sink = diag_sink(&text, opt->diag, opt->sink);
    size_t ntri = m ? m->nidx / 3 : 0;
    if (!ntri || !m->nverts) return SYL_OK;
    if (ntri > 0xffffffffu) return SYL_ELIMIT;
    for (size_t i = 0; i < ntri * 3; i++)
        if (m->idx[i] >= m->nverts) {
            sink_error(sink, "metrics: mesh index %u out of range", m->idx[i]);
            return SYL_EUSAGE;
        }
    if (!coord_check(m->pos, m->nverts, 3, "the model", sink)) return SYL_EMODEL; /* Embree's range */
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int all = 0; all < 2 && lo[0] == INFINITY; all++) /* the crown's vertices, else all */
        for (size_t v = 0; v < m->nverts; v++)
            if (all || m->pos[3 * v + 1] >= base)
                for (int k = 0; k < 3; k++) {
                    lo[k] = fmin(lo[k], m->pos[3 * v + k]);
                    hi[k] = fmax(hi[k], m->pos[3 * v + k]);
                }
    Light l = {.grid = opt->grid > 0 ? opt->grid : 16, .ndirs = opt->directions > 0 ? opt->directions : 1024};
    size_t npts = (size_t)l.grid * (size_t)l.grid;
    l.x0 = lo[0], l.z0 = lo[2];
    l.dx = (hi[0] - lo[0]) / l.grid, l.dz = (hi[2] - lo[2]) / l.grid;
    l.y = (float)base;
    double size = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    l.tnear = (float)(1e-6 * size);
    int status = SYL_ELIMIT;
    float *pos_copy = NULL;
    l.hits = calloc(npts, sizeof *l.hits);
    char config[64];
    snprintf(config, sizeof config, "threads=%d,verbose=0", par_threads(opt->threads));
    RTCDevice dev = l.hits ? rtcNewDevice(config) : NULL;
    if (!dev) goto done;
    rtcSetDeviceErrorFunction(dev, embree_error, (void *)sink);
    l.scene = rtcNewScene(dev);
    /* A plant's mesh can be large: a compact hierarchy. */
    rtcSetSceneFlags(l.scene, RTC_SCENE_FLAG_COMPACT);
    /* Embree reads vertices 16 bytes at a time: it needs room past the last one. */
    const float *pos = m->pos;
    if (!mesh_has_spare(m)) {
        pos_copy = malloc((m->nverts * 3 + 4) * sizeof *pos_copy);
        if (!pos_copy) goto done;
        memcpy(pos_copy, m->pos, m->nverts * 3 * sizeof *pos_copy);
        memset(pos_copy + m->nverts * 3, 0, 4 * sizeof *pos_copy);
        pos = pos_copy;
    }
    RTCGeometry geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, pos, 0, 3 * sizeof(float),
                               m->nverts);
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m->idx, 0, 3 * sizeof(uint32_t),
                               ntri);
    rtcSetGeometryUserData(geom, (void *)m);
    rtcSetGeometryOccludedFilterFunction(geom, front_only);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(l.scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(l.scene);
    if (rtcGetDeviceError(dev) != RTC_ERROR_NONE) goto done;
    par_for(opt->threads, npts, 4, cast, &l);
    uint64_t hits = 0;
    for (size_t i = 0; i < npts; i++) hits += l.hits[i];
    *fraction = (double)hits / ((double)npts * (double)l.ndirs);
    status = SYL_OK;
done:
    if (status) sink_error(sink, "metrics: cannot trace the light rays");
    if (l.scene) rtcReleaseScene(l.scene);
    if (dev) rtcReleaseDevice(dev);
    free(pos_copy);
    free(l.hits);
    return status;
}
