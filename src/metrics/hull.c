/* Convex hulls: the volume of a 3D point set's hull and the diameter of a planar set.
 *
 * 3D: Quickhull (Barber, Dobkin and Huhdanpaa 1996) on the points snapped to an integer grid
 * of 2^20 steps across the set's largest extent. Every orientation test is then exact in
 * 128-bit integers: there is no tolerance to tune, the hull never becomes inconsistent, and a
 * coplanar set is recognised exactly (volume 0). Snapping moves a point by at most 5e-7 of
 * the extent. A hull thinner than 1e-5 of the extent (twice its volume over its area) counts
 * as flat, so a planar plant drawn in a tilted plane also has volume 0.
 *
 * 2D: Andrew's monotone chain, then rotating calipers over the antipodal pairs. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "metrics/metrics_internal.h"

__extension__ typedef __int128 i128;

enum { GRID_BITS = 20 };
static const double flat = 1e-5;

typedef struct IP {
    int64_t x[3];
} IP;

typedef struct Face {
    int32_t v[3];  /* counter-clockwise seen from outside */
    int32_t nb[3]; /* the face across edge v[k] -> v[k + 1] */
    int64_t n[3];  /* (v1 - v0) x (v2 - v0): outward */
    i128 d;        /* n . v0 */
    int32_t head;  /* the first point of the outside set, -1: none */
    int32_t far;   /* the point of the set furthest from the plane */
    i128 fard;
    uint32_t stamp; /* the round that found it visible */
    bool alive;
} Face;

typedef struct Hull {
    const IP *p;
    Face *f;
    size_t nf, cap;
    int32_t *next; /* outside sets: linked lists through the points */
} Hull;

static inline i128 side(const Face *f, const IP *p) {
    return (i128)f->n[0] * p->x[0] + (i128)f->n[1] * p->x[1] + (i128)f->n[2] * p->x[2] - f->d;
}

static int32_t new_face(Hull *h, int32_t a, int32_t b, int32_t c) {
    if (h->nf == h->cap) {
        size_t cap = h->cap ? 2 * h->cap : 64;
        Face *f = realloc(h->f, cap * sizeof *f);
        if (!f) return -1;
        h->f = f;
        h->cap = cap;
    }
    Face *f = &h->f[h->nf];
    memset(f, 0, sizeof *f);
    f->v[0] = a, f->v[1] = b, f->v[2] = c;
    const int64_t *p0 = h->p[a].x, *p1 = h->p[b].x, *p2 = h->p[c].x;
    int64_t e1[3], e2[3];
    for (int k = 0; k < 3; k++) e1[k] = p1[k] - p0[k], e2[k] = p2[k] - p0[k];
    f->n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    f->n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    f->n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    f->d = (i128)f->n[0] * p0[0] + (i128)f->n[1] * p0[1] + (i128)f->n[2] * p0[2];
    f->head = f->far = -1;
    f->alive = true;
    return (int32_t)h->nf++;
}

/* Put point i into the outside set of the first face of [lo, hi) it is above; else drop it. */
static void assign(Hull *h, int32_t i, size_t lo, size_t hi) {
    for (size_t j = lo; j < hi; j++) {
        Face *f = &h->f[j];
        i128 s = side(f, &h->p[i]);
        if (s > 0) {
            h->next[i] = f->head;
            f->head = i;
            if (f->far < 0 || s > f->fard) f->far = i, f->fard = s;
            return;
        }
    }
}

/* Link the faces of [lo, hi) whose edges meet in opposite directions. */
static void link_faces(Hull *h, size_t lo, size_t hi) {
    for (size_t a = lo; a < hi; a++)
        for (int k = 0; k < 3; k++) {
            int32_t u = h->f[a].v[k], w = h->f[a].v[(k + 1) % 3];
            for (size_t b = lo; b < hi; b++)
                for (int j = 0; j < 3; j++)
                    if (h->f[b].v[j] == w && h->f[b].v[(j + 1) % 3] == u) h->f[a].nb[k] = (int32_t)b;
        }
}

typedef struct Edge {
    int32_t a, b, out; /* a -> b as in the visible face; out: the face beyond it */
} Edge;

