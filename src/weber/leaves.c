/* Leaves of the last stem level: their count (Leaves by LeafDistrib and LeafQuality, error
 * diffused), place and direction (the next level's down and rotation angles), LeafBend, and
 * the fans of palms (Leaves < 0). */
#include "util/pages.h"
#include "weber/internal.h"
#include "weber/leaf_turn.h"

double weber_leaves_per_stem(const WeberGen *g, const WStem *st) {
    if (g->leaves == 0 || st->level == 0) return 0;
    const WStem *p = &g->stems[st->parent];
    return fabs((double)g->leaves) * weber_shape_ratio(&g->w, (int)g->w.LeafDistrib, st->offset / p->length) *
           g->w.LeafQuality;
}

/* Eight leaves, from any stems, in the order they come, turned together (leaf_turn.h). The
 * leaves were two thirds of the tree's time, libm's sines and arctangents most of it;
 * nothing grows from a leaf and its frame is stored in floats, so floats do. */
typedef struct LeafBatch {
    Leaves8 q;
    int n;
    bool turned; /* a fan's leaves come turned */
    bool avx2;   /* turned in AVX2's registers (weber_leaf_avx2) */
} LeafBatch;

/* Tree coordinates (z up) to Sylva's (Y up), as write.c does: a position, an axis. */
static void to_sylva(float out[3], double x, double y, double z) {
    out[0] = (float)x, out[1] = (float)z, out[2] = (float)-y;
}
static void axis_to_sylva(float out[3], const v8f v[3], int k) { out[0] = v[0][k], out[1] = v[2][k], out[2] = -v[1][k]; }

/* Turn, bend and store the batch's leaves (their base moved out along the petiole, not drawn). */
static void flush(WeberGen *g, LeafBatch *b) {
    if (b->avx2) weber_leaf_turn_avx2(&b->q, b->turned, (float)g->w.LeafBend);
    else v4_leaf_turn(&b->q, b->turned, (float)g->w.LeafBend);
    if (g->nlvs + (size_t)b->n > g->lvs_cap) { /* (sized by the count: cannot happen) */
        g->failed = true;
        return;
    }
    double stem = g->w.LeafStemLen * g->leaf_len;
    uint8_t kind = g->w.leaf_kind == WEBER_LEAF_SPHERE ? SYL_KIND_SPHERE : SYL_KIND_LEAF;
    for (int m = 0; m < b->n; m++) {
        const Leaves8 *q = &b->q;
        int k = m;
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
    Leaves8 *q = &b->q;
    int k = b->n;
    for (int i = 0; i < 3; i++)
        q->x[i][k] = (float)f->x[i], q->y[i][k] = (float)f->y[i], q->z[i][k] = (float)f->z[i], q->t[k][i] = t[i];
    q->tx[k] = (float)t[0], q->ty[k] = (float)t[1];
    q->dist[k] = dist, q->id[k] = id;
    q->rot[k] = rot, q->down[k] = down;
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

/* The leaves' count: a pass over the last level's stems in the order they were made (the
 * order of the leaves' error diffusion), which it leaves as it found it. */
size_t weber_count_leaves(WeberGen *g) {
    double err = g->leaf_err;
    size_t count = 0;
    LeafBatch b = {0};
    for (size_t i = 0; i < g->nleafy && !g->failed; i++) {
        WStem *st = &g->stems[g->leafy[i]];
        for (int s = st->first_seg; s < st->nseg; s++) leaves_on(g, g->leafy[i], st, s, NULL, NULL, &b, &count);
    }
    g->leaf_err = err;
    return count;
}

/* The leaves (count of them: weber_count_leaves) into an array of that size, in the same
 * order. A stem's leaves draw from its own stream and turn from its first rotation, as they
 * would have while it was made. */
void weber_place_leaves(WeberGen *g, size_t count) {
    if (g->failed) return;
    if (count) { /* the organs' array, the skeleton's to free (after the nodes in the arena:
                  * see weber_write_nodes) */
        if (!budget_charge(g->budget, (uint64_t)count * sizeof *g->lvs) ||
            !(g->lvs = weber_keep(g, count * sizeof *g->lvs))) {
            g->failed = true;
            return;
        }
        g->charged += (uint64_t)count * sizeof *g->lvs;
        g->lvs_cap = count;
    }
    size_t fi = 0;
    LeafBatch b = {.avx2 = weber_leaf_avx2()};
    for (size_t i = 0; i < g->nleafy && !g->failed; i++) {
        int id = g->leafy[i];
        WStem *st = &g->stems[id];
        double rot = st->rot; /* its rotation advances here (the one field a leaf changes), not
                               * in the list: put back after (a copy of the stem took longer) */
        Rng kids = weber_rng(g, st->key, WRNG_KIDS);
        int s0 = first_kept(st);
        for (int s = st->first_seg; s < st->nseg; s++)
            leaves_on(g, id, st, s, s < s0 ? &st->start : &g->leafy_f[fi++], &kids, &b, NULL);
        st->rot = rot;
    }
    if (b.n && !g->failed) flush(g, &b);
}
