/* The generator (thesis §4.2-4.4): the trunk along its curve, first-level branches on the part
 * of the trunk inside the envelope, second-level ones (at most four segments) on them, each
 * grown segment by segment and shortened until it fits inside; Gaussian variation (sigma 10 %
 * of the nominal value) of widths, spacing, angles and bends; a quadrant spiral about the
 * parent; leaves denser toward the tips. Every branch draws from a random stream of its own
 * (seed, level, index): the tree does not depend on the order things are made in. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "skeleton/store.h"
#include "curvetree/curvetree.h"
#include "util/array.h"
#include "util/pages.h"
#include "util/rng.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180)

enum {
    SEG1_MAX = 32, /* a first-level branch's segments: L_trunk / 16 each, at most two trunks long */
    SEG2_MAX = 4,  /* a second-level branch's (the thesis's limit) */
    FIT_STEPS = 12 /* halvings that shorten a segment until its end is inside */
};

/* A branch (or the trunk) as a polyline from its base: points, arc length, radius. */
typedef struct Path {
    double p[SEG1_MAX + 1][3];
    double s[SEG1_MAX + 1], r[SEG1_MAX + 1];
    int n;
    double len;
} Path;

/* A branch to be written: its path and where on its parent it grows. */
typedef struct Branch {
    Path path;
    double at;  /* arc length on the parent */
    Rng rng;    /* its own stream, for its children and leaves */
} Branch;

typedef struct Ct {
    const CtParams *P;
    CtInside inside;
    void *user;
    SylSkeleton *sk;
    uint64_t seed;
    double trunk_len, seg1, leaf_w, leaf_len;
    int leaves; /* per branch */
    bool failed;
} Ct;

