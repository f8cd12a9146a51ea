/* Pruning: a stem that leaves the envelope (Weber & Penn's, or a closed mesh's inside) is shortened until it fits (grown again in test
 * mode from the same random stream, so it keeps its shape), then lengthened back by
 * 1 - PruneRatio of what was cut. */
#include <string.h>

#include "weber/internal.h"

bool weber_inside(const WeberGen *g, const double p[3]) {
    const WeberParams *w = &g->w;
    if (g->envelope) { /* the mesh's inside instead of Weber & Penn's envelope */
        float q[3] = {(float)p[0], (float)p[2], (float)-p[1]};
        return obstacles_inside(&g->envelope->obs, q);
    }
    double r = sqrt(p[0] * p[0] + p[1] * p[1]);
    double ratio = (g->scale_tree - p[2]) / (g->scale_tree * (1 - w->BaseSize));
    return r / g->scale_tree < w->PruneWidth * weber_shape_ratio(w, 8, ratio);
}

void weber_prune(WeberGen *g, WStem *st, int bad) {
    double split_err[10], orig = st->length, corr = st->split_corr;
    memcpy(split_err, g->split_err, sizeof split_err); /* test growth leaves the counts alone */
    if (bad < 0) bad = weber_trace(g, st, 0, st->start, true, NULL);
    while (bad >= 0 && st->length > 0.001 * g->scale_tree) {
        st->split_corr = corr;
        memcpy(g->split_err, split_err, sizeof split_err);
        double shortest = st->length / 2, longest = st->length - orig / 15;
        double len = st->seglen * bad;
        if (len < shortest) len = shortest;
        if (len > longest) len = longest;
        st->length = len;
        st->seglen = len / st->nseg;
        st->base_radius = weber_base_radius(g, st);
        if (st->length > WEBER_MIN_LEN) bad = weber_trace(g, st, 0, st->start, true, NULL);
    }
    st->length = orig - (orig - st->length) * (g->w.PruneRatio > 0 ? g->w.PruneRatio : 1);
    st->seglen = st->length / st->nseg;
    st->base_radius = weber_base_radius(g, st);
    st->split_corr = corr;
    memcpy(g->split_err, split_err, sizeof split_err);
}
