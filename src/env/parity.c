/* The inside test of a closed mesh without a BVH: see parity.h. */
#include "env/parity.h"
#include "util/coord.h"
#include "util/pages.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* obstacles_inside's direction: seldom along an edge of a modelled mesh */
static const double dir[3] = {0.5773503f, 0.5925557f, 0.5619427f};
/* two unit vectors across it (fixed once: every vertex and point is projected the same way) */
static void basis(double u[3], double w[3]) {
    double n = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]), d[3] = {dir[0] / n, dir[1] / n, dir[2] / n};
    double a[3] = {d[1], -d[0], 0}; /* across d, in the xy plane */
    double la = sqrt(a[0] * a[0] + a[1] * a[1]);
    for (int j = 0; j < 3; j++) u[j] = a[j] / la;
    w[0] = d[1] * u[2] - d[2] * u[1], w[1] = d[2] * u[0] - d[0] * u[2], w[2] = d[0] * u[1] - d[1] * u[0];
}

static void project(const double u[3], const double w[3], const float p[3], double out[2]) {
    out[0] = u[0] * p[0] + u[1] * p[1] + u[2] * p[2];
    out[1] = w[0] * p[0] + w[1] * p[1] + w[2] * p[2];
}

static int cell_of(const ParityGrid *pg, double x, int axis) {
    double c = floor((x - pg->lo[axis]) * pg->inv);
    return !(c > 0) ? 0 : c >= pg->g ? pg->g - 1 : (int)c; /* NaN: an empty grid's one cell */
}

/* a before b in one fixed order of the plane's points: an edge's sign is computed from its
 * first end whichever triangle asks, so the two triangles of an edge see the same number */
static bool before(const double a[2], const double b[2]) { return a[0] < b[0] || (a[0] == b[0] && a[1] < b[1]); }

/* Which side of the edge a -> b is q on (twice the signed area), and whether a -> b runs in
 * the fixed order. */
static inline double side_of(const double a[2], const double b[2], const double q[2], bool *forward) {
    *forward = before(a, b);
    const double *s = *forward ? a : b, *e = *forward ? b : a;
    double x = (e[0] - s[0]) * (q[1] - s[1]) - (e[1] - s[1]) * (q[0] - s[0]);
    return *forward ? x : -x;
}

/* A triangle's normal, its dot with the ray, and which way its shadow turns. */
static struct ParityTri tri_of(const ParityGrid *pg, size_t t) {
    const uint32_t *k = pg->tri + 3 * t;
    struct ParityTri r = {{0}, 0, 0};
    bool fa;
    double area = side_of(pg->p[k[0]], pg->p[k[1]], pg->p[k[2]], &fa);
    if (area == 0) return r; /* seen edge-on: the ray runs along its plane */
    r.turn = area < 0 ? -1 : 1;
    const double *v0 = pg->v[k[0]], *v1 = pg->v[k[1]], *v2 = pg->v[k[2]];
    double e[3], g[3];
    for (int j = 0; j < 3; j++) e[j] = v1[j] - v0[j], g[j] = v2[j] - v0[j];
    r.n[0] = e[1] * g[2] - e[2] * g[1], r.n[1] = e[2] * g[0] - e[0] * g[2], r.n[2] = e[0] * g[1] - e[1] * g[0];
    r.den = r.n[0] * dir[0] + r.n[1] * dir[1] + r.n[2] * dir[2];
    return r;
}