static double gauss(Rng *r, double mean) { return mean + 0.1 * fabs(mean) * rng_normal(r); }

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void cross(double o[3], const double a[3], const double b[3]) {
    double t[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    memcpy(o, t, sizeof t);
}
static bool normalize(double a[3]) {
    double n = sqrt(dot(a, a));
    if (!(n > 1e-300)) return false;
    a[0] /= n, a[1] /= n, a[2] /= n;
    return true;
}

/* Two unit vectors perpendicular to h and to each other (a, b, h right-handed). */
static void perp_frame(const double h[3], double a[3], double b[3]) {
    double ref[3] = {0, 1, 0};
    if (fabs(h[1]) > 0.9) ref[0] = 1, ref[1] = 0;
    double k = dot(ref, h);
    for (int j = 0; j < 3; j++) a[j] = ref[j] - k * h[j];
    normalize(a);
    cross(b, h, a);
}

/* The point, heading and radius of a path at arc length s (its pieces linear). */
static void path_at(const Path *pa, double s, double pos[3], double dir[3], double *r) {
    int k = 0;
    while (k + 2 < pa->n && pa->s[k + 1] < s) k++;
    double piece = pa->s[k + 1] - pa->s[k], t = piece > 0 ? (s - pa->s[k]) / piece : 0;
    if (t < 0) t = 0;
    if (t > 1) t = 1;
    for (int j = 0; j < 3; j++) {
        pos[j] = pa->p[k][j] + (pa->p[k + 1][j] - pa->p[k][j]) * t;
        dir[j] = pa->p[k + 1][j] - pa->p[k][j];
    }
    if (!normalize(dir)) dir[0] = 0, dir[1] = 1, dir[2] = 0;
    if (r) *r = pa->r[k + 1]; /* the piece's: a node's radius is its segment's */
}

/* ---- where children grow: on the parent's inside part, spaced by Gaussian steps ---- */

/* The inside part of a parent, as intervals of arc length (sampled every step). */
typedef struct Inside {
    double lo[64], hi[64];
    int n;
    double total;
} Inside;

static void inside_part(Ct *ct, double len, int samples, void (*at)(const void *, double, double[3]),
                        const void *parent, Inside *in) {
    in->n = 0, in->total = 0;
    bool was = false;
    for (int i = 0; i <= samples; i++) {
        double s = len * i / samples, q[3];
        at(parent, s, q);
        bool is = ct->inside(ct->user, q);
        if (is && !was && in->n < 64) in->lo[in->n] = s, in->hi[in->n] = s, in->n++;
        if (is && in->n) in->hi[in->n - 1] = s;
        was = is;
    }
    for (int i = 0; i < in->n; i++) in->total += in->hi[i] - in->lo[i];
}

/* The arc length of the u-th unit of usable length. */
static double usable_to_arc(const Inside *in, double u) {
    for (int i = 0; i < in->n; i++) {
        double w = in->hi[i] - in->lo[i];
        if (u <= w) return in->lo[i] + u;
        u -= w;
    }
    return -1;
}

/* ---- growing one branch ---- */

/* Rotate v about the unit axis k by angle a. */
static void rotate(double v[3], const double k[3], double a) {
    double c = cos(a), s = sin(a), kv[3], d = dot(k, v);
    cross(kv, k, v);
    for (int j = 0; j < 3; j++) v[j] = v[j] * c + kv[j] * s + k[j] * d * (1 - c);
}

/* Grow a branch from base (on the parent, heading hp, radius rp there): the k-th of its
 * parent's children (the quadrant spiral), segments of seg, at most nmax of them, each end
 * inside the envelope (the last one shortened until it is). false: not even a piece fits. */
static bool grow(Ct *ct, Rng *rng, const double base[3], const double hp[3], double rp, int quadrant, double width,
                 double seg, int nmax, Path *out) {
    const CtParams *P = ct->P;
    double a[3], b[3], dir[3], axis[3];
    perp_frame(hp, a, b);
    double phi = (quadrant % 4) * (PI / 2) + rng_unit(rng) * (PI / 2); /* a random angle in the next quadrant */
    double radial[3];
    for (int j = 0; j < 3; j++) radial[j] = cos(phi) * a[j] + sin(phi) * b[j];
    double theta = gauss(rng, (90 - 72 * P->branchAngle) * DEG); /* from the parent's axis */
    for (int j = 0; j < 3; j++) dir[j] = cos(theta) * hp[j] + sin(theta) * radial[j];
    normalize(dir);
    cross(axis, dir, hp); /* bending turns dir toward the parent's heading */
    bool bends = normalize(axis);
    double rb = gauss(rng, rp * width / 2); /* Eq. (5): the parent's width x branchWidth / 2 */
    if (rb > rp) rb = rp;
    if (rb < 0) rb = 0;
    memcpy(out->p[0], base, sizeof out->p[0]);
    out->s[0] = 0, out->n = 1;
    double bend_nominal = 45 * DEG * P->branchCurvature;
    for (int k = 1; k <= nmax; k++) {
        if (k > 1 && bends && bend_nominal > 0) {
            double bend = gauss(rng, bend_nominal), left = acos(fmax(-1, fmin(1, dot(dir, hp))));
            rotate(dir, axis, bend < left ? bend : left); /* never past the parent's heading */
        }
        double q[3], lo = 0, hi = 1;
        for (int j = 0; j < 3; j++) q[j] = out->p[k - 1][j] + seg * dir[j];
        if (!ct->inside(ct->user, q)) { /* shortened until it fits */
            for (int it = 0; it < FIT_STEPS; it++) {
                double t = (lo + hi) / 2, m[3];
                for (int j = 0; j < 3; j++) m[j] = out->p[k - 1][j] + t * seg * dir[j];
                if (ct->inside(ct->user, m)) lo = t; else hi = t;
            }
            if (lo < 1.0 / 16) break;
            for (int j = 0; j < 3; j++) q[j] = out->p[k - 1][j] + lo * seg * dir[j];
        }
        memcpy(out->p[k], q, sizeof q);
        out->s[k] = out->s[k - 1] + (lo < hi && hi < 1 ? lo : 1) * seg;
        out->n = k + 1;
        if (hi < 1) break;
    }
    if (out->n < 2) return false;
    out->len = out->s[out->n - 1];
    /* taper to 0 at the tip, each point's width Gaussian about the linear one; the first
     * segment carries the base width (a node's radius is its segment's) */
    out->r[0] = rb, out->r[1] = rb;
    for (int k = 2; k < out->n; k++) {
        double lin = rb * (1 - out->s[k - 1] / out->len), r = gauss(rng, lin);
        out->r[k] = r < 0 ? 0 : r > rb ? rb : r;
    }
    return true;
}

/* ---- writing ---- */

static int32_t put(Ct *ct, const double pos[3], const double h[3], double r, int32_t parent, int axis, int order,
                   uint8_t kind) {
    SylNode nd = {0};
    double a[3], b[3];
    perp_frame(h, a, b);
    for (int j = 0; j < 3; j++) nd.pos[j] = (float)pos[j], nd.h[j] = (float)h[j], nd.l[j] = (float)a[j];
    cross(b, h, a); /* H x L = U */
    for (int j = 0; j < 3; j++) nd.u[j] = (float)b[j];
    nd.radius = (float)r;
    nd.parent = parent;
    nd.axis = axis;
    nd.order = (uint16_t)order;
    nd.kind = kind;
    nd.material = SYL_MATERIAL_BARK;
    nd.module = (uint32_t)axis;
    int32_t k = syl_skeleton_add_node(ct->sk, &nd);
    if (k < 0) ct->failed = true;
    return k;
}

static int cmp_at(const void *a, const void *b) {
    double x = ((const Branch *)a)->at, y = ((const Branch *)b)->at;
    return x < y ? -1 : x > y;
}

/* A path's nodes after its base node, with a node wherever a child grows (children sorted by
 * at): child_node[i] receives the node child i grows from. Returns the path's nodes' first
 * index (its first node after the base), or -1. */
static int32_t write_path(Ct *ct, const Path *pa, int32_t base, int axis, int order, const Branch *kids, int nk,
                          int32_t *kid_node, int32_t *node_of_point) {
    int32_t last = base, first = -1;
    int c = 0;
    for (; c < nk && kids[c].at <= 0; c++) kid_node[c] = base;
    for (int k = 1; k < pa->n && !ct->failed; k++) {
        double h[3];
        for (int j = 0; j < 3; j++) h[j] = pa->p[k][j] - pa->p[k - 1][j];
        if (!normalize(h)) h[0] = 0, h[1] = 1, h[2] = 0;
        for (; c < nk && kids[c].at < pa->s[k]; c++) {
            double q[3], d[3], r;
            path_at(pa, kids[c].at, q, d, &r);
            last = put(ct, q, h, pa->r[k], last, axis, order, SYL_KIND_INTERNODE);
            if (first < 0) first = last;
            kid_node[c] = last;
        }
        last = put(ct, pa->p[k], h, pa->r[k], last, axis, order, SYL_KIND_INTERNODE);
        if (first < 0) first = last;
        if (node_of_point) node_of_point[k] = last;
        for (; c < nk && kids[c].at <= pa->s[k]; c++) kid_node[c] = last;
    }
    for (; c < nk; c++) kid_node[c] = last;
    return first;
}

int ct_leaves_per_branch(double density) {
    if (!(density > 0)) return 0;
    int n = 0;
    double u = 0, step = 0.1 / density; /* in lengths of the branch: the count is the same for every length */
    for (;;) {
        u += step;
        if (!(u < 1)) break;
        n++;
        step = step * 19 / 20;
        if (step < 1.0 / 30) step = 1.0 / 30;
    }
    return n;
}

/* The branch's leaves at the step rule's places, each on the node that ends its piece. */
static void leaves(Ct *ct, const Path *pa, const int32_t *node_of_point, Rng *rng) {
    double u = 0, step = 0.1 / ct->P->leavesDensity;
    for (int i = 0; i < ct->leaves && !ct->failed; i++) {
        u += step;
        step = step * 19 / 20;
        if (step < 1.0 / 30) step = 1.0 / 30;
        double s = u * pa->len, pos[3], h[3], r, a[3], b[3], radial[3], d[3], l0[3], l[3], up[3];
        path_at(pa, s, pos, h, &r);
        int k = 1;
        while (k + 1 < pa->n && pa->s[k] < s) k++;
        perp_frame(h, a, b);
        double psi = 2 * PI * rng_unit(rng), alpha = (18 + 54 * rng_unit(rng)) * DEG, zeta = 2 * PI * rng_unit(rng);
        for (int j = 0; j < 3; j++) radial[j] = cos(psi) * a[j] + sin(psi) * b[j];
        for (int j = 0; j < 3; j++) d[j] = cos(alpha) * h[j] + sin(alpha) * radial[j], pos[j] += r * radial[j];
        normalize(d);
        cross(l0, d, radial);
        normalize(l0);
        cross(up, d, l0);
        for (int j = 0; j < 3; j++) l[j] = cos(zeta) * l0[j] + sin(zeta) * up[j];
        cross(up, d, l);
        SylOrgan o = {0};
        for (int j = 0; j < 3; j++)
            o.pos[j] = (float)pos[j], o.h[j] = (float)d[j], o.l[j] = (float)l[j], o.u[j] = (float)up[j];
        o.size = (float)ct->leaf_len;
        o.node = node_of_point[k];
        o.kind = SYL_KIND_LEAF;
        o.material = SYL_MATERIAL_LEAF;
        if (syl_skeleton_add_organ(ct->sk, &o) < 0) ct->failed = true;
    }
}

typedef struct PathRef {
    const Path *pa;
} PathRef;
static void path_point(const void *u, double s, double q[3]) {
    double d[3];
    path_at(((const PathRef *)u)->pa, s, q, d, NULL);
}
static void curve_point(const void *u, double s, double q[3]) {
    double d[3];
    ct_curve_at(u, s, q, d);
}

/* Second-level children of a branch: count of them (Eq. 4 scaled by its length), placed on its
 * inside part by Gaussian steps, each grown. Returns how many grew (into kids, sorted by place). */
static int children(Ct *ct, const Path *pa, int count, int level, Rng *rng, Branch *kids) {
    if (count <= 0) return 0;
    Inside in;
    PathRef ref = {pa};
    inside_part(ct, pa->len, 4 * (pa->n - 1), path_point, &ref, &in); /* its points are inside: 4 a segment */
    if (!(in.total > 0)) return 0;
    double avg = in.total / count, u = 0;
    int quadrant = (int)(rng_unit(rng) * 4), made = 0;
    const CtParams *P = ct->P;
    for (int i = 0; i < count; i++) {
        u += gauss(rng, avg);
        double s = usable_to_arc(&in, u);
        if (s < 0) break;
        Branch *k = &kids[made];
        k->rng = rng_stream(ct->seed, (uint64_t)level, (uint64_t)made, rng_next(rng));
        double base[3], hp[3], rp;
        path_at(pa, s, base, hp, &rp);
        double width = level == 1 ? P->branch1Width : P->branch2Width;
        double seg = level == 1 ? ct->seg1 : P->branch2Len * pa->len / 8;
        quadrant++;
        if (!(seg > 0) || !grow(ct, &k->rng, base, hp, rp, quadrant, width, seg, level == 1 ? SEG1_MAX : SEG2_MAX,
                                &k->path))
            continue;
        k->at = s;
        made++;
    }
    qsort(kids, (size_t)made, sizeof *kids, cmp_at);
    return made;
}

static int round_count(double x) { return x > 0 ? (int)floor(x + 0.5) : 0; }

void ct_bounds(const CtParams *P, const CtCurve *trunk, uint64_t *nodes, uint64_t *leaves) {
    uint64_t n1 = (uint64_t)round_count(10 * P->branch1Density * P->branch1Density);
    uint64_t n2 = n1 * (uint64_t)round_count(10 * P->branch2Density * P->branch2Density);
    *nodes = (uint64_t)trunk->n + n1 + n1 * (2 * SEG1_MAX + 1) + n2 * (SEG2_MAX + 1);
    *leaves = (n1 + n2) * (uint64_t)ct_leaves_per_branch(P->leavesDensity);
}

int ct_build(const CtParams *P, const CtCurve *trunk, CtInside inside, void *inside_user, double leaf_aspect,
             uint64_t seed, SylSkeleton *sk, const SylCancel *cancel) {
    Ct ct = {.P = P, .inside = inside, .user = inside_user, .sk = sk, .seed = seed};
    ct.trunk_len = trunk->length;
    ct.seg1 = trunk->length / 16;
    ct.leaves = ct_leaves_per_branch(P->leavesDensity);
    Rng rng = rng_stream(seed, 0, 0, 0);
    uint64_t most_nodes, most_leaves; /* reserved at once (counted by the caller's budget): no doubling series */
    ct_bounds(P, trunk, &most_nodes, &most_leaves);
    if (!skeleton_reserve_nodes(sk, sk->nnodes + most_nodes) ||
        (most_leaves && !skeleton_reserve_organs(sk, sk->norgans + most_leaves)))
        return SYL_ELIMIT;
    /* the trunk: Eq. (3), width = length / 10 x trunkWidth at the base, linear to trunkEndWidth
     * of it at the top, each control point's width Gaussian about the linear one */
    double r0 = trunk->length / 10 * P->trunkWidth / 2, r1 = r0 * P->trunkEndWidth;
    double *rc = malloc((size_t)trunk->nctrl * sizeof *rc);
    int n1 = round_count(10 * P->branch1Density * P->branch1Density);
    Branch *b1 = pages_owned((size_t)(n1 ? n1 : 1) * sizeof *b1, PAGES_OWNED_SCRATCH); /* 1.3 KB a branch, each written */
    int32_t *b1_node = malloc((size_t)(n1 ? n1 : 1) * sizeof *b1_node);
    int n2max = round_count(10 * P->branch2Density * P->branch2Density);
    Branch *b2 = malloc((size_t)(n2max ? n2max : 1) * sizeof *b2);
    int32_t *b2_node = malloc((size_t)(n2max ? n2max : 1) * sizeof *b2_node);
    if (!rc || !b1 || !b1_node || !b2 || !b2_node) {
        free(rc), free(b1), free(b1_node), free(b2), free(b2_node);
        return SYL_ELIMIT;
    }
    for (int i = 0; i < trunk->nctrl; i++) {
        double t = trunk->s[trunk->ctrl[i]] / trunk->length, r = gauss(&rng, r0 + (r1 - r0) * t);
        rc[i] = r > 0 ? r : 0;
    }
    double rmax = 0;
    for (int i = 0; i < trunk->nctrl; i++) rmax = fmax(rmax, rc[i]);
    /* leaf width from the trunk's largest radius and leavesSize (Eq. 7), length by the aspect */
    ct.leaf_w = rmax * P->leavesSize / 2;
    ct.leaf_len = ct.leaf_w * leaf_aspect;
    /* the trunk's radius at a point of its dense polyline: linear between control points */
    double *tr = malloc((size_t)trunk->n * sizeof *tr);
    if (!tr) {
        free(rc), free(b1), free(b1_node), free(b2), free(b2_node);
        return SYL_ELIMIT;
    }
    for (int i = 0, c = 0; i < trunk->n; i++) {
        while (c + 1 < trunk->nctrl - 1 && trunk->ctrl[c + 1] <= i) c++;
        double s0 = trunk->s[trunk->ctrl[c]], s1 = trunk->s[trunk->ctrl[c + 1]];
        double t = s1 > s0 ? (trunk->s[i] - s0) / (s1 - s0) : 0;
        tr[i] = rc[c] + (rc[c + 1] - rc[c]) * (t < 0 ? 0 : t > 1 ? 1 : t);
    }
    /* first-level branches, placed on the curve itself (the dense polyline is longer than a
     * branch's Path) */
    int made1 = 0;
    {
        Inside in;
        inside_part(&ct, trunk->length, 256, curve_point, trunk, &in);
        double avg = n1 ? in.total / n1 : 0, u = 0;
        int quadrant = (int)(rng_unit(&rng) * 4);
        for (int i = 0; i < n1 && in.total > 0; i++) {
            u += gauss(&rng, avg);
            double s = usable_to_arc(&in, u);
            if (s < 0) break;
            double base[3], hp[3];
            int k = ct_curve_at(trunk, s, base, hp);
            double piece = trunk->s[k + 1] - trunk->s[k], t = piece > 0 ? (s - trunk->s[k]) / piece : 0;
            double rp = tr[k] + (tr[k + 1] - tr[k]) * t;
            Branch *br = &b1[made1];
            br->rng = rng_stream(seed, 1, (uint64_t)i, 0);
            quadrant++;
            if (!grow(&ct, &br->rng, base, hp, rp, quadrant, P->branch1Width, ct.seg1, SEG1_MAX, &br->path)) continue;
            br->at = s;
            made1++;
        }
    }
    /* the trunk's nodes: a root, each point of the dense polyline, a node at each branch */
    bool stopped = syl_cancelled(cancel); /* asked before the trunk's nodes, then each branch's */
    ct.failed = ct.failed || stopped;
    double pos0[3], h0[3];
    ct_curve_at(trunk, 0, pos0, h0);
    int32_t last = put(&ct, trunk->p[0], h0, tr[0], -1, 0, 0, SYL_KIND_ROOT);
    int c = 0;
    for (int i = 1; i < trunk->n && !ct.failed; i++) {
        double h[3];
        for (int j = 0; j < 3; j++) h[j] = trunk->p[i][j] - trunk->p[i - 1][j];
        if (!normalize(h)) continue; /* a repeated point */
        for (; c < made1 && b1[c].at < trunk->s[i]; c++) {
            double q[3], d[3];
            ct_curve_at(trunk, b1[c].at, q, d);
            double piece = trunk->s[i] - trunk->s[i - 1], t = piece > 0 ? (b1[c].at - trunk->s[i - 1]) / piece : 0;
            last = put(&ct, q, h, tr[i - 1] + (tr[i] - tr[i - 1]) * t, last, 0, 0, SYL_KIND_INTERNODE);
            b1_node[c] = last;
        }
        last = put(&ct, trunk->p[i], h, tr[i], last, 0, 0, SYL_KIND_INTERNODE);
        for (; c < made1 && b1[c].at <= trunk->s[i]; c++) b1_node[c] = last;
    }
    for (; c < made1; c++) b1_node[c] = last;
    /* the attachment nodes' radii are the parents' widths the branches were given (above) */
    double longest = 0;
    for (int i = 0; i < made1; i++) longest = fmax(longest, b1[i].path.len);
    int axis = 1;
    for (int i = 0; i < made1 && !ct.failed; i++) {
        if (syl_cancelled(cancel)) {
            stopped = ct.failed = true;
            break;
        }
        const Path *pa = &b1[i].path;
        int count = longest > 0 ? round_count(n2max * pa->len / longest) : 0;
        int made2 = children(&ct, pa, count, 2, &b1[i].rng, b2);
        int32_t node_of_point[SEG1_MAX + 1];
        write_path(&ct, pa, b1_node[i], axis++, 1, b2, made2, b2_node, node_of_point);
        if (!ct.failed) leaves(&ct, pa, node_of_point, &b1[i].rng);
        for (int k = 0; k < made2 && !ct.failed; k++) {
            int32_t pts[SEG1_MAX + 1];
            write_path(&ct, &b2[k].path, b2_node[k], axis++, 2, NULL, 0, NULL, pts);
            if (!ct.failed) leaves(&ct, &b2[k].path, pts, &b2[k].rng);
        }
    }
    if (sk->norgans && sk->nmaterials < SYL_MATERIAL_LEAF + 1) sk->nmaterials = SYL_MATERIAL_LEAF + 1;
    sk->materials[SYL_MATERIAL_LEAF].leaf_width = (float)(1 / leaf_aspect); /* the leaves' surface */
    /* the plug-in's cross-sections: 4 x trunkRes sides around the trunk, 4 x branchRes around
     * the branches of both levels (the mesher's, when no --sides is asked for) */
    uint8_t *ring = sk->materials[SYL_MATERIAL_BARK].ring_sides; /* every stem's material */
    ring[0] = (uint8_t)(4 * lround(P->trunkRes));
    for (int o = 1; o < 4; o++) ring[o] = (uint8_t)(4 * lround(P->branchRes));
    free(rc), free(tr), free(b1), free(b1_node), free(b2), free(b2_node);
    return stopped ? SYL_ECANCELED : ct.failed ? SYL_ELIMIT : SYL_OK;
}
