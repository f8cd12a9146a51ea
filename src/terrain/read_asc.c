/* The ESRI ASCII grid reader: a header of `key value` lines (ncols, nrows, xllcorner or
 * xllcenter, yllcorner or yllcenter, cellsize, optionally NODATA_value), then nrows rows of
 * ncols numbers, the northern row first, in any whitespace. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "terrain/terrain.h"
#include "util/diag.h"
#include "util/number.h"

typedef struct Scan {
    const char *s, *end;
    int line, col;
    Diag d;
} Scan;

static void skip_space(Scan *sc) {
    while (sc->s < sc->end && (*sc->s == ' ' || *sc->s == '\t' || *sc->s == '\r' || *sc->s == '\n')) {
        if (*sc->s == '\n') sc->line++, sc->col = 1;
        else sc->col++;
        sc->s++;
    }
}

/* The next token (up to whitespace); its length, 0 at the end. */
static size_t token(Scan *sc, SylLoc *loc) {
    skip_space(sc);
    *loc = (SylLoc){sc->line, sc->col, sc->line, sc->col};
    size_t n = 0;
    while (sc->s + n < sc->end && !strchr(" \t\r\n", sc->s[n]) && sc->s[n]) n++;
    if (n) loc->last_column = sc->col + (int)n - 1;
    return n;
}

static void advance(Scan *sc, size_t n) {
    sc->s += n;
    sc->col += (int)n;
}

static bool is_word(const char *s, size_t n, const char *w) { return strlen(w) == n && !strncasecmp(s, w, n); }

enum { K_NCOLS, K_NROWS, K_XLL, K_YLL, K_CELL, K_NODATA, K_N };

