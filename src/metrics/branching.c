/* Branching angles: for every lateral branch, the angle between its first segment and the
 * direction its parent axis goes on in. A lateral is a segment whose axis differs from the
 * axis of the node it starts at. The parent's direction is the segment that continues that
 * axis from the node; when the axis ends there, the segment that ends at the node; at a root
 * without a continuation there is none, and the lateral is not counted. Zero-length segments
 * are not counted either. */
#include <math.h>

#include "metrics/metrics_internal.h"

static bool direction(const SylNode *from, const SylNode *to, double d[3]) {
    double len = 0;
    for (int k = 0; k < 3; k++) d[k] = (double)to->pos[k] - from->pos[k], len += d[k] * d[k];
    len = sqrt(len);
    if (!(len > 0)) return false;
    for (int k = 0; k < 3; k++) d[k] /= len;
    return true;
}

double metrics_branching_angle(const MetricsTree *t) {
    const SylNode *nd = t->s->nodes;
    double sum = 0;
    size_t count = 0;
    for (size_t i = 0; i < t->s->nnodes; i++) {
        uint32_t lo = t->first[i], hi = t->first[i + 1];
        bool lateral = false;
        int32_t cont = -1;
        for (uint32_t c = lo; c < hi; c++) {
            if (nd[t->kids[c]].axis == nd[i].axis) {
                if (cont < 0) cont = t->kids[c];
            } else lateral = true;
        }
        if (!lateral) continue;
        double ref[3];
        bool have = cont >= 0 ? direction(&nd[i], &nd[cont], ref)
                              : nd[i].parent >= 0 && direction(&nd[nd[i].parent], &nd[i], ref);
        if (!have) continue;
        for (uint32_t c = lo; c < hi; c++) {
            const SylNode *k = &nd[t->kids[c]];
            double d[3];
            if (k->axis == nd[i].axis || !direction(&nd[i], k, d)) continue;
            double cs = d[0] * ref[0] + d[1] * ref[1] + d[2] * ref[2];
            sum += acos(cs > 1 ? 1 : cs < -1 ? -1 : cs) * (180.0 / M_PI);
            count++;
        }
    }
    return count ? sum / (double)count : NAN;
}
