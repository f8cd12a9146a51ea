/* Zamuda's DEM text (his "DMR", digitalni model reliefa; docs/terrain.md#formats): every
 * vertex as three values one a line, x, then z, then the height y, on a square grid (his
 * satellite data: 25 m). Each vertex is the centre of a cell; the spacing is the file's own. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "terrain/terrain.h"
#include "util/diag.h"
#include "util/number.h"

static int by_value(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The distinct values of v[0..n) (sorted into u), and whether they step evenly by *step. */
static int distinct(const double *v, size_t n, double *u, double *step) {
    memcpy(u, v, n * sizeof *u);
    qsort(u, n, sizeof *u, by_value);
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (!m || u[i] != u[m - 1]) u[m++] = u[i];
    *step = m > 1 ? (u[m - 1] - u[0]) / (double)(m - 1) : 0;
    for (size_t i = 1; i < m; i++)
        if (fabs(u[i] - u[i - 1] - *step) > 1e-6 * fabs(*step)) return -1;
    return (int)(m > (size_t)TERRAIN_MAX_SIDE ? -1 : (int)m);
}

int terrain_read_dmr(const char *path, const char *text, size_t len, const SylTerrainOptions *o, Terrain **out) {
    *out = NULL;
    Source src = {path, text, len};
    Diag d = {.out = o->diag, .sink = o->sink, .src = &src, .max_shown = 1};
    size_t n = 0, cap = 0;
    double *v = NULL;
    int line = 0;
    for (const char *p = text, *end = text + len; p < end;) {
        const char *nl = memchr(p, '\n', (size_t)(end - p)), *e = nl ? nl : end, *b = p, *start = p;
        line++;
        p = nl ? nl + 1 : end;
        while (b < e && strchr(" \t\r", *b)) b++;
        const char *w = e;
        while (w > b && strchr(" \t\r", w[-1])) w--;
        if (b == w) continue; /* a blank line */
        double x;
        if (!number_read(b, (size_t)(w - b), &x) || fabs(x) > TERRAIN_MAX_CORNER) {
            char q[80];
            int col = (int)(b - start) + 1;
            SylLoc at = {line, col, line, col + (int)(w - b) - 1};
            diag_error(&d, at, "'%s' is not a number: a DMR file is one value a line (x, z, then the height)",
                       diag_quote(q, sizeof q, b, (size_t)(w - b)));
            free(v);
            return SYL_EMODEL;
        }
        if (n == cap) {
            cap = cap ? 2 * cap : 3072;
            double *g = realloc(v, cap * sizeof *v);
            if (!g) {
                free(v);
                diag_say(o->diag, o->sink, DIAG_ERROR, path, "out of memory");
                return SYL_ELIMIT;
            }
            v = g;
        }
        v[n++] = x;
    }
    size_t nv = n / 3;
    if (n % 3 || nv < 1) {
        diag_error(&d, (SylLoc){0}, "%zu values: a DMR file holds three a vertex (x, z, height)", n);
        free(v);
        return SYL_EMODEL;
    }
    double *xs = malloc(nv * sizeof *xs), *zs = malloc(nv * sizeof *zs), *ux = malloc(nv * sizeof *ux),
           *uz = malloc(nv * sizeof *uz);
    int st = xs && zs && ux && uz ? SYL_OK : SYL_ELIMIT;
    for (size_t i = 0; !st && i < nv; i++) xs[i] = v[3 * i], zs[i] = v[3 * i + 1];
    double sx = 0, sz = 0;
    int nx = st ? 0 : distinct(xs, nv, ux, &sx), nz = st ? 0 : distinct(zs, nv, uz, &sz);
    double cell = nx > 1 ? sx : sz;
    Terrain *t = NULL;
    if (st) {
        diag_say(o->diag, o->sink, DIAG_ERROR, path, "out of memory");
    } else if (nx < 1 || nz < 1 || (nx > 1 && nz > 1 && fabs(sx - sz) > 1e-6 * sx) || (size_t)nx * (size_t)nz != nv ||
               !(cell >= TERRAIN_MIN_CELL && cell <= TERRAIN_MAX_CELL)) {
        diag_error(&d, (SylLoc){0},
                   "the %zu vertices are not a square grid, each (x, z) once at one spacing (Zamuda's: 25 m)", nv);
        st = SYL_EMODEL;
    } else {
        st = terrain_new(nx, nz, o->budget, o->max_memory, path, opt_sink(o), &t);
    }
    if (!st) {
        t->cell = cell;
        t->x0 = ux[0] - cell / 2, t->z0 = uz[0] - cell / 2; /* x east, z south, as he read them */
        uint8_t *seen = calloc(nv, 1);
        for (size_t i = 0; seen && i < nv && !st; i++) {
            size_t c = (size_t)lround((v[3 * i + 1] - uz[0]) / cell) * (size_t)nx + (size_t)lround((v[3 * i] - ux[0]) / cell);
            double h = v[3 * i + 2];
            if (seen[c] || fabs(h) > 1e9) {
                diag_error(&d, (SylLoc){0}, seen[c] ? "the vertex (%g, %g) is given twice"
                                                    : "a height of %g: Sylva reads heights up to 1e9 in size",
                           seen[c] ? v[3 * i] : h, v[3 * i + 1]);
                st = SYL_EMODEL;
            }
            seen[c] = 1, t->height[c] = (float)h;
        }
        if (!seen) st = SYL_ELIMIT;
        free(seen);
        if (st) syl_terrain_free(t);
        else *out = t;
    }
    free(v), free(xs), free(zs), free(ux), free(uz);
    return st;
}
