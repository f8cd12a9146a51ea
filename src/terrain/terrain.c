/* The terrain grid: allocation against the budget, Horn's window, sampling, names. */
#include "terrain/terrain.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "util/budget.h"
#include "util/file.h"

static const char *const names[SYL_TERRAIN_FACTORS] = {
    "altitude", "slope", "aspect", "flow", "wetness", "insolation", "wind", "humidity", "sunniness", "windiness",
};

const char *syl_terrain_factor_name(SylTerrainFactor f) {
    return (unsigned)f < SYL_TERRAIN_FACTORS ? names[f] : "?";
}

int terrain_new(int nx, int nz, SylBudget *budget, uint64_t max_memory, const char *path, const SylSink *sink,
                Terrain **out) {
    *out = NULL;
    if (nx < 1 || nz < 1 || nx > TERRAIN_MAX_SIDE || nz > TERRAIN_MAX_SIDE) {
        diag_say(NULL, sink, DIAG_ERROR, path, "a %d x %d grid: Sylva reads 1 to %d cells a side", nx, nz,
                          TERRAIN_MAX_SIDE);
        return SYL_ELIMIT;
    }
    Terrain *t = calloc(1, sizeof *t);
    if (!t || !(t->store = calloc(1, sizeof *t->store))) goto nomem;
    t->nx = nx, t->nz = nz, t->cell = 1;
    if (budget) t->store->budget = budget;
    else {
        t->store->budget = syl_budget_new(max_memory);
        t->store->own_budget = true;
        if (!t->store->budget) goto nomem;
    }
    size_t n = (size_t)nx * (size_t)nz;
    uint64_t bytes = (uint64_t)n * (sizeof(float) + 1);
    if (!budget_charge(terrain_budget(t), bytes)) {
        diag_say(NULL, sink, DIAG_ERROR, path, "a %d x %d grid needs %llu MB, beyond the memory limit of %llu MB "
                          "(--max-memory)", nx, nz, (unsigned long long)(bytes >> 20),
                    (unsigned long long)budget_limit_mb(terrain_budget(t)));
        syl_terrain_free(t);
        return SYL_ELIMIT;
    }
    t->store->charged = bytes;
    t->height = calloc(n, sizeof(float));
    t->valid = malloc(n);
    if (!t->height || !t->valid) goto nomem;
    memset(t->valid, 1, n);
    *out = t;
    return SYL_OK;
nomem:
    diag_say(NULL, sink, DIAG_ERROR, path, "out of memory for a %d x %d grid", nx, nz);
    syl_terrain_free(t);
    return SYL_ELIMIT;
}

float *terrain_grid(Terrain *t, size_t elem, const SylSink *sink) {
    size_t n = (size_t)t->nx * (size_t)t->nz;
    uint64_t bytes = (uint64_t)n * elem;
    if (!budget_charge(terrain_budget(t), bytes)) {
        if (sink)
            sink_error(sink, "the terrain's maps need more than the memory limit of %llu MB "
                          "(--max-memory)\n", (unsigned long long)budget_limit_mb(terrain_budget(t)));
        return NULL;
    }
    void *g = calloc(n, elem);
    if (!g) {
        budget_release(terrain_budget(t), bytes);
        sink_error(sink, "out of memory for the terrain's maps");
        return NULL;
    }
    return g;
}

void terrain_grid_free(Terrain *t, void *grid, size_t elem) {
    if (!grid) return;
    free(grid);
    budget_release(terrain_budget(t), (uint64_t)t->nx * (uint64_t)t->nz * elem);
}

void syl_terrain_free(SylTerrain *t) {
    if (!t) return;
    for (int f = 0; f < SYL_TERRAIN_FACTORS; f++)
        if (t->factor[f] && t->factor[f] != t->height) terrain_grid_free(t, t->factor[f], sizeof(float));
    free(t->height);
    free(t->valid);
    if (t->store) {
        if (t->store->budget) budget_release(t->store->budget, t->store->charged);
        if (t->store->own_budget) syl_budget_free(t->store->budget);
        free(t->store);
    }
    free(t);
}

bool terrain_fill_unknown(Terrain *t) {
    size_t n = (size_t)t->nx * (size_t)t->nz;
    float lo = INFINITY;
    for (size_t c = 0; c < n; c++)
        if (t->valid[c] && t->height[c] < lo) lo = t->height[c];
    if (lo == INFINITY) return false;
    for (size_t c = 0; c < n; c++)
        if (!t->valid[c]) t->height[c] = lo;
    return true;
}

void terrain_horn(const Terrain *t, int i, int k, double *gx, double *gz) {
    float a = terrain_h(t, i - 1, k - 1), b = terrain_h(t, i, k - 1), c = terrain_h(t, i + 1, k - 1);
    float d = terrain_h(t, i - 1, k), f = terrain_h(t, i + 1, k);
    float g = terrain_h(t, i - 1, k + 1), h = terrain_h(t, i, k + 1), ii = terrain_h(t, i + 1, k + 1);
    /* Summed in float and in gdaldem's order, as gdaldem sums a float DEM's window, so that
     * the rounding matches too (the heights are floats already). */
    float ex = (c + f + f + ii) - (a + d + d + g), ez = (g + h + h + ii) - (a + b + b + c);
    *gx = ex / (8 * t->cell);
    *gz = ez / (8 * t->cell);
}

