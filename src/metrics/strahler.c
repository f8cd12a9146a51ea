/* Horton-Strahler orders of a skeleton's segments (Strahler 1952), and its streams.
 *
 * A segment that no segment continues has order 1. Otherwise let m be the highest order
 * among the segments that start at its end: the segment has order m + 1 when two or more of
 * them have order m, else m. A chain of nodes with one child each therefore keeps one order,
 * as if it were collapsed into one branch segment. The plant's order is the highest of its
 * segments (a root is a point, not a segment: two branches of order k leaving the root give
 * a plant of order k). A stream is a maximal path of segments of one order: a segment starts
 * a stream when it leaves a root or when its parent segment has another order. */
#include "metrics/metrics_internal.h"

int metrics_strahler(const MetricsTree *t, int *order, double streams[SYL_METRICS_MAX_STRAHLER + 1]) {
    const SylSkeleton *s = t->s;
    for (int k = 0; k <= SYL_METRICS_MAX_STRAHLER; k++) streams[k] = 0;
    int top = 0;
    for (size_t i = s->nnodes; i-- > 0;) { /* children come after their parents */
        order[i] = 0;
        if (s->nodes[i].parent < 0) continue;
        int m = 0, count = 0;
        for (uint32_t c = t->first[i]; c < t->first[i + 1]; c++) {
            int o = order[t->kids[c]];
            if (o > m) m = o, count = 1;
            else if (o == m) count++;
        }
        order[i] = m == 0 ? 1 : count >= 2 && m < SYL_METRICS_MAX_STRAHLER ? m + 1 : m;
        if (order[i] > top) top = order[i];
    }
    for (size_t i = 0; i < s->nnodes; i++) {
        int32_t p = s->nodes[i].parent;
        if (p >= 0 && (s->nodes[p].parent < 0 || order[p] != order[i])) streams[order[i]]++;
    }
    return top;
}
