/* Obstacles in an Embree scene: see obstacles.h. */
#include "env/obstacles.h"
#include "util/array.h"
#include "util/coord.h"
#include "util/diag.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "env/objread.h"
#include "sylva/sylva.h"

bool obstacles_add(Obstacles *o, const float *v, size_t nv, const uint32_t *tri, size_t nt) {
    if (o->nv + nv > UINT32_MAX - 2) return false;
    if (!array_reserve(&o->v, &o->vcap, 3 * (o->nv + nv) + 4, sizeof(float)) ||
        !array_reserve(&o->tri, &o->tcap, 3 * (o->nt + nt), sizeof(uint32_t)))
        return false;
    if (o->nv == 0)
        for (int k = 0; k < 3; k++) o->lo[k] = INFINITY, o->hi[k] = -INFINITY;
    for (size_t i = 0; i < 3 * nv; i++) {
        o->v[3 * o->nv + i] = v[i];
        if (v[i] < o->lo[i % 3]) o->lo[i % 3] = v[i];
        if (v[i] > o->hi[i % 3]) o->hi[i % 3] = v[i];
    }
    for (size_t i = 0; i < 3 * nt; i++) o->tri[3 * o->nt + i] = tri[i] + (uint32_t)o->nv;
    o->nv += nv;
    o->nt += nt;
    return true;
}

int obstacles_add_obj(Obstacles *o, const char *path, const float offset[3], float scale, const SylSink *sink) {
    ObjMesh m;
    int st = obj_read(path, &m, sink);
    if (st) return st;
    for (size_t i = 0; i < 3 * m.nv; i++) m.v[i] = m.v[i] * scale + offset[i % 3];
    char what[512];
    snprintf(what, sizeof what, "the obstacle '%s', moved and scaled,", path);
    if (!coord_check(m.v, m.nv, 3, what, sink)) st = SYL_EMODEL;
    else if (!obstacles_add(o, m.v, m.nv, m.tri, m.nt)) {
        sink_error(sink, "out of memory reading '%s'", path);
        st = SYL_ELIMIT;
    }
    obj_free(&m);
    return st;
}

int obstacles_commit(Obstacles *o, RTCDevice dev, const SylSink *sink) {
    if (o->scene) rtcReleaseScene(o->scene);
    o->scene = NULL;
    if (!o->nt) return SYL_OK;
    if (!coord_check(o->v, o->nv, 3, "an obstacle", sink)) return SYL_EMODEL;
    o->scene = rtcNewScene(dev);
    rtcSetSceneFlags(o->scene, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, o->v, 0, 3 * sizeof(float), o->nv);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, o->tri, 0, 3 * sizeof(uint32_t), o->nt);
    rtcCommitGeometry(g);
    rtcAttachGeometry(o->scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(o->scene);
    if (rtcGetDeviceError(dev) != RTC_ERROR_NONE) {
        sink_error(sink, "cannot build the obstacles' ray-tracing scene");
        return SYL_ELIMIT;
    }
    return SYL_OK;
}

void obstacles_free(Obstacles *o) {
    if (o->scene) rtcReleaseScene(o->scene);
    free(o->v);
    free(o->tri);
    memset(o, 0, sizeof *o);
}

static bool occluded(RTCScene scene, const float org[3], const float dir[3], float tfar) {
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRay ray = {.org_x = org[0], .org_y = org[1], .org_z = org[2], .tnear = 0,
                         .dir_x = dir[0], .dir_y = dir[1], .dir_z = dir[2], .time = 0, .tfar = tfar,
                         .mask = 0xffffffffu, .id = 0, .flags = 0};
    rtcOccluded1(scene, &ctx, &ray);
    return ray.tfar < 0;
}

bool obstacles_blocked(const Obstacles *o, const float a[3], const float b[3], float margin) {
    if (!o->scene) return false;
    float d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(len > 0)) return false;
    if (!coord_ok3(a) || !coord_ok3(b)) return true; /* beyond what Embree traces: no way through */
    for (int k = 0; k < 3; k++) d[k] /= len;
    /* quick reject: both ends (with the margin) outside the obstacles' bounds on one side */
    for (int k = 0; k < 3; k++) {
        float e = b[k] + d[k] * margin;
        if ((a[k] < o->lo[k] && e < o->lo[k]) || (a[k] > o->hi[k] && e > o->hi[k])) return false;
    }
    return occluded(o->scene, a, d, len + margin);
}

float obstacles_distance(const Obstacles *o, const float org[3], const float dir[3], float far) {
    if (!o->scene) return far;
    if (!coord_ok3(org)) return 0; /* beyond what Embree traces */
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRayHit rh;
    memset(&rh, 0, sizeof rh);
    rh.ray.org_x = org[0], rh.ray.org_y = org[1], rh.ray.org_z = org[2];
    rh.ray.dir_x = dir[0], rh.ray.dir_y = dir[1], rh.ray.dir_z = dir[2];
    rh.ray.tfar = far;
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(o->scene, &ctx, &rh);
    return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? far : rh.ray.tfar;
}

bool obstacles_inside(const Obstacles *o, const float p[3]) {
    if (!o->scene || !coord_ok3(p)) return false;
    /* an unusual direction, so that the ray seldom runs along an edge of a modelled mesh */
    static const float dir[3] = {0.5773503f, 0.5925557f, 0.5619427f};
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    int crossings = 0;
    float t = 0;
    for (int k = 0; k < 4096; k++) {
        struct RTCRayHit rh;
        memset(&rh, 0, sizeof rh);
        rh.ray.org_x = p[0], rh.ray.org_y = p[1], rh.ray.org_z = p[2];
        rh.ray.dir_x = dir[0], rh.ray.dir_y = dir[1], rh.ray.dir_z = dir[2];
        rh.ray.tnear = t;
        rh.ray.tfar = INFINITY;
        rh.ray.mask = 0xffffffffu;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(o->scene, &ctx, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;
        crossings++;
        t = rh.ray.tfar * (1 + 1e-6f) + 1e-6f; /* past this surface */
    }
    return crossings % 2 == 1;
}

bool obstacles_height(const Obstacles *o, float x, float z, float y, float *out) {
    if (!o->scene || !coord_ok(x) || !coord_ok(y) || !coord_ok(z)) return false;
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRayHit rh;
    memset(&rh, 0, sizeof rh);
    rh.ray.org_x = x, rh.ray.org_y = y, rh.ray.org_z = z;
    rh.ray.dir_y = -1;
    rh.ray.tfar = INFINITY;
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    /* A vertical face has no height under a point; a ray in its plane gets an arbitrary
     * distance from Embree (found by fuzzing: a height below the lowest vertex). Such hits
     * are passed, and the answer is kept within the surfaces' bounds. */
    for (int pass = 0; pass < 8; pass++) {
        rtcIntersect1(o->scene, &ctx, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
        float ng = fabsf(rh.hit.Ng_x) + fabsf(rh.hit.Ng_y) + fabsf(rh.hit.Ng_z);
        if (fabsf(rh.hit.Ng_y) > 1e-6f * ng) break;
        rh.ray.tnear = rh.ray.tfar + 1e-6f * (1 + fabsf(rh.ray.tfar));
        rh.ray.tfar = INFINITY;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    }
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    *out = fminf(fmaxf(y - rh.ray.tfar, o->lo[1]), o->hi[1]);
    return true;
}
