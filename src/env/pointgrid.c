/* The point grid: see pointgrid.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "env/pointgrid.h"

enum { MAX_CELLS = 1 << 24 };

void pgrid_free(PointGrid *g) {
    free(g->start);
    free(g->pts);
    free(g->ids);
    memset(g, 0, sizeof *g);
}

bool pgrid_build(PointGrid *g, float cell, const float *base, size_t stride, size_t n) {
    g->n = 0;
    if (!n) return true;
    if (n > UINT32_MAX - 1) return false;
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            float v = base[i * stride + (size_t)k];
            if (v < lo[k]) lo[k] = v;
            if (v > hi[k]) hi[k] = v;
        }
    /* cells no smaller than asked, and not more of them than MAX_CELLS or 8 per point */
    double limit = fmin((double)MAX_CELLS, fmax(4096.0, 8.0 * (double)n));
    for (;;) {
        g->cell = cell;
        g->inv = 1.0f / cell;
        double total = 1;
        for (int k = 0; k < 3; k++) {
            g->lo[k] = pgrid_coord(g, lo[k]);
            g->dim[k] = pgrid_coord(g, hi[k]) - g->lo[k] + 1;
            total *= g->dim[k];
        }
        if (total <= limit) break;
        cell *= 1.5f;
    }
    size_t cells = (size_t)g->dim[0] * (size_t)g->dim[1] * (size_t)g->dim[2];
    if (cells + 1 > g->cell_cap) {
        free(g->start);
        g->start = malloc((cells + 1) * sizeof *g->start);
        g->cell_cap = g->start ? cells + 1 : 0;
    }
    if (n > g->cap) {
        free(g->pts), free(g->ids);
        g->pts = malloc(n * sizeof *g->pts);
        g->ids = malloc(n * sizeof *g->ids);
        g->cap = g->pts && g->ids ? n : 0;
    }
    uint32_t *slot = malloc(n * sizeof *slot);
    if (!g->start || !g->pts || !g->ids || !slot) {
        free(slot);
        pgrid_free(g);
        return false;
    }
    memset(g->start, 0, (cells + 1) * sizeof *g->start);
    for (size_t i = 0; i < n; i++) {
        const float *p = base + i * stride;
        int x = pgrid_coord(g, p[0]) - g->lo[0], y = pgrid_coord(g, p[1]) - g->lo[1], z = pgrid_coord(g, p[2]) - g->lo[2];
        size_t c = ((size_t)y * (size_t)g->dim[2] + (size_t)z) * (size_t)g->dim[0] + (size_t)x;
        slot[i] = (uint32_t)c;
        g->start[c + 1]++;
    }
    for (size_t c = 0; c < cells; c++) g->start[c + 1] += g->start[c];
    for (size_t i = 0; i < n; i++) { /* start[c] runs ahead as cell c fills, then is set back */
        uint32_t at = g->start[slot[i]]++;
        memcpy(g->pts[at], base + i * stride, sizeof g->pts[at]);
        g->ids[at] = (uint32_t)i;
    }
    for (size_t c = cells; c > 0; c--) g->start[c] = g->start[c - 1];
    g->start[0] = 0;
    free(slot);
    g->n = n;
    return true;
}

bool pgrid_any_within(const PointGrid *g, const float pos[3], float r, uint32_t skip) {
    if (!g->n) return false;
    float r2 = r * r;
    PGRID_FOR_CELLS(g, pos, r, x, y, z) {
        uint32_t first = 0, cnt = pgrid_cell(g, x, y, z, &first);
        for (uint32_t k = first; k < first + cnt; k++) {
            const float *q = g->pts[k];
            float dx = q[0] - pos[0], dy = q[1] - pos[1], dz = q[2] - pos[2];
            if (dx * dx + dy * dy + dz * dz < r2 && g->ids[k] != skip) return true;
        }
    }
    return false;
}
