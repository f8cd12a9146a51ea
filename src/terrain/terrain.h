/* Terrains inside Sylva: the grid (sylva/terrain.h), its readers, one file per factor, and
 * the map writers. A factor function reads the heights and earlier factors and writes only
 * its own grid, row by row, so that its result does not depend on the thread count. */
#ifndef SYL_TERRAIN_TERRAIN_H
#define SYL_TERRAIN_TERRAIN_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "sylva/terrain.h"
#include "util/diag.h"

typedef SylTerrain Terrain;
typedef SylTerrainFactor TerrainFactor;

/* Grids larger than this many cells on a side are refused before anything is allocated. */
enum { TERRAIN_MAX_SIDE = 65536 };
/* Cell sizes and corners Sylva takes: a grid then spans at most 6.6e10 units, well within
 * what Embree traces (util/coord.h), and its cells' positions stay finite in float. */
#define TERRAIN_MIN_CELL 1e-6
#define TERRAIN_MAX_CELL 1e6
#define TERRAIN_MAX_CORNER 1e12

/* ---- the grid (terrain.c) ---- */

/* What a terrain keeps for the library alone (SylTerrain.store): the budget its grids are
 * counted against, the bytes of height and valid charged to it, and whether it is the
 * terrain's own (freed with it). */
struct SylTerrainStore {
    SylBudget *budget;
    uint64_t charged;
    bool own_budget;
};
static inline SylBudget *terrain_budget(const Terrain *t) { return t->store->budget; }

/* A terrain of nx × nz cells, heights 0 and all valid, charged to budget (NULL: its own of
 * max_memory). SYL_OK or SYL_ELIMIT, reported on sink as about path. */
int terrain_new(int nx, int nz, SylBudget *budget, uint64_t max_memory, const char *path, const SylSink *sink,
                Terrain **out);
/* A zeroed grid of nx * nz floats for a factor (or scratch), charged to t's budget; NULL
 * (reported) when refused. Free with terrain_grid_free. */
float *terrain_grid(Terrain *t, size_t elem, const SylSink *sink);
void terrain_grid_free(Terrain *t, void *grid, size_t elem);
/* The height at cell (i, k), indices clamped to the grid (edges repeat: how every 3×3 window
 * is read at the border). */
static inline float terrain_h(const Terrain *t, int i, int k) {
    i = i < 0 ? 0 : i >= t->nx ? t->nx - 1 : i;
    k = k < 0 ? 0 : k >= t->nz ? t->nz - 1 : k;
    return t->height[(size_t)k * (size_t)t->nx + (size_t)i];
}
/* Horn's (1981) gradient at cell (i, k): dh/dx (east) and dh/dz (south, +z), from the 3×3
 * window a b c / d e f / g h i read north row first, as gdaldem reads it. */
void terrain_horn(const Terrain *t, int i, int k, double *gx, double *gz);
/* The factor sampled at (x, z) (sylva/terrain.h: syl_terrain_factor_at). */
double terrain_factor_at(const Terrain *t, TerrainFactor f, double x, double z);
/* Bilinear height, clamped: what the wind's march samples. */
double terrain_height_at(const Terrain *t, double x, double z);
/* The wind's march (wind.c, lee.c): from cell (i, k)'s centre, the terrain sampled every
 * cell width along the unit (ux, uz) for up to steps samples, stopping at the grid's edge;
 * the largest rise per distance, (h_s − h) / d, or −INFINITY when no sample lies on the grid. */
double terrain_max_rise(const Terrain *t, size_t i, size_t k, double ux, double uz, int steps);

/* ---- readers (read_png.c, read_asc.c, read_obj.c) ---- */

/* A PNG or ASCII grid already in memory (path names it in messages): the fuzz harness's way
 * in. Same results as syl_terrain_read. */
int terrain_read_png(const char *path, const uint8_t *data, size_t len, const SylTerrainOptions *o,
                     Terrain **out);
int terrain_read_asc(const char *path, const char *text, size_t len, const SylTerrainOptions *o, Terrain **out);
int terrain_read_obj(const char *path, const SylTerrainOptions *o, Terrain **out);
/* Zamuda's DMR text: x, z and height, one value a line, a vertex per cell centre (read_dmr.c). */
int terrain_read_dmr(const char *path, const char *text, size_t len, const SylTerrainOptions *o, Terrain **out);
/* Cells whose height is not known (NODATA, or no surface under them) get the lowest known
 * height, so that every factor is defined; valid[] remembers them. False when none is known. */
