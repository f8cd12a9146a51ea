/* The environment's life: see env.h. */
#include "env/env.h"

#include <stdlib.h>
#include <string.h>

#include "sylva/sylva.h"

static void embree_error(void *user, enum RTCError code, const char *msg) {
    FILE *diag = user;
    if (diag && code != RTC_ERROR_NONE) fprintf(diag, "sylva: error: Embree: %s\n", msg ? msg : "unknown error");
}

int env_init(Env *e, int threads, FILE *diag) {
    memset(e, 0, sizeof *e);
    e->diag = diag;
    e->threads = threads;
    e->sun[1] = 1;
    char config[64];
    snprintf(config, sizeof config, "threads=%d,verbose=0", threads > 0 ? threads : 0);
    e->dev = rtcNewDevice(config);
    if (!e->dev) {
        if (diag) fprintf(diag, "sylva: error: cannot start Embree (error %d)\n", (int)rtcGetDeviceError(NULL));
        return SYL_ELIMIT;
    }
    rtcSetDeviceErrorFunction(e->dev, embree_error, diag);
    return SYL_OK;
}

void env_free(Env *e) {
    if (!e->dev) return;
    obstacles_free(&e->obstacles);
    shadow_free(&e->shadow);
    sky_free(&e->sky);
    markers_free(&e->cloud);
    pgrid_free(&e->occupied);
    free(e->statics);
    rtcReleaseDevice(e->dev);
    memset(e, 0, sizeof *e);
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
