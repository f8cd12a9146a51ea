/* The crown: the part of the plant at or above its lowest branching node (a node where two
 * or more segments start), or the whole plant when nothing branches. Its points are the
 * skeleton's nodes, organ positions and polygon vertices at or above that height. Width: the
 * largest horizontal distance between two crown points, the diameter of the crown's shadow
 * from straight above (it does not depend on how the plant is turned about the vertical).
 * Depth: the highest crown point minus the crown base. Volume: of the points' convex hull. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "metrics/metrics_internal.h"

bool metrics_crown(const MetricsTree *t, double ground, SylMetrics *out) {
    const SylSkeleton *s = t->s;
    double base = INFINITY;
    for (size_t i = 0; i < s->nnodes; i++)
        if (tree_nkids(t, i) >= 2 && s->nodes[i].pos[1] < base) base = s->nodes[i].pos[1];
    if (base == INFINITY) base = -INFINITY; /* no branching: all of it */
    size_t total = s->nnodes + s->norgans + s->nverts, n = 0;
    float(*p3)[3] = malloc((total ? total : 1) * sizeof *p3);
    double(*p2)[2] = malloc((total ? total : 1) * sizeof *p2);
    bool ok = p3 && p2;
    if (ok) {
        for (size_t i = 0; i < s->nnodes; i++)
            if (s->nodes[i].pos[1] >= base) memcpy(p3[n++], s->nodes[i].pos, sizeof *p3);
        for (size_t i = 0; i < s->norgans; i++)
            if (s->organs[i].pos[1] >= base) memcpy(p3[n++], s->organs[i].pos, sizeof *p3);
        for (size_t i = 0; i < s->nverts; i++)
            if (s->poly_verts[i][1] >= base) memcpy(p3[n++], s->poly_verts[i], sizeof *p3);
        double lo = INFINITY, hi = -INFINITY;
        for (size_t i = 0; i < n; i++) {
            p2[i][0] = p3[i][0];
            p2[i][1] = p3[i][2];
            lo = fmin(lo, p3[i][1]);
            hi = fmax(hi, p3[i][1]);
        }
        if (base == -INFINITY) base = n ? lo : ground;
        out->crown_base = base;
        out->crown_depth = n ? hi - base : 0;
        ok = metrics_diameter_2d((const double(*)[2])p2, n, &out->crown_width) &&
             metrics_hull_volume((const float(*)[3])p3, n, &out->crown_volume);
    }
    free(p3);
    free(p2);
    return ok;
}
