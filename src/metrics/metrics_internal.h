/* Inside the metrics: the pieces syl_metrics_compute puts together, each in a file of its own.
 * Not part of the public API. */
#ifndef SYL_METRICS_INTERNAL_H
#define SYL_METRICS_INTERNAL_H
#include <stdbool.h>
#include <stdint.h>

#include "sylva/metrics.h"

/* The branching structure: the children of node i are kids[first[i] .. first[i + 1]), in
 * increasing order. Parents precede their children. */
typedef struct MetricsTree {
    const SylSkeleton *s;
    uint32_t *first;
    int32_t *kids;
} MetricsTree;

static inline uint32_t tree_nkids(const MetricsTree *t, size_t i) { return t->first[i + 1] - t->first[i]; }

/* Horton-Strahler orders (strahler.c): order[i] of the segment ending at node i (0 for a
 * root), streams[k] the streams of order k; returns the plant's order (0: no segment). */
int metrics_strahler(const MetricsTree *t, int *order, double streams[SYL_METRICS_MAX_STRAHLER + 1]);

/* Stems by order and leaves (counts.c). false: out of memory. */
bool metrics_counts(const SylSkeleton *s, SylMetrics *out);

/* The mean angle, in degrees, between each lateral branch's first segment and its parent's
 * continuation (branching.c); NaN when there is none. */
double metrics_branching_angle(const MetricsTree *t);

/* Volume of the convex hull of n points (hull.c); 0 for a flat or smaller set. false when
 * out of memory. */
bool metrics_hull_volume(const float (*pts)[3], size_t n, double *volume);
/* The largest distance between two of n points of the plane (hull.c). false: out of memory. */
bool metrics_diameter_2d(const double (*pts)[2], size_t n, double *diameter);

/* Crown base, width, depth and volume (crown.c), given the ground. false: out of memory. */
bool metrics_crown(const MetricsTree *t, double ground, SylMetrics *out);

/* The box-counting dimension of the segments (boxdim.c); NaN with no extent. false: out of
 * memory. */
enum { BOX_LEVEL_MIN = 2, BOX_LEVEL_MAX = 7 }; /* boxes of extent / 2^k, k from MIN to MAX */
bool metrics_box_dimension(const SylSkeleton *s, double *dimension);

/* The share of sky rays that the mesh stops (light.c): rays from a grid of points on the
 * plane y = base (the crown base) over the footprint of the mesh above it. */
int metrics_light(const SylMesh *m, double base, const SylMetricsOptions *opt, double *fraction);

#endif
