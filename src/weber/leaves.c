/* Leaves of the last stem level: their count (Leaves by LeafDistrib and LeafQuality, error
 * diffused), place and direction (the next level's down and rotation angles), LeafBend, and
 * the fans of palms (Leaves < 0). */
#include "util/pages.h"
#include "weber/internal.h"
#include "weber/lanes.h"

double weber_leaves_per_stem(const WeberGen *g, const WStem *st) {
    if (g->leaves == 0 || st->level == 0) return 0;
    const WStem *p = &g->stems[st->parent];
    return fabs((double)g->leaves) * weber_shape_ratio(&g->w, (int)g->w.LeafDistrib, st->offset / p->length) *
           g->w.LeafQuality;
}

/* Four leaves in the lanes of lanes.h: their axes (lane k: leaf k), bases and stems. The
 * leaves were two thirds of the tree's time, libm's sines and arctangents most of it;
 * nothing grows from a leaf and its frame is stored in floats, so floats do. */
typedef struct Leaves4 {
    v4f x[3], y[3], z[3];
    double t[4][3], dist[4];
    int id[4];
} Leaves4;

/* Eight leaves, from any stems, in the order they come: two sets of lanes turned side by side
 * (two independent chains of sines and arctangents keep the processor busier than one).
 * Before a flush a plain leaf's lanes hold its segment's axes and rot, down its angles; a
 * fan's leaf's, its own axes. */
typedef struct LeafBatch {
    Leaves4 q[2];
    v4f rot[2], down[2];
    int n;
    bool turned; /* a fan's leaves come turned */
} LeafBatch;

/* Turn the leaves outward (about the vertical) and up (about their x) toward the light. */
static void bend(const WeberGen *g, Leaves4 *q, int nq) {
    float b = (float)g->w.LeafBend;
    if (b == 0) return;
    v4f c[2], s[2], a[2];
    for (int j = 0; j < nq; j++) {
        v4f tx, ty;
        for (int k = 0; k < 4; k++) tx[k] = (float)q[j].t[k][0], ty[k] = (float)q[j].t[k][1];
        a[j] = b * (v4_atan2(ty, tx) - v4_atan2(q[j].y[1], q[j].y[0]));
    }
    for (int j = 0; j < nq; j++) v4_sincos(a[j], &c[j], &s[j]);
    for (int j = 0; j < nq; j++) {
        v4f *axes[3] = {q[j].x, q[j].y, q[j].z};
        for (int i = 0; i < 3; i++) {
            v4f *v = axes[i], x = v[0], y = v[1];
            v[0] = c[j] * x - s[j] * y;
            v[1] = s[j] * x + c[j] * y;
        }
    }
    for (int j = 0; j < nq; j++) {
        const v4f *y = q[j].y;
        a[j] = b * v4_atan2(v4_sqrt(y[0] * y[0] + y[1] * y[1]), y[2]);
    }
    for (int j = 0; j < nq; j++) v4_sincos(a[j], &c[j], &s[j]);
    for (int j = 0; j < nq; j++)
        for (int i = 0; i < 3; i++) {
            v4f p = q[j].y[i], r = q[j].z[i];
            q[j].y[i] = c[j] * p + s[j] * r;
            q[j].z[i] = c[j] * r - s[j] * p;
        }
}

/* Plain leaves: each one's segment frame (in its lanes) turned by rot about its z, then by
 * down about the new x (radians), as weber_child_direction turns a child. */
static void turn_leaves(LeafBatch *b, int nq) {
    v4f cr[2], sr[2], cd[2], sd[2];
    for (int j = 0; j < nq; j++) v4_sincos(b->rot[j], &cr[j], &sr[j]), v4_sincos(b->down[j], &cd[j], &sd[j]);
    for (int j = 0; j < nq; j++) {
        Leaves4 *q = &b->q[j];
        for (int i = 0; i < 3; i++) {
            v4f fx = q->x[i], fy = q->y[i], fz = q->z[i];
            v4f y = cr[j] * fy - sr[j] * fx;
            q->x[i] = cr[j] * fx + sr[j] * fy;
            q->y[i] = cd[j] * y + sd[j] * fz;
            q->z[i] = cd[j] * fz - sd[j] * y;
        }
    }
}

