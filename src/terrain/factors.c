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
    const SylSink *sink = opt_sink(o);
    int measures = o->measures ? o->measures : SYL_TERRAIN_GIS;
    if (measures & ~SYL_TERRAIN_BOTH) {
        sink_error(sink, "unknown terrain measures %d", measures);
        return SYL_EUSAGE;
    }
    if (o->runoff > 1e3 || o->lee_angle > 90 || o->ambient > 1 || o->water_level > 1) {
        sink_error(sink, "Zamuda's ambient light and water level are at most 1, his lee angle at most 90 degrees, his runoff at most 1000");
        return SYL_EUSAGE;
    }
    for (int f = SYL_TERRAIN_SLOPE; f < SYL_TERRAIN_FACTORS; f++) {
        bool zamuda = f >= SYL_TERRAIN_HUMIDITY, wanted = f <= SYL_TERRAIN_ASPECT ||
                                                          (measures & (zamuda ? SYL_TERRAIN_ZAMUDA : SYL_TERRAIN_GIS));
        if (wanted && !t->factor[f] && !(t->factor[f] = terrain_grid(t, sizeof(float), sink))) return SYL_ELIMIT;
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
    const SylSink *sink = opt_sink(o);
    Stamp t0 = now();
    int st = terrain_runoff(t, t->factor[SYL_TERRAIN_SLOPE], o->runoff > 0 ? o->runoff : 10, o->water_level,
                            t->factor[SYL_TERRAIN_HUMIDITY], sink);
    if (st) return st;
    took(t, SYL_TERRAIN_HUMIDITY, t0);
    t0 = now();
    st = terrain_sunniness(t, o->sun_set ? o->latitude : 46, o->sun_samples > 0 ? o->sun_samples : 9,
                           o->ambient > 0 ? o->ambient : 0.2, t->factor[SYL_TERRAIN_SUNNINESS], o->threads, sink);
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
    const SylSink *sink = opt_sink(o);
    int st;
    Stamp t0 = now();
    float *filled = terrain_grid(t, sizeof(float), sink);
    uint8_t *parent = filled ? (uint8_t *)terrain_grid(t, 1, sink) : NULL;
    uint8_t *dir = parent ? (uint8_t *)terrain_grid(t, 1, sink) : NULL;
    st = dir ? terrain_fill(t, filled, parent, sink) : SYL_ELIMIT;
    if (!st) {
        terrain_d8(t, filled, parent, dir, o->threads);
        st = terrain_accumulate(t, dir, t->factor[SYL_TERRAIN_FLOW], sink);
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
        sink_error(sink, "out of memory for the sun's positions");
        return SYL_ELIMIT;
    }
    st = terrain_insolation(t, suns, nsuns, t->factor[SYL_TERRAIN_INSOLATION], o->threads, sink);
    free(suns);
    if (st) return st;
    took(t, SYL_TERRAIN_INSOLATION, t0);

    t0 = now();
    terrain_wind(t, o->wind_set ? o->wind_from : 270, o->wind_distance > 0 ? o->wind_distance : 300,
                 t->factor[SYL_TERRAIN_WIND], o->threads);
    took(t, SYL_TERRAIN_WIND, t0);
    return SYL_OK;
}
