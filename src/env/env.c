/* The environment's life: see env.h. */
#include "env/env.h"

#include <stdlib.h>
#include <string.h>

#include "sylva/sylva.h"
#include "util/diag.h"

static void embree_error(void *user, enum RTCError code, const char *msg) {
    const SylSink *sink = user;
    if (sink && code != RTC_ERROR_NONE) sink_error(sink, "Embree: %s", msg ? msg : "unknown error");
}

int env_init(Env *e, int threads, const SylSink *sink) {
    memset(e, 0, sizeof *e);
    if (sink) e->sink = *sink; /* copied: the device reports to it later */
    e->threads = threads;
    e->sun[1] = 1;
    char config[64];
    snprintf(config, sizeof config, "threads=%d,verbose=0", threads > 0 ? threads : 0);
    e->dev = rtcNewDevice(config);
    if (!e->dev) {
        sink_error(sink, "cannot start Embree (error %d)", (int)rtcGetDeviceError(NULL));
        return SYL_ELIMIT;
    }
    rtcSetDeviceErrorFunction(e->dev, embree_error, &e->sink);
    return SYL_OK;
}

void env_init_probes(Env *e, const ShadowParams *shadow, float ground, const SylSink *sink) {
    memset(e, 0, sizeof *e);
    if (sink) e->sink = *sink; /* copied: the device reports to it later */
    e->ground = ground;
    memcpy(e->sun, shadow->sun, sizeof e->sun);
    shadow_init(&e->shadow, shadow, ground);
    e->shadow_on = true;
}

void env_free(Env *e) {
    obstacles_free(&e->obstacles);
    shadow_free(&e->shadow);
    sky_free(&e->sky);
    markers_free(&e->cloud);
    pgrid_free(&e->occupied);
    free(e->statics);
    free(e->probes.pts);
    pgrid_free(&e->probes.occ);
    sky_free(&e->probes.sky);
    if (e->dev) rtcReleaseDevice(e->dev);
    memset(e, 0, sizeof *e);
}

RTCDevice env_device(Env *e) {
    if (!e->dev) e->dev = rtcNewDevice(NULL);
    return e->dev;
}

bool env_probe_points(Env *e, size_t n) {
    if (n <= e->probes.pts_cap) return true;
    float(*p)[3] = realloc(e->probes.pts, n * sizeof *p);
    if (!p) return false;
    e->probes.pts = p;
    e->probes.pts_cap = n;
    return true;
}

ProbeWorld env_probe_world(const Env *e, float voxel, float ground, const Obstacles *o, const float at[3]) {
    return (ProbeWorld){.shadow = e->shadow_on ? &e->shadow : NULL, .occ = &e->probes.occ, .voxel = voxel,
                        .obstacles = o, .ground = ground, .sky = &e->probes.sky, .foliage = probe_foliage(voxel),
                        .at = {at[0], at[1], at[2]}};
}

bool env_add_static(Env *e, const float pos[3]) {
    if (e->nstatic + 1 > e->static_cap) {
        size_t cap = e->static_cap ? 2 * e->static_cap : 1024;
        float *p = realloc(e->statics, 3 * cap * sizeof *p);
        if (!p) return false;
        e->statics = p;
        e->static_cap = cap;
    }
    memcpy(e->statics + 3 * e->nstatic++, pos, 3 * sizeof(float));
    return true;
}