/* Tree coordinates (z up) to Sylva's (Y up), as write.c does: a position, an axis. */
static void to_sylva(float out[3], double x, double y, double z) {
    out[0] = (float)x, out[1] = (float)z, out[2] = (float)-y;
}
static void axis_to_sylva(float out[3], const v4f v[3], int k) { out[0] = v[0][k], out[1] = v[2][k], out[2] = -v[1][k]; }

/* Turn, bend and store the batch's leaves (their base moved out along the petiole, not drawn). */
static void flush(WeberGen *g, LeafBatch *b) {
    int nq = (b->n + 3) / 4;
    if (!b->turned) turn_leaves(b, nq);
    bend(g, b->q, nq);
    if (g->nlvs + (size_t)b->n > g->lvs_cap) { /* (sized by the count: cannot happen) */
        g->failed = true;
        return;
    }
    double stem = g->w.LeafStemLen * g->leaf_len;
    uint8_t kind = g->w.leaf_kind == WEBER_LEAF_SPHERE ? SYL_KIND_SPHERE : SYL_KIND_LEAF;
    for (int m = 0; m < b->n; m++) {
        const Leaves4 *q = &b->q[m / 4];
        int k = m % 4;
        SylOrgan *o = &g->lvs[g->nlvs++];
        const double *t = q->t[k];
        double zx = q->z[0][k], zy = q->z[1][k], zz = q->z[2][k];
        to_sylva(o->pos, t[0] + zx * stem, t[1] + zy * stem, t[2] + zz * stem);
        axis_to_sylva(o->h, q->z, k);
        axis_to_sylva(o->l, q->x, k);
        axis_to_sylva(o->u, q->y, k); /* y = z x x */
        o->size = (float)g->leaf_len;
        o->node = weber_leaf_node(g, q->id[k], (float)q->dist[k]);
        o->kind = kind;
        o->material = SYL_MATERIAL_LEAF;
        o->module = (uint32_t)q->id[k];
    }
    b->n = 0;
}

/* A leaf into the batch: frame f's axes (a plain leaf: its segment's, to be turned by rot
 * and down; a fan's: its own), its base t. */
static void push_leaf(WeberGen *g, LeafBatch *b, int id, const Frame *f, const double t[3], double dist,
                      float rot, float down) {
    Leaves4 *q = &b->q[b->n / 4];
    int k = b->n % 4;
    for (int i = 0; i < 3; i++)
        q->x[i][k] = (float)f->x[i], q->y[i][k] = (float)f->y[i], q->z[i][k] = (float)f->z[i], q->t[k][i] = t[i];
    q->dist[k] = dist, q->id[k] = id;
    b->rot[b->n / 4][k] = rot, b->down[b->n / 4][k] = down;
    if (++b->n == 8) flush(g, b);
}

/* The leaves of segment seg (its frame f) into the batch, or n of them when count (nothing
 * made). */
