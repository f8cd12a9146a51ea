/* A stem's length from its parent's, its base radius, and its radius along its length:
 * taper (cone, rounded end, periodic beads), the trunk's flare and its 0Scale (the paper:
 * 0Scale ± 0ScaleV per trunk; Arbaro's 0ScaleV jitters the mesh instead, write.c). */
#include "weber/internal.h"

double weber_stem_length(WeberGen *g, const WStem *s, Rng *self) {
    const WeberParams *w = &g->w;
    if (s->level == 0) {
        double v = s->u_length >= 0 ? w->LengthV[0] * (2 * s->u_length - 1) : weber_var(self, w->LengthV[0]);
        return (w->Length[0] + v) * g->scale_tree;
    }
    const WStem *p = &g->stems[s->parent];
    if (w->SaplingLaw) return weber_sapling_length(g, p, s);
    if (s->level == 1) {
        double base = w->BaseSize * g->scale_tree;
        double ratio = (p->length - s->offset) / (p->length - base);
        return p->length * p->lcm * weber_shape_ratio(w, (int)w->Shape, ratio);
    }
    return p->lcm * (p->length - 0.6 * s->offset);
}

double weber_base_radius(const WeberGen *g, const WStem *s) {
    if (s->level == 0) {
        double r = s->length * g->w.Ratio;
        if (g->w.convention != WEBER_PAPER) return r;
        Rng own = weber_rng(g, s->key, WRNG_SCALE0); /* a stream of its own: no other draw moves */
        return r * (g->w.Scale0 + weber_var(&own, g->w.Scale0V));
    }
    const WStem *p = &g->stems[s->parent];
    double most = weber_radius(g, p, s->offset);
    double q = s->length / p->length, rp = g->w.RatioPower;
    double r = p->base_radius * (rp == 2 ? q * q : pow(q, rp)); /* (the common power without its call) */
    return r < most ? r : most;
}

double weber_radius(const WeberGen *g, const WStem *s, double h) {
    const WeberParams *w = &g->w;
    double Z = s->length > 0 ? h / s->length : 1;
    if (Z > 1) Z = 1;
    double taper = w->Taper[weber_lv(s->level)];
    double unit = taper <= 1 ? taper : taper <= 2 ? 2 - taper : 0;
    double r = s->base_radius * (1 - unit * Z);
    if (taper > 1) { /* a rounded end, or beads */
        double Z2 = (1 - Z) * s->length;
        double depth = taper < 2 || Z2 < r ? 1 : taper - 2;
        double Z3 = taper < 2 ? Z2 : fabs(Z2 - 2 * r * (int)(Z2 / 2 / r + 0.5));
        if (taper > 2 || Z3 < r) {
            double q = r * r - (Z3 - r) * (Z3 - r);
            r = (1 - depth) * r + depth * sqrt(q > 0 ? q : 0);
        }
    }
    if (s->level == 0) {
        if (w->Flare != 0) {
            double y = 1 - 8 * Z;
            if (y < 0) y = 0;
            r *= 1 + w->Flare * (pow(100, y) - 1) / 100.0;
        }
        if (w->convention == WEBER_ARBARO) r *= w->Scale0;
    }
    return r;
}