bool parity_build(ParityGrid *pg, const float *v, size_t nv, const uint32_t *tri, size_t nt) {
    memset(pg, 0, sizeof *pg);
    pg->tri = tri;
    /* about two cells a triangle's shadow on each side: a handful of triangles per cell */
    double g = ceil(1.5 * sqrt((double)nt));
    int gmax = g > 1024 ? 1024 : g < 1 ? 1 : (int)g;
    /* the vertices, triangles and cell starts in one block (util/pages.h: one fault where it
     * pays, not one per 4 KB); each part a multiple of 8 bytes */
    size_t n1 = nv ? nv : 1, bp = n1 * sizeof *pg->p, bv = n1 * sizeof *pg->v, bt = (nt ? nt : 1) * sizeof *pg->t;
    char *block = pages_owned(bp + bv + bt + ((size_t)gmax * gmax + 2) * sizeof *pg->start, PAGES_OWNED_SCRATCH);
    if (!block) return false;
    pg->p = (double(*)[2])block, pg->v = (double(*)[3])(block + bp), pg->t = (struct ParityTri *)(block + bp + bv);
    pg->start = (uint32_t *)(block + bp + bv + bt);
    double hi[2] = {-INFINITY, -INFINITY};
    basis(pg->u, pg->w);
    pg->lo[0] = pg->lo[1] = INFINITY;
    for (size_t i = 0; i < nv; i++) {
        project(pg->u, pg->w, v + 3 * i, pg->p[i]);
        for (int k = 0; k < 3; k++) pg->v[i][k] = v[3 * i + k];
        for (int k = 0; k < 2; k++) pg->lo[k] = fmin(pg->lo[k], pg->p[i][k]), hi[k] = fmax(hi[k], pg->p[i][k]);
    }
    double side = fmax(hi[0] - pg->lo[0], hi[1] - pg->lo[1]);
    pg->g = nv == 0 || !(side > 0) ? 1 : gmax;
    pg->inv = side > 0 ? pg->g / side : 0;
    size_t cells = (size_t)pg->g * pg->g;
    memset(pg->start, 0, (cells + 1) * sizeof *pg->start);
    for (size_t t = 0; t < nt; t++) pg->t[t] = tri_of(pg, t);
    /* two passes: count each cell's triangles, then place them (cells by prefix sums) */
    size_t total = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t t = 0; t < nt; t++) {
            const double *a = pg->p[tri[3 * t]], *b = pg->p[tri[3 * t + 1]], *c = pg->p[tri[3 * t + 2]];
            int x0 = cell_of(pg, fmin(a[0], fmin(b[0], c[0])), 0), x1 = cell_of(pg, fmax(a[0], fmax(b[0], c[0])), 0);
            int y0 = cell_of(pg, fmin(a[1], fmin(b[1], c[1])), 1), y1 = cell_of(pg, fmax(a[1], fmax(b[1], c[1])), 1);
            for (int y = y0; y <= y1; y++)
                for (int x = x0; x <= x1; x++) {
                    size_t cell = (size_t)y * pg->g + x;
                    if (pass == 0) pg->start[cell + 1]++, total++;
                    else pg->idx[pg->start[cell]++] = (uint32_t)t;
                }
        }
        if (pass == 0) {
            if (total > UINT32_MAX || !(pg->idx = malloc((total ? total : 1) * sizeof *pg->idx)))
                return parity_free(pg), false;
            for (size_t c = 0; c < cells; c++) pg->start[c + 1] += pg->start[c];
        } else { /* the fill moved each start to the next cell's: back one cell */
            memmove(pg->start + 1, pg->start, cells * sizeof *pg->start);
            pg->start[0] = 0;
        }
    }
    return true;
}

/* Does the ray from p (projected: q) cross triangle t beyond its start? The shadow test is
 * watertight: a point on an edge two triangles share belongs to one of them when the ray
 * passes through the surface there, to both (or neither) when it grazes it. */
static inline bool crosses(const ParityGrid *pg, size_t t, const double q[2], const float p[3]) {
    const struct ParityTri *tr = &pg->t[t];
    if (!tr->turn || tr->den == 0) return false;
    const uint32_t *k = pg->tri + 3 * t;
    const double *a = pg->p[k[0]], *b = pg->p[k[1]], *c = pg->p[k[2]];
    bool f0, f1, f2, neg = tr->turn < 0;
    double e0 = side_of(a, b, q, &f0), e1 = side_of(b, c, q, &f1), e2 = side_of(c, a, q, &f2);
    if (neg) e0 = -e0, e1 = -e1, e2 = -e2;
    /* an edge owns its points when it runs in the fixed order on a triangle turned one way,
     * against it on one turned the other way */
    if (!(e0 > 0 || (e0 == 0 && f0 != neg)) || !(e1 > 0 || (e1 == 0 && f1 != neg)) ||
        !(e2 > 0 || (e2 == 0 && f2 != neg)))
        return false;
    const double *v0 = pg->v[k[0]], *n = tr->n;
    double num = n[0] * (v0[0] - p[0]) + n[1] * (v0[1] - p[1]) + n[2] * (v0[2] - p[2]);
    return num / tr->den >= 0;
}

bool parity_inside(const ParityGrid *pg, const float p[3]) {
    if (!pg->start || !coord_ok3(p)) return false;
    double q[2];
    project(pg->u, pg->w, p, q);
    size_t cell = (size_t)cell_of(pg, q[1], 1) * pg->g + cell_of(pg, q[0], 0);
    int crossings = 0;
    for (uint32_t i = pg->start[cell]; i < pg->start[cell + 1]; i++) crossings += crosses(pg, pg->idx[i], q, p);
    return crossings % 2 == 1;
}

void parity_free(ParityGrid *pg) {
    free(pg->p); /* the block of p, v, t and start */
    free(pg->idx);
    memset(pg, 0, sizeof *pg);
}