static void leaves_on(WeberGen *g, int id, WStem *st, int seg, const Frame *f, Rng *kids, LeafBatch *b,
                      size_t *count) {
    const WeberParams *w = &g->w;
    double len = st->seglen;
    if (g->leaves > 0) {
        int n = (int)(st->lps + g->leaf_err + 0.5);
        g->leaf_err -= n - st->lps;
        if (n <= 0) return;
        if (count) {
            *count += (size_t)n;
            return;
        }
        double offs = seg == 0 ? weber_radius(g, &g->stems[st->parent], st->offset) / len : 0;
        double dist = (1.0 - offs) / n;
        for (int k = 0; k < n && !g->failed; k++) {
            double where = offs + dist / 2 + k * dist + weber_var(kids, dist / 2), d, r, t[3];
            double at = (seg + where) * len;
            weber_child_angles(g, st, at, st->level + 1, kids, &d, &r);
            double step = weber_step(g, st, f);
            for (int i = 0; i < 3; i++) t[i] = f->t[i] + f->z[i] * where * step;
            push_leaf(g, b, id, f, t, at, (float)(r * (M_PI / 180)), (float)(d * (M_PI / 180)));
        }
    } else if (seg == st->nseg - 1) { /* a fan at the tip */
        int cl = weber_lv(st->level + 1);
        int n = (int)(weber_leaves_per_stem(g, st) + 0.5);
        if (n <= 0) return;
        if (count) {
            *count += (size_t)n;
            return;
        }
        Frame tip = *f;
        frame_move(&tip, weber_step(g, st, &tip));
        b->turned = true;
        double step = w->Rotate[cl] / n, stepv = w->RotateV[cl] / n, off;
        if (n % 2 == 1) {
            push_leaf(g, b, id, &tip, tip.t, st->length, 0, 0);
            off = step;
        } else {
            off = step / 2;
        }
        for (int k = 0; k < n / 2 && !g->failed; k++)
            for (int side = 1; side >= -1; side -= 2) {
                Frame lf = tip;
                frame_rot_local(&lf, 0, 1, 0, -side * (off + k * step + weber_var(kids, stepv))); /* Arbaro's roty */
                frame_rot_local(&lf, 1, 0, 0, w->DownAngle[cl] + weber_var(kids, w->DownAngleV[cl]));
                push_leaf(g, b, id, &lf, lf.t, st->length, 0, 0);
            }
    }
}

/* A stem's first segment starts at its start frame unless it is a clone (the first turn of
 * a stem comes after its first segment): that one is not kept twice. */
static int first_kept(const WStem *st) { return st->clone ? st->first_seg : st->first_seg + 1; }

bool weber_defer_leaves(WeberGen *g, int id, const WStem *st, const WSeg *segs) {
    int s0 = first_kept(st);
    size_t n = (size_t)(st->nseg > s0 ? st->nseg - s0 : 0);
    if (!weber_grow(g, (void **)&g->leafy, &g->leafy_cap, g->nleafy + 1, sizeof *g->leafy) ||
        !weber_grow(g, (void **)&g->leafy_f, &g->leafy_f_cap, g->nleafy_f + n, sizeof *g->leafy_f))
        return false;
    g->leafy[g->nleafy++] = id;
    for (int s = s0; s < st->nseg; s++) g->leafy_f[g->nleafy_f++] = segs[s].f;
    return true;
}

/* Two passes over the last level's stems in the order they were made (the order of the
 * leaves' error diffusion): the count, then the leaves into arrays of that size. A stem's
 * leaves draw from its own stream and turn from its first rotation, as they would have
 * while it was made. */
void weber_place_leaves(WeberGen *g) {
    double err = g->leaf_err;
    for (int pass = 0; pass < 2 && !g->failed; pass++) {
        size_t count = 0, fi = 0;
        LeafBatch b = {0};
        g->leaf_err = err;
        for (size_t i = 0; i < g->nleafy && !g->failed; i++) {
            int id = g->leafy[i];
            WStem copy, *st = &g->stems[id]; /* (the count changes nothing) */
            if (pass == 1) copy = *st, st = &copy; /* its rotation advances here, not in the list */
            Rng kids = pass == 1 ? weber_rng(g, st->key, WRNG_KIDS) : (Rng){0};
            int s0 = first_kept(st);
            for (int s = st->first_seg; s < st->nseg; s++)
                leaves_on(g, id, st, s, s < s0 ? &st->start : &g->leafy_f[fi++], &kids, &b, pass == 0 ? &count : NULL);
        }
        if (b.n && !g->failed) flush(g, &b);
        if (pass == 0 && count) { /* the organs' array, the skeleton's to free (after the nodes
                                   * in the arena: see weber_write_nodes) */
            if (!budget_charge(g->budget, (uint64_t)count * sizeof *g->lvs) ||
                !(g->lvs = weber_keep(g, count * sizeof *g->lvs))) {
                g->failed = true;
                return;
            }
            g->charged += (uint64_t)count * sizeof *g->lvs;
            g->lvs_cap = count;
        }
    }
}
