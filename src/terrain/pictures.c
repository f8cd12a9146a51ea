/* Pictures of a terrain for people (sylva/terrain.h): the grey hillshade an ecosystem's map
 * is drawn on, and each factor in colour over the terrain's hillshade, north up, with a legend
 * of its colours, its range and its unit below the map (`sylva terrain --maps`'
 * NAME-colour.png, beside the grey NAME.png that programs read). */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/font.h"
#include "sylva/terrain.h"

/* Pixels per cell: a map of about o->size (512) pixels, 1 to 8 a cell. */
static int cell_pixels(const SylTerrain *t, const SylMapOptions *o) {
    double size = t->nx > t->nz ? t->nx : t->nz, want = o && o->size > 0 ? o->size : 512;
    int px = size >= want ? 1 : (int)(want / size);
    return px > 8 ? 8 : px;
}

int syl_terrain_draw_hillshade(const SylTerrain *t, const SylMapOptions *o, SylPicture *out) {
    *out = (SylPicture){0};
    int px = cell_pixels(t, o), w = t->nx * px, h = t->nz * px;
    uint8_t *rgb = malloc((size_t)w * h * 3 + 1);
    if (!rgb) return SYL_ELIMIT;
    double lx = -0.5, ly = 0.7071, lz = -0.5; /* towards the light: north-west, up */
    for (int k = 0; k < t->nz; k++)
        for (int i = 0; i < t->nx; i++) {
            int i0 = i > 0 ? i - 1 : i, i1 = i + 1 < t->nx ? i + 1 : i;
            int k0 = k > 0 ? k - 1 : k, k1 = k + 1 < t->nz ? k + 1 : k;
            double dx = (t->height[(size_t)k * t->nx + i1] - t->height[(size_t)k * t->nx + i0]) / ((i1 - i0) * t->cell + 1e-12);
            double dz = (t->height[(size_t)k1 * t->nx + i] - t->height[(size_t)k0 * t->nx + i]) / ((k1 - k0) * t->cell + 1e-12);
            double nx = -dx, ny = 1, nz = -dz, len = sqrt(nx * nx + ny * ny + nz * nz);
            double c = (nx * lx + ny * ly + nz * lz) / len;
            uint8_t g = (uint8_t)(60 + 170 * (c > 0 ? c : 0));
            for (int b = 0; b < px; b++) memset(rgb + 3 * ((size_t)(k * px + b) * w + (size_t)i * px), g, 3 * (size_t)px);
        }
    *out = (SylPicture){rgb, w, h};
    return SYL_OK;
}

/* Dark blue to yellow, a ramp that stays readable in grey and to most colour-blind eyes. */
static const double ramp_stops[][3] = {{0.13, 0.05, 0.33}, {0.15, 0.35, 0.55}, {0.13, 0.6, 0.5},
                                       {0.55, 0.8, 0.25}, {0.99, 0.9, 0.15}};
enum { NSTOPS = sizeof ramp_stops / sizeof ramp_stops[0] };

static void ramp(double u, double c[3]) {
    u = (u < 0 ? 0 : u > 1 ? 1 : u) * (NSTOPS - 1);
    int i = (int)u < NSTOPS - 2 ? (int)u : NSTOPS - 2;
    for (int k = 0; k < 3; k++) c[k] = ramp_stops[i][k] + (ramp_stops[i + 1][k] - ramp_stops[i][k]) * (u - i);
}

/* Aspect: a colour wheel, red facing north, green 120 degrees, blue 240. */
static void wheel(double deg, double c[3]) {
    double h = fmod(deg, 360) / 60, x = 0.85 * (1 - fabs(fmod(h, 2) - 1));
    static const int pick[6][3] = {{2, 1, 0}, {1, 2, 0}, {0, 2, 1}, {0, 1, 2}, {1, 0, 2}, {2, 0, 1}};
    double v[3] = {0, x, 0.85};
    for (int k = 0; k < 3; k++) c[k] = v[pick[(int)h % 6][k]];
}

static const char *const units[SYL_TERRAIN_FACTORS] = {
    [SYL_TERRAIN_ALTITUDE] = "M", [SYL_TERRAIN_SLOPE] = "DEGREES", [SYL_TERRAIN_ASPECT] = "DEGREES FROM NORTH",
    [SYL_TERRAIN_FLOW] = "CELLS DRAINING, LOG SCALE", [SYL_TERRAIN_WETNESS] = "LN(A / TAN B)",
    [SYL_TERRAIN_INSOLATION] = "RELATIVE TO OPEN FLAT GROUND", [SYL_TERRAIN_WIND] = "DEGREES, + SHELTERED",
    [SYL_TERRAIN_HUMIDITY] = "RAIN UNITS, 1 WHERE NONE RUNS", [SYL_TERRAIN_SUNNINESS] = "MEAN WEIGHTED COSINE TO THE SUN",
    [SYL_TERRAIN_WINDINESS] = "1 OPEN, 0 SHELTERED",
};

/* The value a colour stands for: flow on a log scale. */
static double shown(SylTerrainFactor f, double v) { return f == SYL_TERRAIN_FLOW ? log10(v > 1 ? v : 1) : v; }

static void colour_of(SylTerrainFactor f, double v, double lo, double hi, double c[3]) {
    if (f == SYL_TERRAIN_ASPECT) {
        if (v < 0) c[0] = c[1] = c[2] = 0.6; /* flat */
        else wheel(v, c);
        return;
    }
    ramp(hi > lo ? (shown(f, v) - lo) / (hi - lo) : 0.5, c);
}

