/* libsylva: terrains (digital elevation models) and the factors a plant's site has on them:
 * altitude, slope, aspect, flow accumulation, wetness, insolation and wind exposure,
 * computed as GIS computes them, or Zamuda's (2006) runoff humidity, sunniness and
 * windiness computed as his thesis does (docs/terrain.md).
 *
 * A terrain is a grid of nx × nz cells of one size lying in Sylva's x–z plane, heights along
 * y (up). North is −z and east is +x, so a raster's first row (its northern edge) is the
 * row of the smallest z. Cell (i, k) is centred at (x0 + (i + ½)·cell, z0 + (k + ½)·cell):
 * (x0, z0) is the grid's north-west corner. Values are addressed cell by cell,
 * grid[k * nx + i], or sampled anywhere with syl_terrain_factor_at. */
#ifndef SYLVA_TERRAIN_H
#define SYLVA_TERRAIN_H
#include <stdint.h>
#include <stdio.h>

#include "sylva/sylva.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum SylTerrainFactor {
    SYL_TERRAIN_ALTITUDE,   /* the height, in the DEM's units (metres) */
    SYL_TERRAIN_SLOPE,      /* degrees, 0 flat (Horn 1981) */
    SYL_TERRAIN_ASPECT,     /* degrees clockwise from north the slope faces; −1 where flat */
    SYL_TERRAIN_FLOW,       /* D8 flow accumulation after depression filling: cells draining
                               through the cell, itself included */
    SYL_TERRAIN_WETNESS,    /* topographic wetness index ln(a / tan β) */
    SYL_TERRAIN_INSOLATION, /* a year's direct sun with the terrain's shadows, relative to open
                               flat ground at the same latitude */
    SYL_TERRAIN_WIND,       /* Winstral's Sx, degrees: > 0 sheltered, < 0 exposed */
    /* Zamuda's measures (computed only with SYL_TERRAIN_ZAMUDA) */
    SYL_TERRAIN_HUMIDITY,   /* his runoff humidity (Algorithm 3), in rain units: 1 where water
                               neither comes nor goes */
    SYL_TERRAIN_SUNNINESS,  /* his sunniness (Algorithm 5): weighted cosines of a day's suns */
    SYL_TERRAIN_WINDINESS,  /* his lee-angle windiness (Algorithm 4): 1 open, 0 sheltered */
    SYL_TERRAIN_FACTORS
} SylTerrainFactor;

/* Which measures of water, sun and wind syl_terrain_compute makes (altitude, slope and aspect
 * always): GIS's flow, wetness, insolation and wind, Zamuda's humidity, sunniness and
 * windiness, or both. 0 is GIS's. */
enum { SYL_TERRAIN_GIS = 1, SYL_TERRAIN_ZAMUDA = 2, SYL_TERRAIN_BOTH = 3 };

typedef struct SylTerrainOptions {
    /* reading */
    double cell;            /* PNG: cell size (default 1); OBJ: grid spacing (default: about
                               one cell per vertex); ASC: ignored (the file's cellsize) */
    double height_lo, height_hi; /* PNG: the heights of grey 0 and of white (default 0, 1
                                    when both are 0) */
    /* insolation */
    double latitude;        /* degrees north (default 46 when `sun_set` is 0) */
    int sun_days;           /* days sampled across the year (default 12) */
    double sun_minutes;     /* minutes between sun positions in a day (default 60) */
    int sun_set;            /* latitude was given (0 is the equator) */
    /* wind */
    double wind_from;       /* azimuth the prevailing wind comes from, degrees (default 270) */
    double wind_distance;   /* Winstral's search distance d_max (default 300) */
    int wind_set;           /* wind_from was given */
    /* Zamuda's measures (0: his values, docs/terrain.md) */
    int measures;           /* SYL_TERRAIN_GIS (0 too), SYL_TERRAIN_ZAMUDA or SYL_TERRAIN_BOTH */
    double runoff;          /* k_m: a patch of his slope s sheds min(1, s k_m) of its water to
                               its lower neighbours (default 10) */
    double water_level;     /* normalised height below which patches are water, + 10 (default 0:
                               none) */
    int lee_samples;        /* N_w, patches marched upwind (default 10) */
    double lee_angle;       /* Θ0, degrees: lee angles above it shelter nothing (default 45) */
    int sun_samples;        /* N_l, odd: the day's sun positions (default 9) */
    double ambient;         /* l_ambient: light of a shadowed or back-lit sample (default 0.2) */
    int threads;            /* <= 0: all cores; the maps never depend on it */
    SylBudget *budget;      /* NULL: a budget of max_memory (or the default) */
    uint64_t max_memory;
    FILE *diag;
    const SylSink *sink;   /* or as records to this sink instead (sylva.h); NULL: diag */
} SylTerrainOptions;

