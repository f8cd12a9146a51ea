/* Metrics: figures that describe a plant's form, computed from its skeleton (and, for light
 * interception, its mesh). They are what `sylva compare` prints; docs/compare.md defines each
 * one. Lengths are model units (metres), angles degrees. A figure that does not exist for a
 * plant (the branching angle of an unbranched pole) is NaN. */
#ifndef SYLVA_METRICS_H
#define SYLVA_METRICS_H
#include <stddef.h>
#include <stdio.h>

#include "mesh.h"
#include "skeleton.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { SYL_METRICS_MAX_STRAHLER = 64, SYL_METRICS_MAX_STEM_ORDER = 63 };

typedef struct SylMetrics {
    double height;             /* highest point - ground (the lowest root) */
    double crown_width;        /* largest horizontal distance between two crown points */
    double crown_depth;        /* highest crown point - crown base */
    double crown_volume;       /* of the convex hull of the crown points */
    double internodes;         /* drawn segments */
    double tips;               /* segments that no segment continues */
    double max_order;          /* largest branch order */
    double strahler;           /* Horton-Strahler order of the plant */
    double bifurcation;        /* Horton's ratio (N_1 / N_S)^(1 / (S - 1)); NaN when S < 2 */
    double total_length;       /* sum of the segments' lengths */
    double branching_angle;    /* mean angle of a lateral to its parent's continuation, degrees */
    double box_dimension;      /* box-counting dimension of the segments */
    double light_interception; /* share of sky rays from under the crown that the mesh stops */
    double biomass;            /* sum of radius^2 x length over the segments */
    /* Also of use: */
    double ground;             /* y of the lowest root */
    double crown_base;         /* y of the lowest branching node (the ground when none) */
    double streams[SYL_METRICS_MAX_STRAHLER + 1]; /* streams[i]: Strahler streams of order i */
    /* Counts (`compare --json`): stems_by_order[k] is the number of stems of branch order k
     * (axes with a drawn segment; a split clone is an axis of its own), for k below
     * stem_orders; orders above SYL_METRICS_MAX_STEM_ORDER are counted there. leaves: organs
     * of kind leaf or needle. */
    double stems_by_order[SYL_METRICS_MAX_STEM_ORDER + 1];
    int stem_orders;
    double leaves;
} SylMetrics;

typedef struct SylMetricsOptions {
    const SylMesh *mesh; /* for light interception; NULL: meshed here with default options */
    int directions;      /* sky directions per ray origin; 0: 1024 */
    int grid;            /* ray origins: grid x grid under the crown; 0: 16 */
    int threads;         /* <= 0: all cores; the figures never depend on it */
    FILE *diag;          /* where problems are reported; NULL: nowhere */
    const SylSink *sink; /* or as records to this sink instead (sylva.h); NULL: diag */
} SylMetricsOptions;

/* All the metrics of a skeleton. SYL_EMODEL when a parent does not precede its child,
 * SYL_ELIMIT when out of memory (reported to opt->sink or opt->diag). */
int syl_metrics_compute(const SylSkeleton *s, const SylMetricsOptions *opt, SylMetrics *out);

/* The metrics in the order tools print them, each listed once here for every output. */
typedef struct SylMetricInfo {
    const char *key;         /* for CSV and JSON: "crown_width" */
    const char *label;       /* for people: "crown width" */
    const char *unit;        /* "m", "m^3", "deg" or "" */
    const char *description; /* one line */
    int integer;             /* a count */
    int per_order;           /* one value per Strahler order i = 1 .. S - 1: key_i, "label i:i+1" */
} SylMetricInfo;

extern const SylMetricInfo syl_metrics_info[];
extern const int syl_metrics_count;

/* The value of metric `metric` (an index into syl_metrics_info); order is the Strahler order
 * i of a per-order metric (R_b = N_i / N_(i+1)), ignored by the others. NaN when undefined. */
double syl_metrics_value(const SylMetrics *m, int metric, int order);

/* Plants side by side, as one mesh (what `sylva compare --image` renders): each of the n
 * meshes moved so that its ground (ground[i], a y) is at y = 0 and its middle in z at z = 0,
 * in a row along +x with gaps between their bounds, and a height ruler left of the first: a
 * pole from 0 to the next tick above the tallest plant, ticks at round heights (1, 2 or 5
 * times a power of ten) and their values in seven-segment digits, all as boxes of a material
 * of its own (the last one). Materials that are the same (colour and kind) are shared.
 * names: NULL, or each plant's name, written in the ruler's material in a 5 x 7 font,
 * upright on the ground in front of its plant. NULL when out of memory; free it with
 * syl_mesh_free. */
SylMesh *syl_metrics_build_lineup(const SylMesh *const *meshes, const double *ground, const char *const *names,
                                  int n);

#ifdef __cplusplus
}
#endif

#endif
