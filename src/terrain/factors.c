/* All the factors of a terrain, in the order they depend on each other, each timed. */
#include <math.h>
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

int syl_terrain_compute(SylTerrain *t, const SylTerrainOptions *o) {
    FILE *diag = o->diag;
    float *g[SYL_TERRAIN_FACTORS] = {0};
    for (int f = SYL_TERRAIN_SLOPE; f < SYL_TERRAIN_FACTORS; f++)
        if (!t->factor[f] && !(g[f] = t->factor[f] = terrain_grid(t, sizeof(float), diag))) return SYL_ELIMIT;
    t->factor[SYL_TERRAIN_ALTITUDE] = t->height;
    Stamp t0 = now();
    terrain_slope_aspect(t, t->factor[SYL_TERRAIN_SLOPE], t->factor[SYL_TERRAIN_ASPECT], o->threads);
    took(t, SYL_TERRAIN_SLOPE, t0);

    t0 = now();
    float *filled = terrain_grid(t, sizeof(float), diag);
    uint8_t *parent = filled ? (uint8_t *)terrain_grid(t, 1, diag) : NULL;
    uint8_t *dir = parent ? (uint8_t *)terrain_grid(t, 1, diag) : NULL;
    int st = dir ? terrain_fill(t, filled, parent, diag) : SYL_ELIMIT;
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
    (void)g;
    return SYL_OK;
}
