/* Leaves of the last stem level: their count (Leaves by LeafDistrib and LeafQuality, error
 * diffused), place and direction (the next level's down and rotation angles), LeafBend, and
 * the fans of palms (Leaves < 0). */
#include "weber/internal.h"

double weber_leaves_per_stem(const WeberGen *g, const WStem *st) {
    if (g->leaves == 0 || st->level == 0) return 0;
    const WStem *p = &g->stems[st->parent];
    return fabs((double)g->leaves) * weber_shape_ratio(&g->w, (int)g->w.LeafDistrib, st->offset / p->length) *
           g->w.LeafQuality;
}

/* A leaf turns by single-precision sines and weber_atan2, several times cheaper than libm's
 * double ones (the leaves were two thirds of the tree's time): nothing grows from a leaf, and
 * its frame is stored in floats, so the error (about 1e-7 radian) ends there. */
static void sincos_f(double rad, double *c, double *s) {
    float sf, cf;
    sincosf((float)rad, &sf, &cf);
    *c = cf, *s = sf;
}

static void turn_x_f(Frame *f, double rad) {
    double c, s;
    sincos_f(rad, &c, &s);
    frame_turn_x(f, c, s);
}

/* Turn a leaf outward (about the vertical) and up (about its x) toward the light. */
static void bend(const WeberGen *g, Frame *f) {
    double b = g->w.LeafBend, c, s;
    if (b == 0) return;
    double tbend = weber_atan2(f->t[1], f->t[0]) - weber_atan2(f->y[1], f->y[0]);
    sincos_f(b * tbend, &c, &s);
    frame_turn_vertical(f, c, s);
    double fbend = weber_atan2(sqrt(f->y[0] * f->y[0] + f->y[1] * f->y[1]), f->y[2]);
    turn_x_f(f, b * fbend);
}

/* The leaf's direction from its segment's frame, as weber_child_direction turns a child */
static void leaf_direction(WeberGen *g, WStem *st, Frame *trf, double offset, Rng *kids) {
    double down, rot, c, s;
    weber_child_angles(g, st, offset, st->level + 1, kids, &down, &rot);
    sincos_f(rot * (M_PI / 180), &c, &s);
    frame_turn_z(trf, c, s);
    turn_x_f(trf, down * (M_PI / 180));
}

/* Tree coordinates (z up) to Sylva's (Y up), as write.c does. */
static void to_sylva(float out[3], const double in[3]) {
    out[0] = (float)in[0], out[1] = (float)in[2], out[2] = (float)-in[1];
}

/* (frames by pointer: copies of the 96-byte struct were a sixth of the leaves' time) */
static void put_leaf(WeberGen *g, int id, Frame *f, double dist) {
    bend(g, f);
    if (!weber_grow(g, (void **)&g->lvs, &g->lvs_cap, g->nlvs + 1, sizeof *g->lvs) ||
        !weber_grow(g, (void **)&g->ldist, &g->ldist_cap, g->nlvs + 1, sizeof *g->ldist))
        return;
    SylOrgan *o = &g->lvs[g->nlvs];
    g->ldist[g->nlvs++] = (float)dist;
    double stem = g->w.LeafStemLen * g->leaf_len, p[3]; /* the petiole, not drawn */
    for (int i = 0; i < 3; i++) p[i] = f->t[i] + f->z[i] * stem;
    to_sylva(o->pos, p);
    to_sylva(o->h, f->z);
    to_sylva(o->l, f->x);
    to_sylva(o->u, f->y); /* y = z x x */
    o->size = (float)g->leaf_len;
    o->node = -1;
    o->kind = g->w.leaf_kind == WEBER_LEAF_SPHERE ? SYL_KIND_SPHERE : SYL_KIND_LEAF;
    o->material = SYL_MATERIAL_LEAF;
    o->module = (uint32_t)id;
}

void weber_leaves(WeberGen *g, int id, WStem *st, int seg, const WSeg *segs, Rng *kids) {
    const WeberParams *w = &g->w;
    double len = st->seglen;
    if (g->leaves > 0) {
        int n = (int)(st->lps + g->leaf_err + 0.5);
        g->leaf_err -= n - st->lps;
        if (n <= 0) return;
        double offs = seg == 0 ? weber_radius(g, &g->stems[st->parent], st->offset) / len : 0;
        double dist = (1.0 - offs) / n;
        for (int k = 0; k < n && !g->failed; k++) {
            double where = offs + dist / 2 + k * dist + weber_var(kids, dist / 2);
            double at = (seg + where) * len;
            Frame f = segs[seg].f;
            leaf_direction(g, st, &f, at, kids);
            for (int i = 0; i < 3; i++) f.t[i] = segs[seg].f.t[i] + segs[seg].f.z[i] * where * len;
            put_leaf(g, id, &f, at);
        }
    } else if (seg == st->nseg - 1) { /* a fan at the tip */
        int cl = weber_lv(st->level + 1);
        int n = (int)(weber_leaves_per_stem(g, st) + 0.5);
        if (n <= 0) return;
        Frame tip = segs[seg].f;
        frame_move(&tip, len);
        double step = w->Rotate[cl] / n, stepv = w->RotateV[cl] / n, off;
        if (n % 2 == 1) {
            Frame f = tip;
            put_leaf(g, id, &f, st->length);
            off = step;
        } else {
            off = step / 2;
        }
        for (int k = 0; k < n / 2 && !g->failed; k++)
            for (int side = 1; side >= -1; side -= 2) {
                Frame f = tip;
                frame_rot_local(&f, 0, 1, 0, -side * (off + k * step + weber_var(kids, stepv))); /* Arbaro's roty */
                frame_rot_local(&f, 1, 0, 0, w->DownAngle[cl] + weber_var(kids, w->DownAngleV[cl]));
                put_leaf(g, id, &f, st->length);
            }
    }
}
