/* Stems by order and leaves (docs/compare.md): what a user can count on the plant. A stem is
 * an axis of the skeleton with at least one drawn segment; its order is its segments' branch
 * order. A split clone starts an axis of its own, so it counts as a stem of its level (as
 * Arbaro counts stems); a branch that draws nothing is no stem. */
#include <stdlib.h>

#include "metrics/metrics_internal.h"

bool metrics_counts(const SylSkeleton *s, SylMetrics *out) {
    int32_t axes = 0;
    for (size_t i = 0; i < s->nnodes; i++)
        if (s->nodes[i].axis >= axes) axes = s->nodes[i].axis + 1;
    unsigned char *seen = calloc((size_t)axes + 1, 1);
    if (!seen) return false;
    for (size_t i = 0; i < s->nnodes; i++) {
        const SylNode *n = &s->nodes[i];
        if (n->kind != SYL_KIND_INTERNODE || n->axis < 0 || seen[n->axis]) continue;
        seen[n->axis] = 1;
        int k = n->order < SYL_METRICS_MAX_STEM_ORDER ? n->order : SYL_METRICS_MAX_STEM_ORDER;
        out->stems_by_order[k]++;
        if (k + 1 > out->stem_orders) out->stem_orders = k + 1;
    }
    free(seen);
    for (size_t i = 0; i < s->norgans; i++)
        out->leaves += s->organs[i].kind == SYL_KIND_LEAF || s->organs[i].kind == SYL_KIND_NEEDLE;
    return true;
}