int terrain_read_asc(const char *path, const char *text, size_t len, const SylTerrainOptions *o, Terrain **out) {
    *out = NULL;
    Source src = {path, text, len};
    Scan sc = {text, text + len, 1, 1, {.out = o->diag, .sink = o->sink, .src = &src, .max_shown = 1}};
    double v[K_N] = {0};
    bool have[K_N] = {0}, xcenter = false, ycenter = false;
    static const char *const key_name[K_N] = {"ncols", "nrows", "xllcorner", "yllcorner", "cellsize", "NODATA_value"};
    SylLoc loc, vloc;
    for (;;) {
        size_t n = token(&sc, &loc);
        double num;
        if (n == 0 || number_read(sc.s, n, &num)) break; /* the grid begins */
        int key = -1;
        if (is_word(sc.s, n, "ncols")) key = K_NCOLS;
        else if (is_word(sc.s, n, "nrows")) key = K_NROWS;
        else if (is_word(sc.s, n, "xllcorner")) key = K_XLL;
        else if (is_word(sc.s, n, "xllcenter")) key = K_XLL, xcenter = true;
        else if (is_word(sc.s, n, "yllcorner")) key = K_YLL;
        else if (is_word(sc.s, n, "yllcenter")) key = K_YLL, ycenter = true;
        else if (is_word(sc.s, n, "cellsize")) key = K_CELL;
        else if (is_word(sc.s, n, "nodata_value")) key = K_NODATA;
        else if (is_word(sc.s, n, "dx") || is_word(sc.s, n, "dy")) {
            diag_error(&sc.d, loc, "cells of different width and height (dx, dy) are not read: Sylva's cells are square");
            return SYL_EMODEL;
        } else {
            char q[80];
            diag_error(&sc.d, loc, "'%s' is not a key of an ESRI ASCII grid (ncols, nrows, xllcorner, yllcorner, "
                                   "cellsize, NODATA_value)", diag_quote(q, sizeof q, sc.s, n));
            return SYL_EMODEL;
        }
        if (have[key]) {
            diag_error(&sc.d, loc, "%s is given twice", key_name[key]);
            return SYL_EMODEL;
        }
        int line = sc.line;
        advance(&sc, n);
        size_t m = token(&sc, &vloc);
        if (m == 0 || sc.line != line || !number_read(sc.s, m, &v[key])) {
            if (m == 0 || sc.line != line) vloc = (SylLoc){line, loc.last_column + 1, line, loc.last_column + 1};
            diag_error(&sc.d, vloc, "%s expects a number", key_name[key]);
            return SYL_EMODEL;
        }
        if ((key == K_NCOLS || key == K_NROWS) && (v[key] < 1 || v[key] != floor(v[key]))) {
            diag_error(&sc.d, vloc, "%s must be a whole number of at least 1", key_name[key]);
            return SYL_EMODEL;
        }
        if (key == K_CELL && !(v[key] >= TERRAIN_MIN_CELL && v[key] <= TERRAIN_MAX_CELL)) {
            diag_error(&sc.d, vloc, "cellsize must be from %g to %g", TERRAIN_MIN_CELL, TERRAIN_MAX_CELL);
            return SYL_EMODEL;
        }
        if ((key == K_XLL || key == K_YLL) && !(fabs(v[key]) <= TERRAIN_MAX_CORNER)) {
            diag_error(&sc.d, vloc, "%s must lie within %g of 0", key_name[key], TERRAIN_MAX_CORNER);
            return SYL_EMODEL;
        }
        have[key] = true;
        advance(&sc, m);
    }
    for (int k = 0; k < K_NODATA; k++)
        if (!have[k]) {
            diag_error(&sc.d, loc, "the header lacks %s%s before the grid's values", key_name[k],
                       k == K_XLL ? " (or xllcenter)" : k == K_YLL ? " (or yllcenter)" : "");
            return SYL_EMODEL;
        }
    if (v[K_NCOLS] > TERRAIN_MAX_SIDE || v[K_NROWS] > TERRAIN_MAX_SIDE) {
        diag_error(&sc.d, loc, "a %.0f x %.0f grid: Sylva reads 1 to %d cells a side", v[K_NCOLS], v[K_NROWS],
                   TERRAIN_MAX_SIDE);
        return SYL_ELIMIT;
    }
    int nx = (int)v[K_NCOLS], nz = (int)v[K_NROWS];
    Terrain *t;
    int st = terrain_new(nx, nz, o->budget, o->max_memory, path, opt_sink(o), &t);
    if (st) return st;
    double cell = v[K_CELL];
    t->cell = cell;
    /* The grid's north-west corner in Sylva's x–z: north is −z. */
    double xll = v[K_XLL] - (xcenter ? cell / 2 : 0), yll = v[K_YLL] - (ycenter ? cell / 2 : 0);
    t->x0 = xll;
    t->z0 = -(yll + nz * cell);
    size_t total = (size_t)nx * (size_t)nz, c = 0;
    for (; c < total; c++) {
        size_t n = token(&sc, &loc);
        if (n == 0) {
            diag_error(&sc.d, loc, "the grid ends after %zu of its %zu values (%d x %d)", c, total, nx, nz);
            syl_terrain_free(t);
            return SYL_EMODEL;
        }
        double h;
        if (!number_read(sc.s, n, &h)) {
            char q[80];
            diag_error(&sc.d, loc, "'%s' is not a number (value %zu: row %zu, column %zu)",
                       diag_quote(q, sizeof q, sc.s, n), c + 1, c / nx + 1, c % nx + 1);
            syl_terrain_free(t);
            return SYL_EMODEL;
        }
        if (have[K_NODATA] && h == v[K_NODATA]) t->valid[c] = 0;
        else if (fabs(h) > 1e9) {
            diag_error(&sc.d, loc, "a height of %g: Sylva reads heights up to 1e9 in size", h);
            syl_terrain_free(t);
            return SYL_EMODEL;
        } else t->height[c] = (float)h;
        advance(&sc, n);
    }
    if (token(&sc, &loc)) {
        diag_error(&sc.d, loc, "more values than the %d x %d the header gives", nx, nz);
        syl_terrain_free(t);
        return SYL_EMODEL;
    }
    if (!terrain_fill_unknown(t)) {
        diag_error(&sc.d, (SylLoc){0}, "every value is NODATA_value: no height is known");
        syl_terrain_free(t);
        return SYL_EMODEL;
    }
    *out = t;
    return SYL_OK;
}
