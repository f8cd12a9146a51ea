/* Zamuda's Algorithm 2 (drevca), eqs. 3.1-3.26: every segment of a tree of strands, one
 * pass. The recursion's tail (the main branch) is a loop and its other call (the lateral) a
 * stack, so a deep trunk cannot overflow the C stack; the geometry is the recursion's. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "strands/strands.h"
#include "util/array.h"
#include "util/rng.h"

#define DEG (3.14159265358979323846 / 180.0)

typedef struct Pending {
    StrandsFrame f;
    double L, l; /* relative and actual length of this segment */
    int64_t S;
    int g, w;    /* Gravelius and Weibull orders */
    int32_t parent, axis;
} Pending;

static void rotate(double v[3], const double k[3], double c, double s) { /* Rodrigues, k unit */
    double kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    double x[3] = {k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]};
    for (int i = 0; i < 3; i++) v[i] = v[i] * c + x[i] * s + k[i] * kv * (1 - c);
}

static void normalize(double v[3]) {
    double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++) v[i] /= n;
}

/* Rotated about the unit axis; then made orthonormal again, since rounding grows
 * geometrically along a trunk of hundreds of forks when the axes turn about each other. */
static void frame_rotate(StrandsFrame *f, const double axis[3], double angle) {
    double k[3] = {axis[0], axis[1], axis[2]}, c = cos(angle), s = sin(angle);
    normalize(k);
    rotate(f->x, k, c, s);
    rotate(f->y, k, c, s);
    normalize(f->y);
    double *x = f->x, *y = f->y, *z = f->z;
    z[0] = x[1] * y[2] - x[2] * y[1], z[1] = x[2] * y[0] - x[0] * y[2], z[2] = x[0] * y[1] - x[1] * y[0];
    normalize(z);
    x[0] = y[1] * z[2] - y[2] * z[1], x[1] = y[2] * z[0] - y[0] * z[2], x[2] = y[0] * z[1] - y[1] * z[0];
}

/* Turned toward the ground by angle (negative: up) about y x y_m; a vertical frame has no
 * such axis and stays. */
static void droop(StrandsFrame *f, double angle) {
    double ax[3] = {f->y[2], 0, -f->y[0]}, an = hypot(ax[0], ax[2]); /* y x (0,-1,0) */
    if (angle == 0 || an < 1e-12) return;
    ax[0] /= an, ax[2] /= an;
    frame_rotate(f, ax, angle);
}

/* Turned the shortest way until y points up. */
static void upright(StrandsFrame *f) {
    double tilt = acos(fmax(-1, fmin(1, f->y[1])));
    if (tilt < 1e-12) return;
    droop(f, -tilt);
}

/* A segment of length l that would end below the ground is turned up until it ends on it:
 * a hanging branch that reaches the ground trails along it (nothing grows into the soil). */
static void above_ground(StrandsFrame *f, double l) {
    double end = f->pos[1] + l * f->y[1];
    if (!(l > 0) || end >= 0 || f->y[1] >= 0) return;
    double want = asin(fmax(-1, fmin(0, -f->pos[1] / l))); /* elevation that ends at y = 0 */
    droop(f, -(want - asin(f->y[1])));
}

int strands_leaf_count(const StrandsParams *P) {
    if (P->leaf_type == LEAVES_NONE || !(P->leaf_size > 0)) return 0;
    return (int)lround(P->leaf_density);
}

StrandsCounts strands_counts(const StrandsParams *P, double age) {
    StrandsCounts c = {.strands = P->strands, .trunk_length = P->trunk_length};
    if (age > 0 && age < 1) { /* S' = t^2 S, l_0' = t^2 l_0 (3.33, 3.34) */
        c.strands = llround(age * age * (double)P->strands);
        if (c.strands < 1) c.strands = 1;
        c.trunk_length = age * age * P->trunk_length;
    }
    c.nodes = 2 * (uint64_t)c.strands; /* the root and 2S - 1 segment ends (3.1) */
    c.organs = (uint64_t)c.strands * (uint64_t)strands_leaf_count(P);
    return c;
}

static int32_t add_node(SylSkeleton *sk, const Pending *b, const double tip[3], double radius) {
    SylNode n = {.radius = (float)radius, .parent = b->parent, .axis = b->axis, .order = (uint16_t)b->g,
                 .kind = SYL_KIND_INTERNODE, .material = SYL_MATERIAL_BARK, .module = (uint32_t)sk->nnodes};
    for (int i = 0; i < 3; i++) {
        n.pos[i] = (float)tip[i];
        n.h[i] = (float)b->f.y[i]; /* H the heading, L and U across it, H x L = U */
        n.l[i] = (float)b->f.z[i];
        n.u[i] = (float)b->f.x[i];
    }
    return syl_skeleton_add_node(sk, &n);
}

