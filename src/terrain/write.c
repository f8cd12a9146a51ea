/* Factor maps: a 16-bit greyscale PNG (grey 0 the grid's lowest value, white its highest;
 * the two values in the text chunk "sylva:range", the factor's name in "sylva:factor") and
 * an ESRI ASCII grid of the values themselves (NODATA_value −9999 where the DEM had none).
 * Both go through util/outfile: nothing half-written is left at the path. */
#include <math.h>
#include <png.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "terrain/terrain.h"
#include "util/outfile.h"

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

typedef struct PngErr {
    FILE *diag;
    const OutFile *o;
} PngErr;

static void on_error(png_structp png, png_const_charp msg) {
    PngErr *e = png_get_error_ptr(png);
    if (e->diag && !e->o->err) fprintf(e->diag, "sylva: error: cannot write '%s': %s\n", e->o->path, msg);
    png_longjmp(png, 1);
}

static void on_warning(png_structp png, png_const_charp msg) {
    (void)png;
    (void)msg;
}

static int encode(const Terrain *t, const float *g, const char *name, const OutFile *o, FILE *diag, double lo,
                  double hi) {
    PngErr err = {diag, o};
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &err, on_error, on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    uint16_t *row = malloc((size_t)t->nx * 2);
    if (!info || !row) {
        png_destroy_write_struct(&png, &info);
        free(row);
        if (diag) fprintf(diag, "sylva: error: out of memory writing '%s'\n", o->path);
        return SYL_ELIMIT;
    }
    volatile bool ok = false;
    if (!setjmp(png_jmpbuf(png))) {
        png_init_io(png, o->f);
        png_set_IHDR(png, info, (png_uint_32)t->nx, (png_uint_32)t->nz, 16, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
                     PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
        char range[64], cell[32];
        snprintf(range, sizeof range, "%.9g %.9g", lo, hi);
        snprintf(cell, sizeof cell, "%.9g", t->cell);
        png_text text[3] = {
            {.compression = PNG_TEXT_COMPRESSION_NONE, .key = "sylva:factor", .text = (char *)name},
            {.compression = PNG_TEXT_COMPRESSION_NONE, .key = "sylva:range", .text = range},
            {.compression = PNG_TEXT_COMPRESSION_NONE, .key = "sylva:cell", .text = cell},
        };
        png_set_text(png, info, text, 3);
        png_set_compression_level(png, 6);
        png_write_info(png, info);
        png_set_swap(png); /* rows are little-endian uint16_t; PNG is big-endian */
        double scale = hi > lo ? 65535 / (hi - lo) : 0;
        for (int k = 0; k < t->nz; k++) {
            const float *r = g + (size_t)k * (size_t)t->nx;
            for (int i = 0; i < t->nx; i++) {
                double p = (r[i] - lo) * scale;
                row[i] = p > 0 ? (uint16_t)(p < 65535 ? p + 0.5 : 65535) : 0;
            }
            png_write_row(png, (png_const_bytep)row);
        }
        png_write_end(png, info);
        ok = true;
    }
    png_destroy_write_struct(&png, &info);
    free(row);
    return ok ? SYL_OK : SYL_EIO;
}

int terrain_write_png(const Terrain *t, const float *grid, const char *name, const char *path, FILE *diag) {
    OutFile o;
    if (!outfile_open(&o, path, NULL, diag)) return SYL_EIO;
    double lo, hi;
    grid_range(t, grid, &lo, &hi);
    int st = encode(t, grid, name, &o, diag, lo, hi);
    if (!outfile_close(&o, st == SYL_OK, diag) && !st) st = SYL_EIO;
    return st;
}

int terrain_write_asc(const Terrain *t, const float *grid, const char *path, FILE *diag) {
    OutFile o;
    if (!outfile_open(&o, path, NULL, diag)) return SYL_EIO;
    fprintf(o.f, "ncols %d\nnrows %d\nxllcorner %.17g\nyllcorner %.17g\ncellsize %.17g\nNODATA_value -9999\n", t->nx,
            t->nz, t->x0 + 0.0, -(t->z0 + t->nz * t->cell) + 0.0, t->cell); /* + 0.0: never "-0" */
    for (int k = 0; k < t->nz; k++) {
        const float *r = grid + (size_t)k * (size_t)t->nx;
        const uint8_t *ok = t->valid + (size_t)k * (size_t)t->nx;
        for (int i = 0; i < t->nx; i++) {
            if (ok[i]) fprintf(o.f, i ? " %.9g" : "%.9g", r[i]);
            else fputs(i ? " -9999" : "-9999", o.f);
        }
        fputc('\n', o.f);
    }
    return outfile_close(&o, true, diag) ? SYL_OK : SYL_EIO;
}

int syl_terrain_write_map(const SylTerrain *t, SylTerrainFactor f, const char *path, FILE *diag) {
    const float *g = (unsigned)f < SYL_TERRAIN_FACTORS ? (f == SYL_TERRAIN_ALTITUDE ? t->height : t->factor[f]) : NULL;
    if (!g) {
        if (diag) fprintf(diag, "sylva: error: cannot write '%s': the factor has not been computed\n", path);
        return SYL_EUSAGE;
    }
    size_t n = strlen(path);
    if (n >= 4 && !strcasecmp(path + n - 4, ".png")) return terrain_write_png(t, g, syl_terrain_factor_name(f), path, diag);
    if (n >= 4 && !strcasecmp(path + n - 4, ".asc")) return terrain_write_asc(t, g, path, diag);
    if (diag) fprintf(diag, "sylva: error: cannot tell the map's format of '%s': name it *.png or *.asc\n", path);
    return SYL_EUSAGE;
}
