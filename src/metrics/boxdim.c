/* Box-counting dimension of the segments: cover the cube of side L (the largest extent of
 * the segments' bounding box, from its lowest corner) with boxes of side L / 2^k for k from
 * BOX_LEVEL_MIN to BOX_LEVEL_MAX, count the boxes N_k that a segment passes through, and fit
 * log2 N_k = D k + c by least squares: D is the dimension. A segment is sampled at both ends
 * and at steps of at most a quarter of a box, so a box it merely grazes may be missed. A
 * straight segment gives 1 (exactly, when it is parallel to an axis); a tree that fills an
 * area or a volume more and more densely gives up to 2 or 3 over these scales. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "metrics/metrics_internal.h"

bool metrics_box_dimension(const SylSkeleton *s, double *dimension) {
    *dimension = NAN;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    size_t segments = 0;
    for (size_t i = 0; i < s->nnodes; i++) {
        int32_t p = s->nodes[i].parent;
        if (p < 0) continue;
        segments++;
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], fmin(s->nodes[i].pos[k], s->nodes[p].pos[k]));
            hi[k] = fmax(hi[k], fmax(s->nodes[i].pos[k], s->nodes[p].pos[k]));
        }
    }
    double ext = segments ? fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2])) : 0;
    if (!(ext > 0) || !isfinite(ext)) return true;
    size_t words = ((size_t)1 << (3 * BOX_LEVEL_MAX)) / 64;
    uint64_t *bits = malloc(words * sizeof *bits);
    if (!bits) return false;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int levels = 0;
    for (int level = BOX_LEVEL_MIN; level <= BOX_LEVEL_MAX; level++) {
        int64_t g = (int64_t)1 << level;
        double box = ext / (double)g;
        memset(bits, 0, words * sizeof *bits);
        for (size_t i = 0; i < s->nnodes; i++) {
            int32_t p = s->nodes[i].parent;
            if (p < 0) continue;
            const float *a = s->nodes[p].pos, *b = s->nodes[i].pos;
            double d[3] = {(double)b[0] - a[0], (double)b[1] - a[1], (double)b[2] - a[2]};
            double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            double steps = ceil(len / (0.25 * box));
            size_t m = steps < 1 ? 1 : (size_t)steps;
            for (size_t j = 0; j <= m; j++) {
                double t = (double)j / (double)m;
                size_t cell = 0;
                for (int k = 0; k < 3; k++) {
                    double c = floor(((double)a[k] + t * d[k] - lo[k]) / box);
                    int64_t ci = c < 0 ? 0 : c >= (double)g ? g - 1 : (int64_t)c;
                    cell = cell << level | (size_t)ci;
                }
                bits[cell / 64] |= (uint64_t)1 << (cell % 64);
            }
        }
        size_t count = 0;
        for (size_t w = 0; w < words; w++) count += (size_t)__builtin_popcountll(bits[w]);
        double x = level, y = log2((double)count);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
        levels++;
    }
    free(bits);
    double n = levels;
    *dimension = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    return true;
}