/* Grow the hull until no point is outside. false: out of memory. */
static bool expand(Hull *h, size_t npts) {
    bool ok = false;
    int32_t *stack = NULL, *edge_at = malloc(npts * sizeof *edge_at);
    Edge *edges = NULL, *loop = NULL;
    size_t stack_cap = 0, edge_cap = 0;
    if (!edge_at) return false;
    for (size_t i = 0; i < npts; i++) edge_at[i] = -1;
    uint32_t round = 0;
    for (size_t fi = 0; fi < h->nf; fi++) {
        if (!h->f[fi].alive || h->f[fi].head < 0) continue;
        round++;
        int32_t eye = h->f[fi].far;
        /* The faces the eye sees: a connected set, found from fi. */
        size_t nstack = 0, nvis = 0, nedges = 0;
        if (stack_cap < 64) {
            stack_cap = 64;
            int32_t *s = realloc(stack, stack_cap * sizeof *s);
            if (!s) goto done;
            stack = s;
        }
        stack[nstack++] = (int32_t)fi;
        h->f[fi].stamp = round;
        while (nvis < nstack) { /* the stack doubles as the list of visible faces */
            Face *g = &h->f[stack[nvis++]];
            for (int k = 0; k < 3; k++) {
                int32_t o = g->nb[k];
                Face *of = &h->f[o];
                if (of->stamp == round) continue;
                if (side(of, &h->p[eye]) > 0) {
                    if (nstack == stack_cap) {
                        int32_t *s = realloc(stack, 2 * stack_cap * sizeof *s);
                        if (!s) goto done;
                        stack = s;
                        stack_cap *= 2;
                    }
                    of->stamp = round;
                    stack[nstack++] = o;
                }
            }
        }
        /* The horizon: edges between a visible face and one that is not. */
        for (size_t v = 0; v < nvis; v++) {
            const Face *g = &h->f[stack[v]];
            for (int k = 0; k < 3; k++) {
                if (h->f[g->nb[k]].stamp == round) continue;
                if (nedges == edge_cap) {
                    size_t cap = edge_cap ? 2 * edge_cap : 64;
                    Edge *e = realloc(edges, cap * sizeof *e), *l = realloc(loop, cap * sizeof *l);
                    if (e) edges = e;
                    if (l) loop = l;
                    if (!e || !l) goto done;
                    edge_cap = cap;
                }
                edges[nedges++] = (Edge){g->v[k], g->v[(k + 1) % 3], g->nb[k]};
            }
        }
        /* In order around the eye: each horizon vertex starts exactly one edge. */
        for (size_t e = 0; e < nedges; e++) edge_at[edges[e].a] = (int32_t)e;
        size_t nloop = 0;
        for (int32_t e = 0; nloop < nedges; e = edge_at[edges[e].b]) {
            if (e < 0 || (nloop && e == 0)) break;
            loop[nloop++] = edges[e];
        }
        for (size_t e = 0; e < nedges; e++) edge_at[edges[e].a] = -1;
        if (nloop != nedges || loop[nloop - 1].b != loop[0].a) goto done; /* not with exact tests */
        /* The cone from the horizon to the eye. */
        size_t base = h->nf;
        for (size_t e = 0; e < nloop; e++)
            if (new_face(h, loop[e].a, loop[e].b, eye) < 0) goto done;
        for (size_t e = 0; e < nloop; e++) {
            Face *f = &h->f[base + e];
            f->nb[0] = loop[e].out;
            f->nb[1] = (int32_t)(base + (e + 1) % nloop);
            f->nb[2] = (int32_t)(base + (e + nloop - 1) % nloop);
            Face *o = &h->f[loop[e].out];
            for (int k = 0; k < 3; k++)
                if (o->v[k] == loop[e].b && o->v[(k + 1) % 3] == loop[e].a) o->nb[k] = (int32_t)(base + e);
        }
        /* The points above the faces that go: to the new faces, or inside. */
        for (size_t v = 0; v < nvis; v++) {
            Face *g = &h->f[stack[v]];
            g->alive = false;
            for (int32_t i = g->head, nx; i >= 0; i = nx) {
                nx = h->next[i];
                if (i != eye) assign(h, i, base, h->nf);
            }
            g->head = -1;
        }
    }
    ok = true;
done:
    free(stack);
    free(edge_at);
    free(edges);
    free(loop);
    return ok;
}

