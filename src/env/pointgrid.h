/* A uniform grid of points: cells of a given edge over the points' bounding box, filled in
 * linear time (a counting sort by cell), so finding the points near a place costs a few
 * array lookups whatever the number of points. When the box would need too many cells the
 * cells are made larger (queries stay right, only slower). Points of one cell keep their
 * input order, so every walk over the grid is deterministic. */
#ifndef SYL_ENV_POINTGRID_H
#define SYL_ENV_POINTGRID_H
#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct PointGrid {
    float cell, inv;
    size_t n;
    int lo[3], dim[3];     /* cell coordinates of the first cell; cells per axis */
    uint32_t *start;       /* per cell, and one more: its points are start[c] .. start[c+1]-1 */
    float (*pts)[3];       /* positions sorted by cell */
    uint32_t *ids;         /* the caller's index of each sorted point */
    size_t cap, cell_cap;
} PointGrid;

/* Build from n points (pos of point i at base + i * stride floats); ids[i] = i. Reuses the
 * grid's memory. False when out of memory (the grid is then empty). */
bool pgrid_build(PointGrid *g, float cell, const float *base, size_t stride, size_t n);
void pgrid_free(PointGrid *g);

static inline int pgrid_coord(const PointGrid *g, float v) { /* floor, clamped */
    float f = v * g->inv;
    if (!(f > -1e6f)) return -1000000;
    if (f > 1e6f) return 1000000;
    int i = (int)f;
    return i - (f < (float)i);
}
/* The points of cell (x, y, z): *first and the count returned. */
static inline uint32_t pgrid_cell(const PointGrid *g, int x, int y, int z, uint32_t *first) {
    x -= g->lo[0], y -= g->lo[1], z -= g->lo[2];
    if (!g->n || x < 0 || y < 0 || z < 0 || x >= g->dim[0] || y >= g->dim[1] || z >= g->dim[2]) return 0;
    size_t c = ((size_t)y * (size_t)g->dim[2] + (size_t)z) * (size_t)g->dim[0] + (size_t)x;
    *first = g->start[c];
    return g->start[c + 1] - g->start[c];
}

/* Visit the cells overlapping the box pos ± r (clipped to the grid): a loop helper. */
#define PGRID_FOR_CELLS(g, pos, r, X, Y, Z)                                                         \
    for (int X = pgrid_lo((g), 0, (pos)[0] - (r)), X##_hi = pgrid_hi((g), 0, (pos)[0] + (r)); X <= X##_hi; X++) \
        for (int Y = pgrid_lo((g), 1, (pos)[1] - (r)), Y##_hi = pgrid_hi((g), 1, (pos)[1] + (r)); Y <= Y##_hi; Y++) \
            for (int Z = pgrid_lo((g), 2, (pos)[2] - (r)), Z##_hi = pgrid_hi((g), 2, (pos)[2] + (r)); Z <= Z##_hi; Z++)
static inline int pgrid_lo(const PointGrid *g, int k, float v) {
    int c = pgrid_coord(g, v);
    return c < g->lo[k] ? g->lo[k] : c;
}
static inline int pgrid_hi(const PointGrid *g, int k, float v) {
    int c = pgrid_coord(g, v), top = g->lo[k] + g->dim[k] - 1;
    return c > top ? top : c;
}

/* Is any point within r of pos? Points with id == skip do not count. */
bool pgrid_any_within(const PointGrid *g, const float pos[3], float r, uint32_t skip);

#endif
