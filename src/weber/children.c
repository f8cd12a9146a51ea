/* Children of a stem: how many on each segment (error diffusion, the trunk's bare base),
 * where on the segment (BranchDist), and their direction (the angles: internal.h). */
#include "weber/internal.h"

Frame weber_child_direction(WeberGen *g, WStem *st, Frame trf, double offset, int child_level, Rng *kids) {
    double down, rot;
    weber_child_angles(g, st, offset, child_level, kids, &down, &rot);
    frame_rotxz(&trf, down, rot);
    return trf;
}

void weber_children(WeberGen *g, int id, WStem *st, int seg, const WSeg *segs, Rng *kids) {
    const WeberParams *w = &g->w;
    int cl = weber_lv(st->level + 1), lv = st->level < 9 ? st->level : 9;
    double per = segs[seg].sps, offs = 0, len = st->seglen;
    if (st->level > 0) {
        if (seg == 0) offs = weber_radius(g, &g->stems[st->parent], st->offset) / len; /* not inside the parent */
    } else if (seg * len > w->BaseSize * st->length) {
    } else if ((seg + 1) * len <= w->BaseSize * st->length) {
        return; /* the bare base of the trunk */
    } else {
        offs = (w->BaseSize * st->length - seg * len) / len;
        per *= 1 - offs;
    }
    int n = (int)(per + g->sub_err[lv] + 0.5);
    g->sub_err[lv] -= n - per;
    if (n <= 0) return;
    double dist = (1.0 - offs) / n * w->BranchDist[cl], distv = dist * 0.25;
    for (int k = 0; k < n && !g->failed; k++) {
        double where = offs + dist / 2 + k * dist + weber_var(kids, distv);
        WStem c = {0};
        c.level = st->level + 1;
        c.parent = id;
        c.offset = (seg + where) * len;
        c.u_lcm = -1; /* its children's length drawn, ± LengthV (Arbaro's lengthChildMax per stem) */
        c.key = weber_key(st->key, 1, (uint64_t)seg << 20 | (uint64_t)k);
        c.start = weber_child_direction(g, st, segs[seg].f, c.offset, c.level, kids);
        for (int i = 0; i < 3; i++) c.start.t[i] = segs[seg].f.t[i] + segs[seg].f.z[i] * where * len;
        weber_make_stem(g, c);
    }
}

/* SaplingLaw: the stem every stem (and clone) sprouts at its tip, along it, as Sapling's does. */
void weber_tip_child(WeberGen *g, int id, WStem *st, const WSeg *segs, Rng *kids) {
    WStem c = {0};
    c.level = st->level + 1;
    c.parent = id;
    c.offset = st->length - 0.5 * st->seglen; /* its length and radius from just below the tip, where the radius is not 0 */
    c.u_lcm = -1; /* its children's length drawn, ± LengthV */
    c.key = weber_key(st->key, 1, (uint64_t)1 << 40);
    c.start = segs[st->nseg - 1].f;
    frame_move(&c.start, weber_step(g, st, &c.start));
    double down, rot;
    weber_child_angles(g, st, c.offset, c.level, kids, &down, &rot);
    frame_rotxz(&c.start, 0, rot);
    weber_make_stem(g, c);
}