static void put(uint8_t *o, const double c[3], double s) {
    for (int k = 0; k < 3; k++) {
        double v = 255 * c[k] * s + 0.5;
        o[k] = (uint8_t)(v > 255 ? 255 : v < 0 ? 0 : v);
    }
}

static void number(char *buf, size_t n, double v) {
    if (fabs(v) >= 1000 || v == floor(v)) snprintf(buf, n, "%.0f", v);
    else snprintf(buf, n, fabs(v) >= 10 ? "%.1f" : "%.2f", v);
}

static int draw(const SylTerrain *t, SylTerrainFactor f, const float *shade, int px, SylPicture *out) {
    const float *g = t->factor[f];
    int mw = t->nx * px, mh = t->nz * px, s = mw >= 400 ? 2 : 1, strip = 34 * s;
    char title[96], a[32], b[32];
    snprintf(title, sizeof title, "%s (%s)", syl_terrain_factor_name(f), units[f]);
    int w = mw, h = mh + strip, need = font_text_width(title, s) + 8 * s;
    if (w < need) w = need;
    if (w < 200 * s) w = 200 * s;
    uint8_t *rgb = calloc((size_t)w * h, 3);
    if (!rgb) return SYL_ELIMIT;
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < (size_t)t->nx * t->nz; i++)
        if ((!t->valid || t->valid[i]) && isfinite(g[i]) && !(f == SYL_TERRAIN_ASPECT && g[i] < 0))
            lo = fmin(lo, shown(f, g[i])), hi = fmax(hi, shown(f, g[i]));
    if (!(lo <= hi)) lo = hi = 0;
    static const double nodata[3] = {0.85, 0.85, 0.85};
    for (int k = 0; k < t->nz; k++)
        for (int i = 0; i < t->nx; i++) {
            size_t c = (size_t)k * t->nx + i;
            double col[3];
            bool known = (!t->valid || t->valid[c]) && isfinite(g[c]);
            if (known) colour_of(f, g[c], lo, hi, col);
            for (int b = 0; b < px; b++)
                for (int a = 0; a < px; a++)
                    put(rgb + 3 * ((size_t)(k * px + b) * w + i * px + a), known ? col : nodata,
                        known ? 0.55 + 0.45 * shade[c] : 1);
        }
    /* the legend: the name and unit, then the colours with the range's ends */
    static const uint8_t paper[3] = {250, 250, 250}, ink[3] = {20, 20, 20};
    font_fill_rect(rgb, w, h, 0, mh, w, strip, paper);
    font_fill_rect(rgb, w, h, mw, 0, w - mw, mh, paper);
    font_text_draw(rgb, w, h, 4 * s, mh + 3 * s, title, s, ink);
    int y0 = mh + 13 * s, bar = 9 * s;
    if (f == SYL_TERRAIN_ASPECT) {
        static const char *const dirs[] = {"N", "E", "S", "W"};
        for (int d = 0; d < 4; d++) {
            double col[3];
            wheel(90.0 * d, col);
            uint8_t c8[3];
            put(c8, col, 1);
            font_fill_rect(rgb, w, h, 4 * s + d * 24 * s, y0, 9 * s, bar, c8);
            font_text_draw(rgb, w, h, 15 * s + d * 24 * s, y0 + s, dirs[d], s, ink);
        }
        font_text_draw(rgb, w, h, 4 * s + 4 * 24 * s, y0 + s, "GREY: FLAT", s, ink);
    } else {
        number(a, sizeof a, f == SYL_TERRAIN_FLOW ? pow(10, lo) : lo);
        number(b, sizeof b, f == SYL_TERRAIN_FLOW ? pow(10, hi) : hi);
        int left = 4 * s + font_text_width(a, s) + 4 * s, right = w - 8 * s - font_text_width(b, s);
        font_text_draw(rgb, w, h, 4 * s, y0 + s, a, s, ink);
        for (int x = left; x < right; x++) {
            double col[3];
            ramp((double)(x - left) / (right - left > 1 ? right - left - 1 : 1), col);
            uint8_t c8[3];
            put(c8, col, 1);
            font_fill_rect(rgb, w, h, x, y0, 1, bar, c8);
        }
        font_text_draw(rgb, w, h, right + 4 * s, y0 + s, b, s, ink);
    }
    *out = (SylPicture){rgb, w, h};
    return SYL_OK;
}

int syl_terrain_draw_colour_map(const SylTerrain *t, SylTerrainFactor f, const SylMapOptions *o, SylPicture *out) {
    *out = (SylPicture){0};
    if ((unsigned)f >= SYL_TERRAIN_FACTORS || !t->factor[f] || !t->factor[SYL_TERRAIN_SLOPE] ||
        !t->factor[SYL_TERRAIN_ASPECT])
        return SYL_EUSAGE;
    size_t n = (size_t)t->nx * t->nz;
    float *shade = malloc((n ? n : 1) * sizeof *shade);
    if (!shade) return SYL_ELIMIT;
    /* hillshade as gdaldem computes it, the sun in the north-west 45 degrees up */
    const double zen = M_PI / 4, az = 315 * M_PI / 180, deg = M_PI / 180;
    for (size_t i = 0; i < n; i++) {
        double sl = t->factor[SYL_TERRAIN_SLOPE][i] * deg, as = t->factor[SYL_TERRAIN_ASPECT][i];
        double v = as < 0 ? cos(zen) : cos(zen) * cos(sl) + sin(zen) * sin(sl) * cos(az - as * deg);
        shade[i] = (float)(v > 0 ? v : 0);
    }
    int st = draw(t, f, shade, cell_pixels(t, o), out);
    free(shade);
    return st;
}