typedef struct SylTerrain {
    int nx, nz;          /* cells along x (columns) and z (rows) */
    double cell;         /* cell size */
    double x0, z0;       /* the north-west corner */
    float *height;       /* nx * nz */
    uint8_t *valid;      /* 0 where the DEM had no data (its height was filled in), else 1 */
    float *factor[SYL_TERRAIN_FACTORS]; /* each nx * nz once computed, NULL before */
    double seconds[SYL_TERRAIN_FACTORS];     /* how long each took, wall clock (the aspect's is
                                                with the slope's; altitude: none) */
    double cpu_seconds[SYL_TERRAIN_FACTORS]; /* the same in processor time, every thread's */
    uint64_t sun_pairs, rays;   /* insolation: (cell, sun) pairs facing the sun, rays traced */
    struct SylTerrainStore *store; /* the library's own record (the memory budget the grids
                                      count against), as SylSkeleton's and SylMesh's */
} SylTerrain;

/* Read a DEM: a greyscale PNG (8 or 16 bits), an ESRI ASCII grid (.asc) or an OBJ mesh
 * (rasterized by casting rays down), by the file's extension. SYL_OK, SYL_EMODEL (malformed,
 * reported as `file:line:col: error:` or `file: error:`), SYL_EIO, SYL_ELIMIT (too big for
 * the budget) or SYL_EUSAGE (bad options). */
int syl_terrain_read(const char *path, const SylTerrainOptions *o, SylTerrain **out);
/* Compute every factor. SYL_OK or SYL_ELIMIT. */
int syl_terrain_compute(SylTerrain *t, const SylTerrainOptions *o);
/* A factor bilinearly interpolated between cell centres at (x, z), clamped to the grid;
 * aspect is the nearest cell's. NaN when the factor has not been computed. */
double syl_terrain_factor_at(const SylTerrain *t, SylTerrainFactor f, double x, double z);
/* Write one factor's map: PATH.png is a 16-bit greyscale PNG whose text chunk "sylva:range"
 * holds the values of grey 0 and of white, PATH.asc an ESRI ASCII grid. */
int syl_terrain_write_map(const SylTerrain *t, SylTerrainFactor f, const char *path, const SylSink *sink);
const char *syl_terrain_factor_name(SylTerrainFactor f); /* "altitude", "slope", ... */

/* Pictures of a terrain for people (src/terrain/pictures.c), north up: a cell is `size` /
 * (the grid's longer side) pixels across, from 1 to 8 (size 0: 512). */
typedef struct SylMapOptions {
    int size;
} SylMapOptions;
/* Grey hillshade, lit from the north-west 45 degrees up (the ecosystem map's background).
 * SYL_OK or SYL_ELIMIT. */
int syl_terrain_draw_hillshade(const SylTerrain *t, const SylMapOptions *o, SylPicture *out);
/* A factor in colour over the hillshade gdaldem computes (the slope and aspect must have been
 * computed), with a legend of its colours, range and unit below: `sylva terrain --maps`'
 * NAME-colour.png. SYL_OK, SYL_EUSAGE (the factor or the slope not computed) or SYL_ELIMIT. */
int syl_terrain_draw_colour_map(const SylTerrain *t, SylTerrainFactor f, const SylMapOptions *o, SylPicture *out);
void syl_terrain_free(SylTerrain *t);

#ifdef __cplusplus
}
#endif
#endif