int strands_build(const StrandsParams *P, double age, SylSkeleton *sk, int64_t *strands_of, const SylCancel *cancel) {
    StrandsCounts cnt = strands_counts(P, age);
    const StrandsOrderParam *o = P->order;
    /* a seed other than 0 turns the tree about its trunk: Zamuda's stand-in for Holton's
     * Writh vectors, so that trees of one species stand differently in a scene */
    Rng rng = rng_stream(P->seed, 0, 0, 0);
    double turn = P->seed ? 2 * 3.14159265358979323846 * rng_unit(&rng) : 0;
    Pending b = {.f = {.x = {cos(turn), 0, -sin(turn)}, .y = {0, 1, 0}, .z = {sin(turn), 0, cos(turn)}},
                 .L = 1, .l = cnt.trunk_length, .S = cnt.strands, .parent = -1, .axis = 0};
    SylNode root = {.radius = (float)(P->thickness * sqrt((double)cnt.strands) / 2), .parent = -1,
                    .kind = SYL_KIND_ROOT, .material = SYL_MATERIAL_BARK, .h = {0, 1, 0},
                    .l = {(float)b.f.z[0], 0, (float)b.f.z[2]}, .u = {(float)b.f.x[0], 0, (float)b.f.x[2]}};
    size_t first = sk->nnodes;
    if ((b.parent = syl_skeleton_add_node(sk, &root)) < 0) return SYL_ELIMIT;
    if (strands_of) strands_of[0] = cnt.strands;
    Pending *stack = NULL;
    size_t nstack = 0, cap = 0;
    int32_t next_axis = 1;
    int status = SYL_OK;
    for (size_t segs = 0;; segs++) {
        if (segs % STRANDS_CANCEL_EVERY == 0 && syl_cancelled(cancel)) { /* the caller frees sk */
            status = SYL_ECANCELED;
            break;
        }
        /* 1. d = k_d sqrt(S_0) (3.4); the segment along the frame's y */
        above_ground(&b.f, b.l);
        double tip[3], d = P->thickness * sqrt((double)b.S);
        for (int i = 0; i < 3; i++) tip[i] = b.f.pos[i] + b.l * b.f.y[i];
        int32_t node = add_node(sk, &b, tip, d / 2);
        if (node < 0) {
            status = SYL_ELIMIT;
            break;
        }
        if (strands_of) strands_of[(size_t)node - first] = b.S;
        if (b.S == 1) { /* 2. one strand: the branching ends, leaves grow */
            StrandsFrame lf = b.f;
            if (strands_leaves(P, &lf, b.l, node, sk) < 0) {
                status = SYL_ELIMIT;
                break;
            }
            if (!nstack) break;
            b = stack[--nstack];
            continue;
        }
        /* 3. the split (3.5-3.6), the angles (3.7-3.8), the lengths (3.24-3.26) at (g, w) */
        double ks = strands_order_value(&o[SP_SPLIT], b.g, b.w);
        double S0 = (double)b.S;
        int64_t S1 = (int64_t)ceil(1 + ks * (S0 - 2) - 1e-9), S2 = b.S - S1;
        double alpha = strands_order_value(&o[SP_ANGLE], b.g, b.w) * DEG;
        double kc = b.g == 0 ? P->gravicentral : 1; /* k_c differs from 1 only at g = 0 */
        double a1 = kc * sqrt((double)S2 / S0) * alpha, a2 = alpha - a1;
        double r1 = fmax(fmin(sqrt((double)S1 / S0), strands_order_value(&o[SP_LENGTH_MAX], b.g, b.w)),
                         strands_order_value(&o[SP_LENGTH_MIN], b.g, b.w));
        double r2 = fmax(fmin(sqrt((double)S2 / S0), strands_order_value(&o[SP_LAT_LENGTH_MAX], b.g, b.w)),
                         strands_order_value(&o[SP_LAT_LENGTH_MIN], b.g, b.w));
        double L1 = r1 * b.L, L2 = r2 * b.L;
        double l1 = strands_order_value(&o[SP_LENGTH_SCALE], b.g, b.w) * L1;
        double l2 = strands_order_value(&o[SP_LAT_LENGTH_SCALE], b.g, b.w) * L2;
        /* 4. at the tip: phyllotaxis about y, then each child turns about z, the two apart by
         * alpha. The trunk's continuation (g = 0) turns from the vertical, not from its parent:
         * k_c's "correction toward the centre", so that the trunk swings about its axis but
         * cannot fall (docs/strands.md). Every other sub-branch then turns toward the ground by
         * alpha_m about y x y_m (y_m the world's down). */
        StrandsFrame f = b.f;
        memcpy(f.pos, tip, sizeof tip);
        if (b.g == 0) upright(&f);
        if (P->phyllotaxis != 0) {
            double y[3] = {f.y[0], f.y[1], f.y[2]};
            frame_rotate(&f, y, P->phyllotaxis * DEG);
        }
        double am = strands_order_value(&o[SP_GRAVIMORPHISM], b.g, b.w) * DEG;
        double z[3] = {f.z[0], f.z[1], f.z[2]};
        Pending lat = {.f = f, .L = L2, .l = l2, .S = S2, .g = b.g + 1, .w = b.w + 1, .parent = node,
                       .axis = next_axis++};
        frame_rotate(&lat.f, z, -a2);
        droop(&lat.f, am);
        if (!array_reserve(&stack, &cap, nstack + 1, sizeof *stack)) {
            status = SYL_ELIMIT;
            break;
        }
        stack[nstack++] = lat;
        /* 5. the main branch continues this axis: the thicker bundle, the same order */
        int trunk = b.g == 0;
        b = (Pending){.f = f, .L = L1, .l = l1, .S = S1, .g = b.g, .w = b.w + 1, .parent = node, .axis = b.axis};
        frame_rotate(&b.f, z, a1);
        if (!trunk) droop(&b.f, am);
    }
    free(stack);
    return status;
}