bool metrics_hull_volume(const float (*pts)[3], size_t n, double *volume) {
    *volume = 0;
    if (n < 4 || n > INT32_MAX) return true;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            if (pts[i][k] < lo[k]) lo[k] = pts[i][k];
            if (pts[i][k] > hi[k]) hi[k] = pts[i][k];
        }
    double ext = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    if (!(ext > 0) || !isfinite(ext)) return true;
    double scale = (double)(1 << GRID_BITS) / ext;
    Hull h = {0};
    IP *p = malloc(n * sizeof *p);
    h.next = malloc(n * sizeof *h.next);
    bool ok = false;
    if (!p || !h.next) goto done;
    h.p = p;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) p[i].x[k] = llround(((double)pts[i][k] - lo[k]) * scale);

    /* A first tetrahedron: the lowest x, the point furthest from it, the furthest from
     * their line and the furthest from their plane. Any of them missing: flat. */
    size_t i0 = 0, i1 = 0, i2 = 0, i3 = 0;
    for (size_t i = 1; i < n; i++)
        if (p[i].x[0] < p[i0].x[0]) i0 = i;
    int64_t best = 0;
    for (size_t i = 0; i < n; i++) {
        int64_t d = 0;
        for (int k = 0; k < 3; k++) d += (p[i].x[k] - p[i0].x[k]) * (p[i].x[k] - p[i0].x[k]);
        if (d > best) best = d, i1 = i;
    }
    if (!best) goto flat;
    i128 best2 = 0;
    int64_t u[3];
    for (int k = 0; k < 3; k++) u[k] = p[i1].x[k] - p[i0].x[k];
    for (size_t i = 0; i < n; i++) {
        int64_t w[3];
        for (int k = 0; k < 3; k++) w[k] = p[i].x[k] - p[i0].x[k];
        int64_t c[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
        i128 d = (i128)c[0] * c[0] + (i128)c[1] * c[1] + (i128)c[2] * c[2];
        if (d > best2) best2 = d, i2 = i;
    }
    if (!best2) goto flat;
    if (new_face(&h, (int32_t)i0, (int32_t)i1, (int32_t)i2) < 0) goto done;
    i128 best3 = 0;
    for (size_t i = 0; i < n; i++) {
        i128 s = side(&h.f[0], &p[i]);
        if (s < 0) s = -s;
        if (s > best3) best3 = s, i3 = i;
    }
    if (!best3) goto flat;
    h.nf = 0;
    int32_t t[4] = {(int32_t)i0, (int32_t)i1, (int32_t)i2, (int32_t)i3};
    static const int faces[4][4] = {{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 3, 1}, {1, 2, 3, 0}};
    for (int f = 0; f < 4; f++) {
        const int *q = faces[f];
        if (new_face(&h, t[q[0]], t[q[1]], t[q[2]]) < 0) goto done;
        if (side(&h.f[f], &p[t[q[3]]]) > 0) { /* face away from the fourth vertex */
            h.nf--;
            new_face(&h, t[q[0]], t[q[2]], t[q[1]]);
        }
    }
    link_faces(&h, 0, 4);
    for (size_t i = 0; i < n; i++)
        if (i != i0 && i != i1 && i != i2 && i != i3) assign(&h, (int32_t)i, 0, 4);
    if (!expand(&h, n)) goto done;

    /* Volume: tetrahedra from a hull vertex, exactly; area for the flatness test. */
    i128 six = 0;
    double area = 0;
    for (size_t f = 0; f < h.nf; f++) {
        const Face *fc = &h.f[f];
        if (!fc->alive) continue;
        six += fc->d - ((i128)fc->n[0] * p[i0].x[0] + (i128)fc->n[1] * p[i0].x[1] + (i128)fc->n[2] * p[i0].x[2]);
        area += 0.5 * sqrt((double)fc->n[0] * fc->n[0] + (double)fc->n[1] * fc->n[1] + (double)fc->n[2] * fc->n[2]);
    }
    double v = (double)six / 6.0;
    double grid = (double)(1 << GRID_BITS);
    if (area > 0 && 2 * v / area >= flat * grid) *volume = v / (scale * scale * scale);
flat:
    ok = true;
done:
    free(p);
    free(h.next);
    free(h.f);
    return ok;
}

static int cmp_pt(const void *a, const void *b) {
    const double *p = a, *q = b;
    if (p[0] != q[0]) return p[0] < q[0] ? -1 : 1;
    if (p[1] != q[1]) return p[1] < q[1] ? -1 : 1;
    return 0;
}

static inline double cross2(const double *o, const double *a, const double *b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

static inline double dist2(const double *a, const double *b) {
    double dx = a[0] - b[0], dy = a[1] - b[1];
    return dx * dx + dy * dy;
}

bool metrics_diameter_2d(const double (*pts)[2], size_t n, double *diameter) {
    *diameter = 0;
    if (n < 2) return true;
    double(*s)[2] = malloc(n * sizeof *s), (*h)[2] = malloc((2 * n + 1) * sizeof *h);
    if (!s || !h) {
        free(s);
        free(h);
        return false;
    }
    memcpy(s, pts, n * sizeof *s);
    qsort(s, n, sizeof *s, cmp_pt);
    size_t m = 0; /* lower hull, then upper, counter-clockwise, without collinear points */
    for (size_t i = 0; i < n; i++) {
        while (m >= 2 && cross2(h[m - 2], h[m - 1], s[i]) <= 0) m--;
        memcpy(h[m++], s[i], sizeof *h);
    }
    for (size_t i = n - 1, lower = m + 1; i-- > 0;) {
        while (m >= lower && cross2(h[m - 2], h[m - 1], s[i]) <= 0) m--;
        memcpy(h[m++], s[i], sizeof *h);
    }
    m--; /* the last point is the first */
    double best = 0;
    if (m < 3) {
        for (size_t i = 0; i < m; i++)
            for (size_t j = i + 1; j < m + 1 && j < n; j++) best = fmax(best, dist2(h[i], h[j]));
        best = fmax(best, dist2(s[0], s[n - 1]));
    } else {
        size_t j = 1;
        for (size_t i = 0; i < m; i++) {
            size_t ni = (i + 1) % m;
            while (fabs(cross2(h[i], h[ni], h[(j + 1) % m])) > fabs(cross2(h[i], h[ni], h[j]))) j = (j + 1) % m;
            best = fmax(best, fmax(dist2(h[i], h[j]), dist2(h[ni], h[j])));
        }
    }
    *diameter = sqrt(best);
    free(s);
    free(h);
    return true;
}
