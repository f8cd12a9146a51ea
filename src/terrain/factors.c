/* All the factors of a terrain, in the order they depend on each other, each timed. */
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <time.h>

#include "terrain/terrain.h"

static double clock_s(clockid_t id) {
    struct timespec ts;
    clock_gettime(id, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

typedef struct Stamp {
    double wall, cpu;
} Stamp;

static Stamp now(void) { return (Stamp){clock_s(CLOCK_MONOTONIC), clock_s(CLOCK_PROCESS_CPUTIME_ID)}; }

static void took(SylTerrain *t, int f, Stamp since) {
    Stamp n = now();
    t->seconds[f] = n.wall - since.wall;
    t->cpu_seconds[f] = n.cpu - since.cpu;
}

static int gis(SylTerrain *t, const SylTerrainOptions *o);
static int zamuda(SylTerrain *t, const SylTerrainOptions *o);

int syl_terrain_compute(SylTerrain *t, const SylTerrainOptions *o) {
    FILE *diag = o->diag;
    int measures = o->measures ? o->measures : SYL_TERRAIN_GIS;
    if (measures & ~SYL_TERRAIN_BOTH) {
        if (diag) fprintf(diag, "sylva: error: unknown terrain measures %d\n", measures);
        return SYL_EUSAGE;
    }
    if (o->runoff > 1e3 || o->lee_angle > 90 || o->ambient > 1 || o->water_level > 1) {
        if (diag) fprintf(diag, "sylva: error: Zamuda's ambient light and water level are at most 1, his lee angle at most 90 degrees, his runoff at most 1000\n");
        return SYL_EUSAGE;
    }
    for (int f = SYL_TERRAIN_SLOPE; f < SYL_TERRAIN_FACTORS; f++) {
        bool zamuda = f >= SYL_TERRAIN_HUMIDITY, wanted = f <= SYL_TERRAIN_ASPECT ||
                                                          (measures & (zamuda ? SYL_TERRAIN_ZAMUDA : SYL_TERRAIN_GIS));
        if (wanted && !t->factor[f] && !(t->factor[f] = terrain_grid(t, sizeof(float), diag))) return SYL_ELIMIT;
    }
    t->factor[SYL_TERRAIN_ALTITUDE] = t->height;
    Stamp t0 = now();
    terrain_slope_aspect(t, t->factor[SYL_TERRAIN_SLOPE], t->factor[SYL_TERRAIN_ASPECT], o->threads);
    took(t, SYL_TERRAIN_SLOPE, t0);
    int st = measures & SYL_TERRAIN_GIS ? gis(t, o) : SYL_OK;
    return !st && measures & SYL_TERRAIN_ZAMUDA ? zamuda(t, o) : st;
}

/* Zamuda's humidity, sunniness and windiness (his defaults where o gives 0). */
static int zamuda(SylTerrain *t, const SylTerrainOptions *o) {
    FILE *diag = o->diag;
    Stamp t0 = now();
    int st = terrain_runoff(t, t->factor[SYL_TERRAIN_SLOPE], o->runoff > 0 ? o->runoff : 10, o->water_level,
                            t->factor[SYL_TERRAIN_HUMIDITY], diag);
    if (st) return st;
    took(t, SYL_TERRAIN_HUMIDITY, t0);
    t0 = now();
    st = terrain_sunniness(t, o->sun_set ? o->latitude : 46, o->sun_samples > 0 ? o->sun_samples : 9,
                           o->ambient > 0 ? o->ambient : 0.2, t->factor[SYL_TERRAIN_SUNNINESS], o->threads, diag);
    if (st) return st;
    took(t, SYL_TERRAIN_SUNNINESS, t0);
    t0 = now();
    terrain_lee(t, o->wind_set ? o->wind_from : 270, o->lee_samples > 0 ? o->lee_samples : 10,
                o->lee_angle > 0 ? o->lee_angle : 45, t->factor[SYL_TERRAIN_WINDINESS], o->threads);
    took(t, SYL_TERRAIN_WINDINESS, t0);
    return SYL_OK;
}

/* GIS's flow, wetness, insolation and wind. */
static int gis(SylTerrain *t, const SylTerrainOptions *o) {
    FILE *diag = o->diag;
    int st;
    Stamp t0 = now();
    float *filled = terrain_grid(t, sizeof(float), diag);
    uint8_t *parent = filled ? (uint8_t *)terrain_grid(t, 1, diag) : NULL;
    uint8_t *dir = parent ? (uint8_t *)terrain_grid(t, 1, diag) : NULL;
    st = dir ? terrain_fill(t, filled, parent, diag) : SYL_ELIMIT;
    if (!st) {
        terrain_d8(t, filled, parent, dir, o->threads);
        st = terrain_accumulate(t, dir, t->factor[SYL_TERRAIN_FLOW], diag);
    }
    terrain_grid_free(t, filled, sizeof(float));
    terrain_grid_free(t, parent, 1);
    terrain_grid_free(t, dir, 1);
    if (st) return st;
    took(t, SYL_TERRAIN_FLOW, t0);

    t0 = now();
    terrain_wetness(t, t->factor[SYL_TERRAIN_FLOW], t->factor[SYL_TERRAIN_SLOPE], t->factor[SYL_TERRAIN_WETNESS],
                    o->threads);
    took(t, SYL_TERRAIN_WETNESS, t0);

    t0 = now();
    size_t nsuns;
    TerrainSun *suns = terrain_suns(o->sun_set ? o->latitude : 46, o->sun_days > 0 ? o->sun_days : 12,
                                    o->sun_minutes > 0 ? o->sun_minutes : 60, &nsuns);
    if (!suns) {
        if (diag) fprintf(diag, "sylva: error: out of memory for the sun's positions\n");
        return SYL_ELIMIT;
    }
    st = terrain_insolation(t, suns, nsuns, t->factor[SYL_TERRAIN_INSOLATION], o->threads, diag);
    free(suns);
    if (st) return st;
    took(t, SYL_TERRAIN_INSOLATION, t0);

    t0 = now();
    terrain_wind(t, o->wind_set ? o->wind_from : 270, o->wind_distance > 0 ? o->wind_distance : 300,
                 t->factor[SYL_TERRAIN_WIND], o->threads);
    took(t, SYL_TERRAIN_WIND, t0);
    return SYL_OK;
}
