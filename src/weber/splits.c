/* Splits (clones of a stem at a segment's end): how many, by error diffusion per level or
 * 0BaseSplits at the trunk's first segment, and the direction of each fork. */
#include "weber/internal.h"

int weber_split_count(WeberGen *g, const WStem *st, int seg) {
    if (st->level == 0 && seg == 0 && g->w.BaseSplits > 0) return (int)g->w.BaseSplits;
    int lv = st->level < 9 ? st->level : 9;
    double want = g->w.SegSplits[weber_lv(st->level)];
    int n = (int)(want + g->split_err[lv] + 0.5);
    g->split_err[lv] -= n - want;
    return n;
}

/* Turn a fork by the split angle (less the stem's declination) about its x axis, and a
 * clone (s_angle > 0) about the vertical: base splits evenly, others by Weber & Penn's
 * spread. The later segments turn back by split_corr, so the fork straightens out. */
Frame weber_split(WeberGen *g, WStem *st, Rng *r, Frame trf, double s_angle, int seg, int nsplits, bool test) {
    const WeberParams *w = &g->w;
    int lv = weber_lv(st->level);
    int remaining = st->nseg - seg - 1;
    double zz = trf.z[2] > 1 ? 1 : trf.z[2] < -1 ? -1 : trf.z[2];
    double decl = acos(zz) * 180 / M_PI;
    double angle = w->SplitAngle[lv] + weber_var(r, w->SplitAngleV[lv]) - decl;
    if (angle < 0) angle = 0;
    frame_rot_local(&trf, 1, 0, 0, angle);
    if (remaining > 0) st->split_corr -= angle / remaining;
    if (s_angle > 0) {
        double spread;
        if (w->BaseSplits > 0 && st->level == 0 && seg == 0) {
            spread = s_angle + weber_var(r, w->SplitAngleV[lv]);
        } else {
            double u = (weber_var(r, 1) + 1) / 2.0;
            spread = 20 + 0.75 * (30 + fabs(decl - 90)) * u * u;
            if (weber_var(r, 1) >= 0) spread = -spread;
        }
        static const double up[3] = {0, 0, 1};
        frame_rot_global(&trf, up, spread);
    }
    if (!test) st->sps /= nsplits + 1;
    return trf;
}
