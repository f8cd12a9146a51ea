/* Sky exposure by rays: see sky.h. */
#include "env/sky.h"
#include "util/coord.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void sky_reset(SkyScene *s) {
    if (s->scene) rtcReleaseScene(s->scene);
    s->scene = NULL;
    s->n = 0;
}

bool sky_add(SkyScene *s, const float pos[3], float radius) {
    if (!coord_ok3(pos) || !coord_ok(radius)) return true; /* beyond what Embree traces: no shade */
    if (4 * (s->n + 1) + 4 > s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 4096;
        float *p = realloc(s->spheres, cap * sizeof *p);
        if (!p) return false;
        s->spheres = p;
        s->cap = cap;
    }
    float *q = s->spheres + 4 * s->n++;
    q[0] = pos[0], q[1] = pos[1], q[2] = pos[2], q[3] = radius;
    return true;
}

int sky_commit(SkyScene *s, RTCDevice dev, const Obstacles *o) {
    if (s->scene) rtcReleaseScene(s->scene);
    s->scene = rtcNewScene(dev);
    if (s->n) {
        RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_SPHERE_POINT);
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, s->spheres, 0, 4 * sizeof(float),
                                   s->n);
        rtcCommitGeometry(g);
        rtcAttachGeometry(s->scene, g);
        rtcReleaseGeometry(g);
    }
    if (o && o->nt) {
        RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, o->v, 0, 3 * sizeof(float), o->nv);
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, o->tri, 0, 3 * sizeof(uint32_t), o->nt);
        rtcCommitGeometry(g);
        rtcAttachGeometry(s->scene, g);
        rtcReleaseGeometry(g);
    }
    rtcCommitScene(s->scene);
    return rtcGetDeviceError(dev) == RTC_ERROR_NONE ? 0 : 3;
}

void sky_free(SkyScene *s) {
    sky_reset(s);
    free(s->spheres);
    memset(s, 0, sizeof *s);
}

float sky_exposure(const SkyScene *s, const float pos[3], const float sun[3], int rays, Rng *rng, float tnear) {
    if (!s->scene || rays <= 0) return 1;
    if (!coord_ok3(pos)) return 0; /* a ray from there would abort Embree: no sky is seen */
    /* a frame about the sun's direction */
    float n[3] = {sun[0], sun[1], sun[2]}, t[3], b[3];
    float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0)) n[0] = 0, n[1] = 1, n[2] = 0, len = 1;
    for (int k = 0; k < 3; k++) n[k] /= len;
    if (fabsf(n[0]) < 0.9f) t[0] = 0, t[1] = -n[2], t[2] = n[1];
    else t[0] = n[2], t[1] = 0, t[2] = -n[0];
    len = sqrtf(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    for (int k = 0; k < 3; k++) t[k] /= len;
    b[0] = n[1] * t[2] - n[2] * t[1], b[1] = n[2] * t[0] - n[0] * t[2], b[2] = n[0] * t[1] - n[1] * t[0];
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    int open = 0;
    for (int i = 0; i < rays; i++) {
        /* cosine-weighted, stratified in azimuth */
        float u1 = ((float)i + (float)rng_unit(rng)) / (float)rays, u2 = (float)rng_unit(rng);
        float r = sqrtf(u2), z = sqrtf(1 - u2), a = 6.2831853f * u1;
        float cx = r * cosf(a), cy = r * sinf(a);
        struct RTCRay ray = {.org_x = pos[0], .org_y = pos[1], .org_z = pos[2], .tnear = tnear,
                             .dir_x = t[0] * cx + b[0] * cy + n[0] * z, .dir_y = t[1] * cx + b[1] * cy + n[1] * z,
                             .dir_z = t[2] * cx + b[2] * cy + n[2] * z, .time = 0, .tfar = INFINITY,
                             .mask = 0xffffffffu, .id = 0, .flags = 0};
        rtcOccluded1(s->scene, &ctx, &ray);
        open += ray.tfar >= 0;
    }
    return (float)open / (float)rays;
}
