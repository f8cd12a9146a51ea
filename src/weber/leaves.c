/* Leaves of the last stem level: their count (Leaves by LeafDistrib and LeafQuality, error
 * diffused), place and direction (the next level's down and rotation angles), LeafBend, and
 * the fans of palms (Leaves < 0). */
#include "weber/internal.h"
#include "weber/lanes.h"

double weber_leaves_per_stem(const WeberGen *g, const WStem *st) {
    if (g->leaves == 0 || st->level == 0) return 0;
    const WStem *p = &g->stems[st->parent];
    return fabs((double)g->leaves) * weber_shape_ratio(&g->w, (int)g->w.LeafDistrib, st->offset / p->length) *
           g->w.LeafQuality;
}

/* Up to four leaves at once, in the lanes of lanes.h: their axes (lane k: leaf k) and their
 * bases. The leaves were two thirds of the tree's time, libm's sines and arctangents most
 * of it; nothing grows from a leaf and its frame is stored in floats, so floats do. */
typedef struct Leaves4 {
    v4f x[3], y[3], z[3];
    double t[4][3], dist[4];
    int n;
} Leaves4;

/* Turn the leaves outward (about the vertical) and up (about their x) toward the light. */
static void bend(const WeberGen *g, Leaves4 *q) {
    float b = (float)g->w.LeafBend;
    if (b == 0) return;
    v4f tx = {0}, ty = {0}, c, s;
    for (int k = 0; k < q->n; k++) tx[k] = (float)q->t[k][0], ty[k] = (float)q->t[k][1];
    v4_sincos(b * (v4_atan2(ty, tx) - v4_atan2(q->y[1], q->y[0])), &c, &s);
    v4f *axes[3] = {q->x, q->y, q->z};
    for (int a = 0; a < 3; a++) {
        v4f *v = axes[a], x = v[0], y = v[1];
        v[0] = c * x - s * y;
        v[1] = s * x + c * y;
    }
    v4f *y = q->y, *z = q->z;
    v4_sincos(b * v4_atan2(v4_sqrt(y[0] * y[0] + y[1] * y[1]), y[2]), &c, &s);
    for (int i = 0; i < 3; i++) {
        v4f p = y[i], r = z[i];
        y[i] = c * p + s * r;
        z[i] = c * r - s * p;
    }
}

/* The leaves on a segment: its frame f turned by rot about its z, then by down about the new
 * x (radians), as weber_child_direction turns a child. */
static void turn_leaves(const Frame *f, v4f rot, v4f down, Leaves4 *q) {
    v4f cr, sr, cd, sd;
    v4_sincos(rot, &cr, &sr);
    v4_sincos(down, &cd, &sd);
    for (int i = 0; i < 3; i++) {
        float fx = (float)f->x[i], fy = (float)f->y[i], fz = (float)f->z[i];
        v4f y = cr * fy - sr * fx;
        q->x[i] = cr * fx + sr * fy;
        q->y[i] = cd * y + sd * fz;
        q->z[i] = cd * fz - sd * y;
    }
}

/* Tree coordinates (z up) to Sylva's (Y up), as write.c does: a position, an axis. */
static void to_sylva(float out[3], double x, double y, double z) {
    out[0] = (float)x, out[1] = (float)z, out[2] = (float)-y;
}
static void axis_to_sylva(float out[3], const v4f v[3], int k) { out[0] = v[0][k], out[1] = v[2][k], out[2] = -v[1][k]; }

/* Bend the leaves and store them (their base moved out along the petiole, not drawn). */
static void put_leaves(WeberGen *g, int id, Leaves4 *q) {
    bend(g, q);
    if (g->nlvs + q->n > g->lvs_cap) { /* (sized by the count: cannot happen) */
        g->failed = true;
        return;
    }
    double stem = g->w.LeafStemLen * g->leaf_len;
    uint8_t kind = g->w.leaf_kind == WEBER_LEAF_SPHERE ? SYL_KIND_SPHERE : SYL_KIND_LEAF;
    for (int k = 0; k < q->n; k++) {
        SylOrgan *o = &g->lvs[g->nlvs++];
        const double *t = q->t[k];
        double zx = q->z[0][k], zy = q->z[1][k], zz = q->z[2][k];
        to_sylva(o->pos, t[0] + zx * stem, t[1] + zy * stem, t[2] + zz * stem);
        axis_to_sylva(o->h, q->z, k);
        axis_to_sylva(o->l, q->x, k);
        axis_to_sylva(o->u, q->y, k); /* y = z x x */
        o->size = (float)g->leaf_len;
        o->node = weber_leaf_node(g, id, (float)q->dist[k]);
        o->kind = kind;
        o->material = SYL_MATERIAL_LEAF;
        o->module = (uint32_t)id;
    }
    q->n = 0;
}

