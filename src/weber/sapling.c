/* Blender Sapling's laws of counting (SaplingLaw 1, which Sapling's presets set; docs/arbaro.md
 * "Sapling's presets"): how many children a stem gets, when a stem splits, and the stem each
 * stem sprouts at its tip. Facts of Sapling's add-on (GPL) written anew. */
#include <math.h>

#include "weber/internal.h"

/* The longest a stem of st's level can be: its trunk's length times each level's Length. */
double weber_sapling_most(const WeberGen *g, const WStem *st) {
    const WStem *t = st;
    while (t->level > 0 && t->parent >= 0) t = &g->stems[t->parent];
    double most = t->length;
    for (int l = 1; l <= st->level; l++) most *= g->w.Length[weber_lv(l)];
    return most;
}

/* Splits at the end of segment seg: at most one, by odds of SegSplits × 1.33 after a segment
 * that did not split and SegSplits² after one that did; a branch's odds scale with its length
 * (SaplingSplitByLen). The trunk splits 0BaseSplits times after its first segment, never below
 * SaplingSplitHeight, and always once at the first segment above it. */
int weber_sapling_splits(WeberGen *g, const WStem *st, int seg, Rng *r) {
    const WeberParams *w = &g->w;
    int k = seg + 1; /* Sapling counts the segment the split starts */
    double s = w->SegSplits[weber_lv(st->level)];
    double odds = st->split_last ? s * s : s * 1.33;
    if (st->level == 0) {
        if (k == 1) return (int)w->BaseSplits;
        double h = (st->nseg - 1) * w->SaplingSplitHeight;
        if (k < h) return 0;
        if (k == (int)h + 1 && odds > 0) return 1;
    } else if (w->SaplingSplitByLen) {
        double most = weber_sapling_most(g, st);
        if (most > 0) odds *= st->length / most;
    }
    return rng_unit(r) < odds;
}

/* Sapling's shapes of a child's length along its parent (r: 1 at the parent's bare base, 0 at
 * its tip); 8 is its custom shape of four values, 10 grows towards the tip. */
double weber_sapling_shape(const WeberParams *w, int shape, double r) {
    switch (shape) {
    case 0: return 0.05 + 0.95 * r;
    case 5: return r <= 0.7 ? 0.05 + 0.95 * r / 0.7 : 0.05 + 0.95 * (1 - r) / 0.3;
    case 8: {
        double t = 1 - r, at = w->SaplingCustomPeak, pos;
        if (t >= 1) return w->SaplingCustomTip;
        if (t >= at) {
            pos = (t - at) / (1 - at);
            return pos * pos * (w->SaplingCustomTip - w->SaplingCustomMid) + w->SaplingCustomMid;
        }
        pos = t / at;
        pos = 1 - (1 - pos) * (1 - pos);
        return pos * (w->SaplingCustomMid - w->SaplingCustomBase) + w->SaplingCustomBase;
    }
    case 10: return 0.5 + 0.5 * (1 - r);
    default: return weber_shape_ratio(w, shape, r); /* 1-4, 6, 7: Weber & Penn's */
    }
}

/* A branch's length by Sapling: its parent's length × its level's Length (with LengthV) × the
 * shape (Shape for level 1, SaplingShapeS below) at its place above the parent's bare base. */
double weber_sapling_length(const WeberGen *g, const WStem *p, const WStem *s) {
    const WeberParams *w = &g->w;
    double b = fmin(0.999, w->BaseSize * pow(w->SaplingBaseSizeS, p->level)) * p->length;
    double r = p->length - b > 0 ? (p->length - s->offset) / (p->length - b) : 0;
    r = r < 0 ? 0 : r > 1 ? 1 : r;
    return p->length * p->lcm * weber_sapling_shape(w, s->level == 1 ? (int)w->Shape : (int)w->SaplingShapeS, r);
}

/* A branch's children by Sapling: sap_main even places along it, t = 1/main … 1; the lowest
 * int(b (main + 1)) dropped (b its level's bare base), and the last, t = 1, left to its tip's
 * stem; each of its clones takes the places at or above where it split off. */
void weber_sapling_children(WeberGen *g, int id, WStem *st, const WSeg *segs, Rng *kids) {
    int m = st->sap_main;
    if (m <= 0) return;
    double b = fmin(0.999, g->w.BaseSize * pow(g->w.SaplingBaseSizeS, st->level));
    for (int a = (int)(b * (m + 1)); a < m - 1 && !g->failed; a++) {
        double at = (a + 1.0) / m * st->nseg;
        int seg = (int)at;
        if (seg < st->first_seg || seg >= st->nseg) continue;
        double where = at - seg;
        WStem c = {0};
        c.level = st->level + 1;
        c.parent = id;
        c.offset = at * st->seglen;
        c.key = weber_key(st->key, 1, (uint64_t)seg << 20 | (uint64_t)a);
        c.start = weber_child_direction(g, st, segs[seg].f, c.offset, c.level, kids);
        for (int i = 0; i < 3; i++) c.start.t[i] = segs[seg].f.t[i] + segs[seg].f.z[i] * where * st->seglen;
        weber_make_stem(g, c);
    }
}