/* Bilinear in a grid of cell-centred values. */
static double bilinear(const Terrain *t, const float *g, double x, double z) {
    double u = (x - t->x0) / t->cell - 0.5, v = (z - t->z0) / t->cell - 0.5;
    if (!(u > 0)) u = 0; /* NaN too */
    if (!(v > 0)) v = 0;
    if (u > t->nx - 1) u = t->nx - 1;
    if (v > t->nz - 1) v = t->nz - 1;
    int i = (int)u, k = (int)v;
    int i1 = i + 1 < t->nx ? i + 1 : i, k1 = k + 1 < t->nz ? k + 1 : k;
    double fu = u - i, fv = v - k;
    size_t nx = (size_t)t->nx;
    double a = g[k * nx + i], b = g[k * nx + i1], c = g[k1 * nx + i], d = g[k1 * nx + i1];
    return (a * (1 - fu) + b * fu) * (1 - fv) + (c * (1 - fu) + d * fu) * fv;
}

double terrain_height_at(const Terrain *t, double x, double z) { return bilinear(t, t->height, x, z); }

double terrain_max_rise(const Terrain *t, size_t i, size_t k, double ux, double uz, int steps) {
    double xlo = t->x0 + t->cell / 2, xhi = t->x0 + (t->nx - 0.5) * t->cell;
    double zlo = t->z0 + t->cell / 2, zhi = t->z0 + (t->nz - 0.5) * t->cell;
    double x = t->x0 + (i + 0.5) * t->cell, z = t->z0 + (k + 0.5) * t->cell, h = t->height[k * (size_t)t->nx + i];
    double best = -INFINITY;
    for (int s = 1; s <= steps; s++) {
        double d = s * t->cell, sx = x + ux * d, sz = z + uz * d;
        /* a little slack: a march along a row or column stays on it despite rounding */
        double e = 1e-9 * t->cell;
        if (sx < xlo - e || sx > xhi + e || sz < zlo - e || sz > zhi + e) break;
        double r = (terrain_height_at(t, sx, sz) - h) / d;
        if (r > best) best = r;
    }
    return best;
}

double terrain_factor_at(const Terrain *t, TerrainFactor f, double x, double z) {
    if ((unsigned)f >= SYL_TERRAIN_FACTORS) return NAN;
    const float *g = f == SYL_TERRAIN_ALTITUDE ? t->height : t->factor[f];
    if (!g) return NAN;
    if (f != SYL_TERRAIN_ASPECT) return bilinear(t, g, x, z);
    /* An angle (and −1 on flats) does not interpolate: the nearest cell's. */
    double u = floor((x - t->x0) / t->cell), v = floor((z - t->z0) / t->cell);
    int i = !(u > 0) ? 0 : u > t->nx - 1 ? t->nx - 1 : (int)u;
    int k = !(v > 0) ? 0 : v > t->nz - 1 ? t->nz - 1 : (int)v;
    return g[(size_t)k * (size_t)t->nx + (size_t)i];
}

double syl_terrain_factor_at(const SylTerrain *t, SylTerrainFactor f, double x, double z) {
    return terrain_factor_at(t, f, x, z);
}

static bool ends_with(const char *s, const char *ext) {
    size_t n = strlen(s), e = strlen(ext);
    return n >= e && !strcasecmp(s + n - e, ext);
}

int syl_terrain_read(const char *path, const SylTerrainOptions *o, SylTerrain **out) {
    *out = NULL;
    const SylSink *sink = opt_sink(o);
    bool png = ends_with(path, ".png"), asc = ends_with(path, ".asc"), obj = ends_with(path, ".obj"),
         dmr = ends_with(path, ".dmr");
    if (!png && !asc && !obj && !dmr) {
        diag_say(NULL, sink, DIAG_ERROR, path, "cannot tell the DEM's format: name it *.png, *.asc, *.obj or *.dmr");
        return SYL_EUSAGE;
    }
    if (o->cell != 0 && !(o->cell >= TERRAIN_MIN_CELL && o->cell <= TERRAIN_MAX_CELL)) {
        sink_error(sink, "a cell size of %g: Sylva takes %g to %g", o->cell, TERRAIN_MIN_CELL,
                          TERRAIN_MAX_CELL);
        return SYL_EUSAGE;
    }
    if (!(fabs(o->height_lo) <= 1e9 && fabs(o->height_hi) <= 1e9)) {
        sink_error(sink, "heights of %g and %g: Sylva takes heights up to 1e9 in size",
                          o->height_lo, o->height_hi);
        return SYL_EUSAGE;
    }
    if (obj) return terrain_read_obj(path, o, out);
    size_t len;
    char *data = file_read_named(path, &len, o->budget);
    if (!data) {
        int e = errno; /* before the message, which may change it */
        sink_error(sink, "cannot read '%s': %s", path, file_strerror(e));
        return e == ENOMEM || e == FILE_EBUDGET ? SYL_ELIMIT : SYL_EIO;
    }
    int st = png   ? terrain_read_png(path, (const uint8_t *)data, len, o, out)
             : dmr ? terrain_read_dmr(path, data, len, o, out)
                   : terrain_read_asc(path, data, len, o, out);
    file_free_named(data, len, o->budget);
    return st;
}