/* A fan's leaf, its frame made one by one; stored four at a time. */
static void push_leaf(WeberGen *g, int id, Leaves4 *q, const Frame *f, double dist) {
    int k = q->n++;
    for (int i = 0; i < 3; i++)
        q->x[i][k] = (float)f->x[i], q->y[i][k] = (float)f->y[i], q->z[i][k] = (float)f->z[i], q->t[k][i] = f->t[i];
    q->dist[k] = dist;
    if (q->n == 4) put_leaves(g, id, q);
}

/* The leaves of segment seg (its frame f), or n of them when count (nothing made). */
static void leaves_on(WeberGen *g, int id, WStem *st, int seg, const Frame *f, Rng *kids, size_t *count) {
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
        Leaves4 q = {0};
        v4f rot = {0}, down = {0};
        for (int k = 0; k < n && !g->failed; k++) {
            double where = offs + dist / 2 + k * dist + weber_var(kids, dist / 2), d, r;
            double at = (seg + where) * len;
            weber_child_angles(g, st, at, st->level + 1, kids, &d, &r);
            rot[q.n] = (float)(r * (M_PI / 180)), down[q.n] = (float)(d * (M_PI / 180));
            for (int i = 0; i < 3; i++) q.t[q.n][i] = (*f).t[i] + (*f).z[i] * where * len;
            q.dist[q.n++] = at;
            if (q.n == 4 || k == n - 1) {
                turn_leaves(f, rot, down, &q);
                put_leaves(g, id, &q);
            }
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
        frame_move(&tip, len);
        Leaves4 q = {0};
        double step = w->Rotate[cl] / n, stepv = w->RotateV[cl] / n, off;
        if (n % 2 == 1) {
            push_leaf(g, id, &q, &tip, st->length);
            off = step;
        } else {
            off = step / 2;
        }
        for (int k = 0; k < n / 2 && !g->failed; k++)
            for (int side = 1; side >= -1; side -= 2) {
                Frame f = tip;
                frame_rot_local(&f, 0, 1, 0, -side * (off + k * step + weber_var(kids, stepv))); /* Arbaro's roty */
                frame_rot_local(&f, 1, 0, 0, w->DownAngle[cl] + weber_var(kids, w->DownAngleV[cl]));
                push_leaf(g, id, &q, &f, st->length);
            }
        if (q.n && !g->failed) put_leaves(g, id, &q);
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
        g->leaf_err = err;
        for (size_t i = 0; i < g->nleafy && !g->failed; i++) {
            int id = g->leafy[i];
            WStem copy, *st = &g->stems[id]; /* (the count changes nothing) */
            if (pass == 1) copy = *st, st = &copy; /* its rotation advances here, not in the list */
            Rng kids = pass == 1 ? weber_rng(g, st->key, WRNG_KIDS) : (Rng){0};
            g->stems[id].leaf_first = (uint32_t)g->nlvs;
            int s0 = first_kept(st);
            for (int s = st->first_seg; s < st->nseg; s++)
                leaves_on(g, id, st, s, s < s0 ? &st->start : &g->leafy_f[fi++], &kids, pass == 0 ? &count : NULL);
            g->stems[id].leaf_count = (uint32_t)(g->nlvs - g->stems[id].leaf_first);
        }
        if (pass == 0 && count) { /* the organs' array, the skeleton's to free */
            if (!budget_charge(g->budget, (uint64_t)count * sizeof *g->lvs) ||
                !(g->lvs = weber_alloc_owned(count * sizeof *g->lvs))) {
                g->failed = true;
                return;
            }
            g->charged += (uint64_t)count * sizeof *g->lvs;
            g->lvs_cap = count;
        }
    }
}