bool terrain_fill_unknown(Terrain *t);

/* ---- factors, one file each ---- */

void terrain_slope_aspect(const Terrain *t, float *slope, float *aspect, int threads); /* slope.c */

/* Priority-flood (Barnes et al. 2014), fill.c: filled[] the heights with every depression
 * raised to its spill height; parent[] the direction (D8 code below) of the cell each cell
 * was reached from, TERRAIN_OUT for the edge cells the flood starts from. SYL_OK or
 * SYL_ELIMIT (its queues refused by the budget). */
int terrain_fill(Terrain *t, float *filled, uint8_t *parent, const SylSink *sink);

/* D8 codes: the neighbour a cell drains to. */
enum { TERRAIN_E, TERRAIN_SE, TERRAIN_S, TERRAIN_SW, TERRAIN_W, TERRAIN_NW, TERRAIN_N, TERRAIN_NE, TERRAIN_OUT = 255 };
extern const int terrain_d8_di[8], terrain_d8_dk[8];
/* flow.c: each cell's D8 direction on the filled heights (the steepest drop per distance;
 * where there is none, on a flat, the flood's parent), then the accumulation: the cells
 * that drain through each cell, itself included. SYL_OK or SYL_ELIMIT. */
void terrain_d8(const Terrain *t, const float *filled, const uint8_t *parent, uint8_t *dir, int threads);
int terrain_accumulate(Terrain *t, const uint8_t *dir, float *acc, const SylSink *sink);

/* wetness.c: ln(a / tan β), a = acc · cell, tan β at least TERRAIN_MIN_TAN. */
#define TERRAIN_MIN_TAN 0.001
void terrain_wetness(const Terrain *t, const float *acc, const float *slope, float *out, int threads);

/* insolation.c */
typedef struct TerrainSun {
    float dir[3];  /* unit vector toward the sun, y up */
    float weight;  /* how many of the year's samples it stands for */
} TerrainSun;
/* The sun positions above the horizon over a year at latitude (degrees): days sampled days
 * placed symmetrically about the June solstice (so that pairs of days share a declination
 * and are traced once, weight 2), one position every minutes (mid-interval). Free the
 * array. NULL when out of memory; *n may be 0 (a polar night). */
TerrainSun *terrain_suns(double latitude, int days, double minutes, size_t *n);
/* The direct sun on each cell (max(0, n·s), zero where the terrain is between the cell and
 * the sun) summed over suns, over the same sum on open flat ground. SYL_OK, SYL_ELIMIT. */
/* Upper bounds of the tangent of each cell's horizon in each quadrant of directions
 * (horizon.c): bound[q * cells + cell] for directions of x sign (q & 1 ? + : −) and z sign
 * (q & 2 ? + : −); a sun higher than it needs no ray. scratch holds 2 grids. */
void terrain_horizon_bound(const Terrain *t, float *bound, float *scratch);
int terrain_insolation(Terrain *t, const TerrainSun *suns, size_t nsuns, float *out, int threads, const SylSink *sink);

/* wind.c: Winstral et al. (2002) Sx, degrees, for wind from the azimuth from (degrees
 * clockwise from north) within distance dmax. */
void terrain_wind(const Terrain *t, double from, double dmax, float *out, int threads);

/* Zamuda's (2006) measures, one file each (docs/terrain.md): runoff.c his Algorithm 3 (SYL_OK
 * or SYL_ELIMIT), lee.c his Algorithm 4 (wind from the azimuth from, degrees), sunniness.c
 * his Algorithm 5 (SYL_OK, SYL_ELIMIT, or SYL_EUSAGE for an even or out-of-range count). */
int terrain_runoff(Terrain *t, const float *slope, double k_m, double water_level, float *out, const SylSink *sink);
void terrain_lee(const Terrain *t, double from, int samples, double theta0_deg, float *out, int threads);
int terrain_sunniness(Terrain *t, double latitude, int samples, double ambient, float *out, int threads, const SylSink *sink);

/* ---- maps (write.c) ---- */
int terrain_write_png(const Terrain *t, const float *grid, const char *name, const char *path, const SylSink *sink);
int terrain_write_asc(const Terrain *t, const float *grid, const char *path, const SylSink *sink);

#endif
