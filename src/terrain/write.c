/* Factor maps: a 16-bit greyscale PNG (grey 0 the grid's lowest value, white its highest;
 * the two values in the text chunk "sylva:range", the factor's name in "sylva:factor") and
 * an ESRI ASCII grid of the values themselves (NODATA_value where the DEM had none: −9999, or
 * −99999, −999999 ... when the data reach −9999, so that no value reads back as missing).
 * Both go through util/outfile: nothing half-written is left at the path. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "terrain/terrain.h"
#include "util/diag.h"
#include "util/outfile.h"
#include "util/pngout.h"

static void grid_range(const Terrain *t, const float *g, double *lo, double *hi) {
    size_t n = (size_t)t->nx * (size_t)t->nz;
    *lo = INFINITY, *hi = -INFINITY;
    for (size_t c = 0; c < n; c++)
        if (t->valid[c]) {
            if (g[c] < *lo) *lo = g[c];
            if (g[c] > *hi) *hi = g[c];
        }
    if (*lo > *hi) *lo = *hi = 0;
}

/* A grid's rows as 16-bit grey, lo..hi spread over 0..65535. */
typedef struct Grey16 {
    const Terrain *t;
    const float *g;
    double lo, scale;
} Grey16;

static const void *grey_row(void *ctx, int k, void *scratch) {
    const Grey16 *s = ctx;
    const float *r = s->g + (size_t)k * (size_t)s->t->nx;
    uint16_t *row = scratch;
    for (int i = 0; i < s->t->nx; i++) {
        double p = (r[i] - s->lo) * s->scale;
        row[i] = p > 0 ? (uint16_t)(p < 65535 ? p + 0.5 : 65535) : 0;
    }
    return row;
}

static int encode(const Terrain *t, const float *g, const char *name, const OutFile *o, const SylSink *sink, double lo,
                  double hi) {
    char range[64], cell[32];
    snprintf(range, sizeof range, "%.9g %.9g", lo, hi);
    snprintf(cell, sizeof cell, "%.9g", t->cell);
    PngOutText text[3] = {{"sylva:factor", name}, {"sylva:range", range}, {"sylva:cell", cell}};
    Grey16 src = {t, g, lo, hi > lo ? 65535 / (hi - lo) : 0};
    PngOutImage img = {.width = t->nx, .height = t->nz, .channels = 1, .depth = 16, .level = 6,
                       .text = text, .ntext = 3, .row = grey_row, .ctx = &src};
    return pngout_encode(o, &img, sink);
}

int terrain_write_png(const Terrain *t, const float *grid, const char *name, const char *path, const SylSink *sink) {
    OutFile o;
    if (!outfile_open(&o, path, NULL, sink)) return SYL_EIO;
    double lo, hi;
    grid_range(t, grid, &lo, &hi);
    int st = encode(t, grid, name, &o, sink, lo, hi);
    if (!outfile_close(&o, st == SYL_OK, sink) && !st) st = SYL_EIO;
    return st;
}

int terrain_write_asc(const Terrain *t, const float *grid, const char *path, const SylSink *sink) {
    OutFile o;
    if (!outfile_open(&o, path, NULL, sink)) return SYL_EIO;
    double lo, hi, nodata = -9999;
    grid_range(t, grid, &lo, &hi);
    while (nodata >= lo && nodata > -1e300) nodata = nodata * 10 - 9; /* below every value */
    char nd[32];
    snprintf(nd, sizeof nd, "%.0f", nodata);
    fprintf(o.f, "ncols %d\nnrows %d\nxllcorner %.17g\nyllcorner %.17g\ncellsize %.17g\nNODATA_value %s\n", t->nx,
            t->nz, t->x0 + 0.0, -(t->z0 + t->nz * t->cell) + 0.0, t->cell, nd); /* + 0.0: never "-0" */
    for (int k = 0; k < t->nz; k++) {
        const float *r = grid + (size_t)k * (size_t)t->nx;
        const uint8_t *ok = t->valid + (size_t)k * (size_t)t->nx;
        for (int i = 0; i < t->nx; i++) {
            if (ok[i]) fprintf(o.f, i ? " %.9g" : "%.9g", r[i]);
            else fprintf(o.f, i ? " %s" : "%s", nd);
        }
        fputc('\n', o.f);
    }
    return outfile_close(&o, true, sink) ? SYL_OK : SYL_EIO;
}

int syl_terrain_write_map(const SylTerrain *t, SylTerrainFactor f, const char *path, const SylSink *sink) {
    const float *g = (unsigned)f < SYL_TERRAIN_FACTORS ? (f == SYL_TERRAIN_ALTITUDE ? t->height : t->factor[f]) : NULL;
    if (!g) {
        sink_error(sink, "cannot write '%s': the factor has not been computed", path);
        return SYL_EUSAGE;
    }
    size_t n = strlen(path);
    if (n >= 4 && !strcasecmp(path + n - 4, ".png")) return terrain_write_png(t, g, syl_terrain_factor_name(f), path, sink);
    if (n >= 4 && !strcasecmp(path + n - 4, ".asc")) return terrain_write_asc(t, g, path, sink);
    sink_error(sink, "cannot tell the map's format of '%s': name it *.png or *.asc", path);
    return SYL_EUSAGE;
}
