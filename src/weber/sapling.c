/* Blender Sapling's laws of counting (SaplingLaw 1, which Sapling's presets set; docs/arbaro.md
 * "Sapling's presets"): how many children a stem gets, when a stem splits, and the stem each
 * stem sprouts at its tip. Facts of Sapling's add-on (GPL) written anew. */
#include <math.h>
#include <stdlib.h>

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
 * SaplingSplitHeight, and always once at the first segment above it; its SegSplits is times
 * 1 + 2 SaplingSplitBias (h - 1/2) at the split's height h (a share of its segments), not below 0. */
int weber_sapling_splits(WeberGen *g, const WStem *st, int seg, Rng *r) {
    const WeberParams *w = &g->w;
    int k = seg + 1; /* Sapling counts the segment the split starts */
    double s = w->SegSplits[weber_lv(st->level)];
    if (st->level == 0 && w->SaplingSplitBias != 0) {
        double h = st->nseg > 1 ? (double)k / (st->nseg - 1) : 1;
        s = fmax(0, (2 * w->SaplingSplitBias * (h - 0.5) + 1) * s);
    }
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

/* A child of st at `at` segments from its base (place number a), along segment int(at). */
void weber_sapling_child(WeberGen *g, int id, WStem *st, const WSeg *segs, double at, int a, Rng *kids) {
    int seg = (int)at;
    double where = at - seg;
    WStem c = {0};
    c.level = st->level + 1;
    c.parent = id;
    c.offset = at * st->seglen;
    c.u_lcm = -1; /* its children's length drawn, ± LengthV */
    c.key = weber_key(st->key, 1, (uint64_t)seg << 20 | (uint64_t)a);
    c.start = weber_child_direction(g, st, segs[seg].f, c.offset, c.level, kids);
    double step = weber_step(g, st, &segs[seg].f);
    for (int i = 0; i < 3; i++) c.start.t[i] = segs[seg].f.t[i] + segs[seg].f.z[i] * where * step;
    weber_make_stem(g, c);
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
        if ((int)at < st->first_seg || (int)at >= st->nseg) continue;
        weber_sapling_child(g, id, st, segs, at, a, kids);
    }
}

static int by_value(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The trunk's places for children, as shares t of its length, by Sapling: Branches (level 1)
 * even places t = 1/N … 1, the lowest int(BaseSize (N + 1)) dropped; with SaplingRings k, each
 * but the last moved down to its whorl, floor(t k) / k, times 1 ± 0.5 %, and those not above
 * the bare base dropped; then spread above the bare base b by SaplingBranchDist d, the share
 * u = (t - b) / (1 - b) becoming u^(1/d) below 1 and 1 - (1 - u)^d from 1 on. The last, t = 1,
 * is left to the tip's stem. out has room for Branches; returns the count, in ascending order. */
size_t weber_sapling_trunk_places(const WeberParams *w, Rng *r, double *out) {
    double nb = w->Branches[1], b = w->BaseSize, d = w->SaplingBranchDist;
    int n = nb < 1 ? 0 : nb > 1e9 ? 1000000000 : (int)nb, rings = (int)fmin(w->SaplingRings, 1e9);
    size_t k = 0;
    for (int a = (int)(b * (n + 1.0)); a < n; a++) {
        double t = (a + 1.0) / n;
        if (rings > 0 && a < n - 1) {
            t = floor(t * rings) / rings * (0.995 + 0.01 * rng_unit(r));
            if (!(t > b)) continue;
        }
        if (b < 1) {
            double u = (t - b) / (1 - b);
            u = d < 1 ? pow(u, 1 / d) : d > 1 ? 1 - pow(1 - u, d) : u;
            t = u * (1 - b) + b;
        }
        if (t < 1) out[k++] = t;
    }
    qsort(out, k, sizeof *out, by_value);
    return k;
}

/* Sapling's taperCrown: a trunk (or trunk fork) segment heading at declination d degrees is
 * max(0.1, 1 - 30 SaplingTaperCrown (d / 180)^2) as long; 1 elsewhere. */
static double crown_taper(const WeberGen *g, const WStem *st, const Frame *f) {
    if (!g->w.SaplingLaw || st->level != 0 || !(g->w.SaplingTaperCrown > 0)) return 1;
    double zz = f->z[2] > 1 ? 1 : f->z[2] < -1 ? -1 : f->z[2];
    double d = acos(zz) / M_PI; /* degrees / 180 */
    return fmax(0.1, 1 - 30 * g->w.SaplingTaperCrown * d * d);
}

/* The length of the step a stem's segment with frame f takes: its seglen, shortened by
 * taperCrown; the segment's share of the stem (radius, children's places) stays its seglen's,
 * as Sapling's radii and places go by the segment's number. */
double weber_step(const WeberGen *g, const WStem *st, const Frame *f) {
    double k = crown_taper(g, st, f);
    return k == 1 ? st->seglen : st->seglen * k;
}

/* A fork's own length, as a share of its stem's before any fork's: 1 ± LengthV / Length of its
 * level, drawn from the fork's own stream (so that a fork of a fork can find its origin's). */
static double fork_share(const WeberGen *g, const WStem *c) {
    int lv = weber_lv(c->level);
    double v = g->w.Length[lv] > 0 ? g->w.LengthV[lv] / g->w.Length[lv] : 0;
    if (!c->clone || !(v > 0)) return 1;
    Rng own = weber_rng(g, c->key, WRNG_FORK);
    return 1 + weber_var(&own, v);
}

/* SaplingLaw: a fork c split from `from` at frame f, as Sapling's: its segments 1 ± lengthV as
 * long as the stem's before any fork's (not compounded), its radius times that share times the
 * crown taper at the split, at most 1 (compounded, as Sapling's radii are). */
void weber_sapling_fork(const WeberGen *g, const WStem *from, WStem *c, const Frame *f) {
    double own = fork_share(g, c), k = own / fork_share(g, from);
    if (k != 1) c->seglen *= k, c->length *= k;
    double r = fmin(own * crown_taper(g, from, f), 1);
    if (r != 1) c->base_radius *= r;
}
