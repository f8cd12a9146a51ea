/* The named leaf outlines (leafoutline.h): Arbaro's disc of n triangles (n + 2 points of the
 * ellipse through base and tip), its square, and Sylva's folded palm leaflet. */
#include "util/leafoutline.h"

#include <math.h>

#define PALM_FOLD 0.4363323f /* 25 degrees: each half of a palm leaflet raised about the midrib */

/* The palm leaflet's half, base to tip (s, |t|): lanceolate, widest at 0.3 of its length. */
static const float palm_half[5][2] = {{0, 0}, {0.1f, 0.7f}, {0.3f, 1}, {0.6f, 0.7f}, {1, 0}};

bool leaf_outline_valid(int kind, int tris) {
    return kind == LEAF_OUTLINE_SQUARE || kind == LEAF_OUTLINE_PALM ||
           (kind == LEAF_OUTLINE_OVAL && tris >= 1 && tris <= LEAF_OUTLINE_MAX_TRIS);
}

int leaf_outline_panels(int kind, int tris, LeafPanel *out) {
    if (!leaf_outline_valid(kind, tris)) return 0;
    switch (kind) {
    case LEAF_OUTLINE_SQUARE: { /* the leaf's whole rectangle */
        static const float c[4][2] = {{0, -1}, {1, -1}, {1, 1}, {0, 1}};
        out[0] = (LeafPanel){.n = 4, .fold = 0};
        for (int i = 0; i < 4; i++) out[0].st[i][0] = c[i][0], out[0].st[i][1] = c[i][1];
        return 1;
    }
    case LEAF_OUTLINE_PALM:
        for (int side = 0; side < 2; side++) { /* side 0: t < 0, base to tip; side 1: t > 0, tip to base */
            out[side] = (LeafPanel){.n = 5, .fold = side ? PALM_FOLD : -PALM_FOLD};
            for (int i = 0; i < 5; i++) {
                const float *p = palm_half[side ? 4 - i : i];
                out[side].st[i][0] = p[0], out[side].st[i][1] = side ? p[1] : -p[1];
            }
        }
        return 2;
    default: { /* the oval: from the base through t < 0, the tip and t > 0 */
        int m = tris + 2;
        out[0] = (LeafPanel){.n = m, .fold = 0};
        for (int i = 0; i < m; i++) {
            float a = 3.14159265358979f + 6.28318530718f * (float)i / (float)m;
            out[0].st[i][0] = 0.5f + 0.5f * cosf(a), out[0].st[i][1] = sinf(a);
        }
        return 1;
    }
    }
}

int leaf_outline_tris(int kind, int tris) {
    LeafPanel p[LEAF_OUTLINE_MAX_PANELS];
    int np = leaf_outline_panels(kind, tris, p), t = 0;
    for (int k = 0; k < np; k++) t += p[k].n - 2;
    return t;
}

double leaf_outline_area(int kind, int tris) {
    switch (kind) {
    case LEAF_OUTLINE_SQUARE: return 1;
    case LEAF_OUTLINE_PALM: { /* two halves, each its trapezoids in (s, t) times 1/2 (t = 1 is
                                * half the width) */
        double a = 0;
        for (int i = 0; i + 1 < 5; i++)
            a += (palm_half[i + 1][0] - palm_half[i][0]) * (palm_half[i][1] + palm_half[i + 1][1]) / 2;
        return a;
    }
    default: { /* a regular m-gon inscribed in the unit circle, squeezed to semi-axes 1/2 */
        int m = tris + 2;
        return leaf_outline_valid(kind, tris) ? 0.125 * m * sin(2 * M_PI / m) : 0;
    }
    }
}

/* Crossing number of a closed polygon. */
static bool in_polygon(const LeafPanel *p, float s, float t) {
    bool in = false;
    for (int i = 0, j = p->n - 1; i < p->n; j = i++) {
        const float *a = p->st[i], *b = p->st[j];
        if ((a[1] > t) != (b[1] > t) && s < a[0] + (t - a[1]) * (b[0] - a[0]) / (b[1] - a[1])) in = !in;
    }
    return in;
}

bool leaf_outline_inside(int kind, int tris, float s, float t) {
    LeafPanel p[LEAF_OUTLINE_MAX_PANELS];
    int np = leaf_outline_panels(kind, tris, p);
    for (int k = 0; k < np; k++)
        if (in_polygon(&p[k], s, t)) return true;
    return false;
}
