/* The Weber–Penn generator's shared state. Coordinates here are the paper's and Arbaro's:
 * z up; the skeleton writer turns them into Sylva's Y-up frame at the end. */
#ifndef WEBER_INTERNAL_H
#define WEBER_INTERNAL_H
#include <math.h>
#include <stdbool.h>
#include <stdint.h>

#include "sylva/skeleton.h"
#include "env/obstacles.h"
#include "util/arena.h"
#include "util/budget.h"
#include "util/rng.h"
#include "weber/params.h"

/* A frame: the local axes x, y, z (z along the stem) in tree coordinates, and its origin t. */
typedef struct Frame {
    double x[3], y[3], z[3], t[3];
} Frame;

/* Stems below these are not made (Arbaro's limits: its mesher breaks below them). */
#define WEBER_MIN_LEN 1e-5
#define WEBER_MIN_RADIUS (WEBER_MIN_LEN / 10)

typedef struct WStem { /* (fields ordered so that it has no padding: 240 bytes, not 256) */
    Frame start;       /* the base of its first segment */
    uint64_t key;      /* names its random streams: (parent's key, child or clone number) */
    int from;          /* the stem it grows out of: its parent, or for a clone the stem it split from */
    int parent;        /* the stem whose child it is (a clone's is its origin's); -1 for a trunk */
    int nseg, first_seg; /* CurveRes; a clone starts at first_seg */
    int sap_main;      /* SaplingLaw: the even places along it (and its clones) children take */
    int16_t level;
    bool clone;
    bool split_last;   /* SaplingLaw: its last segment split (Sapling's odds depend on it) */
    double offset;     /* from the parent's base (a clone: its origin's offset) */
    double length, seglen, base_radius;
    double lcm;        /* most length of a child, relative (drawn once per stem) */
    double split_corr; /* turn per segment that straightens a split out again */
    double sps, lps;   /* children and leaves per segment */
    double rot;        /* the last child's rotation angle */
    double sap_n;      /* SaplingLaw: its children before the bare base's share */
    double u_length, u_lcm; /* the first trunk's draws for its length and its children's, when
                             * they come from Arbaro's streams (else negative) */
    uint32_t pt_first, pt_count;
    uint32_t node_first, node_count; /* its own nodes in the skeleton (write.c) */
} WStem;
_Static_assert(sizeof(WStem) == 240, "WStem: padding crept in (it is copied and stored per stem)");

/* A point of a stem's axis: segment ends and the sub-sections of flare, rounded ends, beads
 * and helices. */
typedef struct WPoint {
    float pos[3], z[3], x[3];
    float r, dist;     /* radius there; distance from the stem's base */
} WPoint;


typedef struct WSeg {  /* one segment while its stem is made */
    Frame f;           /* at its base */
    double sps;        /* children per segment there (splits divide it) */
} WSeg;

/* `envelope "crown.obj"`: a closed mesh stems are pruned to (Sylva's coordinates). */
typedef struct WeberEnvelope {
    Obstacles obs;
    RTCDevice dev;
} WeberEnvelope;

typedef struct WeberGen {
    WeberParams w;
    int levels;        /* stem levels made (the block's, or fewer) */
    int leaves;        /* Leaves, or 0 when levels were cut */
    uint64_t seed;
    double scale_tree;
    double leaf_len, leaf_width;
    WStem *stems;
    size_t nstems, stems_cap;
    WPoint *pts;
    size_t npts, pts_cap;
    SylOrgan *lvs;     /* the leaves, in Sylva's coordinates, in the skeleton's order */
    size_t nlvs, lvs_cap;
    float *node_dist;  /* each skeleton node's distance along its stem (for the leaves' nodes) */
    size_t node_dist_cap;
    /* The last level's stems, in the order their leaves come, and their segments' frames
     * (from each one's first_seg): the leaves are made after the stems and their nodes,
     * once their count is known, so their array is filled once and never copied. */
    int *leafy;
    size_t nleafy, leafy_cap;
    Frame *leafy_f;
    size_t nleafy_f, leafy_f_cap;
    double sub_err[10], split_err[10], leaf_err; /* error diffusion, per level (Arbaro's) */
    /* the arrays above (not lvs) packed in one fixed arena (util/arena.h) sized from the
     * tree's estimate, in huge pages: they cost the 2 MB pages they reach, not a page (and
     * its rounding) each, and are never moved (weber.c sizes them) */
    Arena arena;
    Budget *budget;
    uint64_t charged;
    bool failed;       /* out of memory or budget, or stopped (cancelled) */
    bool cancelled;    /* the caller's cancel asked to stop (failed set too, so that every loop ends) */
    const SylCancel *cancel;
    const WeberEnvelope *envelope;
} WeberGen;

enum { WRNG_SELF, WRNG_SHAPE, WRNG_KIDS, WRNG_SCALE0, WRNG_PLACES, WRNG_FORK };
static inline Rng weber_rng(const WeberGen *g, uint64_t key, int table) { return rng_stream(g->seed, key, (uint64_t)table, 0); }
/* Arbaro's var(v): uniform in [-v, v]. */
static inline double weber_var(Rng *r, double v) { return v * (2 * rng_unit(r) - 1); }
static inline uint64_t weber_key(uint64_t parent, uint64_t kind, uint64_t n) { return rng_mix(parent * 0x9e3779b97f4a7c15ull ^ (kind << 48) ^ n); }

/* arbaro_rng.c: java.util.Random, for Arbaro's tree size */
typedef struct JRand {
    uint64_t s;
} JRand;
void jrand_seed(JRand *r, int64_t seed);
int64_t jrand_long(JRand *r);
double jrand_double(JRand *r);
void jrand_tree(int64_t seed, JRand *level0, JRand *level1);

/* frame.c */
void frame_identity(Frame *f);
void frame_rot_global(Frame *f, const double axis[3], double deg);   /* about a tree axis */
void frame_rot_local(Frame *f, double ax, double ay, double az, double deg); /* about a local axis */
void frame_rotxz(Frame *f, double down, double rot);  /* about local z by rot, then the new x by down */
void frame_move(Frame *f, double d);                  /* along its z */
/* the same turns by an angle's cosine c and sine s: about the frame's x (y toward z), its z
 * (x toward y), and the tree's vertical (inline: a leaf makes four) */
static inline void frame_turn(double a[3], double b[3], double c, double s) { /* a toward b */
    for (int i = 0; i < 3; i++) {
        double p = a[i], q = b[i];
        a[i] = c * p + s * q;
        b[i] = c * q - s * p;
    }
}
static inline void frame_turn_x(Frame *f, double c, double s) { frame_turn(f->y, f->z, c, s); }
static inline void frame_turn_z(Frame *f, double c, double s) { frame_turn(f->x, f->y, c, s); }
static inline void frame_turn_vertical(Frame *f, double c, double s) {
    double *v[3] = {f->x, f->y, f->z};
    for (int k = 0; k < 3; k++) {
        double x = v[k][0], y = v[k][1];
        v[k][0] = c * x - s * y;
        v[k][1] = s * x + c * y;
    }
}

/* shape.c */
double weber_shape_ratio(const WeberParams *w, int shape, double r);

/* radius.c */
double weber_stem_length(WeberGen *g, const WStem *s, Rng *self);
double weber_base_radius(const WeberGen *g, const WStem *s);
double weber_radius(const WeberGen *g, const WStem *s, double h);

/* stem.c */
bool weber_make_stem(WeberGen *g, WStem st);
/* Asks the caller's cancel (once it said stop, again true without asking): see WeberGen.cancelled */
bool weber_stop(WeberGen *g);
int weber_trace(WeberGen *g, WStem *st, int s0, Frame trf, bool test, WSeg *segs);
/* grow one of the generator's arrays (in the arena, or util/pages.h's: cap * size bytes) */
bool weber_grow(WeberGen *g, void **arr, size_t *cap, size_t need, size_t size);
void weber_free(WeberGen *g, void *arr, size_t bytes); /* one of them */
/* its room past n given back to the arena, when it is the last array there */
void weber_trim(WeberGen *g, void *arr, size_t *cap, size_t n, size_t size);
/* the stems, points and leafy stems' arrays packed against each other (their room unused
 * given back) when the tree then reaches fewer 2 MB pages; later: the bytes taken after them */
void weber_pack(WeberGen *g, size_t later);
/* scratch for a while: from the arena while it has room, else malloc; weber_drop gives it
 * back (to the arena whole when it was the last taken) */
void *weber_take(WeberGen *g, size_t bytes);
/* an array the skeleton keeps (its nodes, its organs): from the arena while it has room,
 * whose pages then go to the skeleton (free_gen), else pages_owned */
void *weber_keep(WeberGen *g, size_t bytes);
void weber_drop(WeberGen *g, void *p, size_t bytes);

/* splits.c */
int weber_split_count(WeberGen *g, const WStem *st, int seg);
int weber_sapling_splits(WeberGen *g, const WStem *st, int seg, Rng *r);
double weber_sapling_most(const WeberGen *g, const WStem *st);
double weber_sapling_shape(const WeberParams *w, int shape, double r);
double weber_sapling_length(const WeberGen *g, const WStem *p, const WStem *s);
void weber_tip_child(WeberGen *g, int id, WStem *st, const WSeg *segs, Rng *kids);
void weber_sapling_children(WeberGen *g, int id, WStem *st, const WSeg *segs, Rng *kids);
void weber_sapling_child(WeberGen *g, int id, WStem *st, const WSeg *segs, double at, int a, Rng *kids);
size_t weber_sapling_trunk_places(const WeberParams *w, Rng *r, double *out);
double weber_step(const WeberGen *g, const WStem *st, const Frame *f);
void weber_sapling_fork(const WeberGen *g, const WStem *from, WStem *c, const Frame *f);
Frame weber_split(WeberGen *g, WStem *st, Rng *r, Frame trf, double s_angle, int seg, int nsplits, bool test);

/* children.c */
void weber_children(WeberGen *g, int id, WStem *st, int seg, const WSeg *segs, Rng *kids);
Frame weber_child_direction(WeberGen *g, WStem *st, Frame trf, double offset, int child_level, Rng *kids);
/* its down and rotation angles (degrees), the stem's rotation advanced */
static inline void weber_child_angles(WeberGen *g, WStem *st, double offset, int child_level, Rng *kids,
                                      double *down_out, double *rot_out) { /* (inline: every leaf) */
    const WeberParams *w = &g->w;
    int cl = weber_lv(child_level);
    double rot;
    if (w->Rotate[cl] >= 0) { /* a spiral */
        double a = st->rot + w->Rotate[cl] + weber_var(kids, w->RotateV[cl]) + 360;
        /* fmod's value, without its call when one subtraction gives it (exact there: Sterbenz) */
        st->rot = a >= 0 && a < 360 ? a : a >= 360 && a < 720 ? a - 360 : a >= 720 && a < 1080 ? a - 720 : fmod(a, 360);
        rot = st->rot;
    } else { /* alternate sides */
        if (fabs(st->rot) != 1) st->rot = 1;
        st->rot = -st->rot;
        rot = st->rot * (180 + w->Rotate[cl] + weber_var(kids, w->RotateV[cl]));
    }
    double down;
    if (w->DownAngleV[cl] >= 0 || st->level < 0) { /* (trunks: always so) */
        down = w->DownAngle[cl] + weber_var(kids, w->DownAngleV[cl]);
    } else { /* lower children hang lower */
        double len = st->level == 0 ? st->length * (1 - w->BaseSize) : st->length;
        down = w->DownAngle[cl] + w->DownAngleV[cl] * (1 - 2 * weber_shape_ratio(w, 0, (st->length - offset) / len));
    }
    *down_out = down, *rot_out = rot;
}

/* leaves.c */
double weber_leaves_per_stem(const WeberGen *g, const WStem *st);
bool weber_defer_leaves(WeberGen *g, int id, const WStem *st, const WSeg *segs); /* a last-level stem */
size_t weber_count_leaves(WeberGen *g); /* how many leaves weber_place_leaves will make */
void weber_place_leaves(WeberGen *g, size_t count); /* every deferred stem's leaves */

/* prune.c */
bool weber_inside(const WeberGen *g, const double p[3]);
/* bad: the segment where the stem as it is leaves the envelope, when known (else -1: traced) */
void weber_prune(WeberGen *g, WStem *st, int bad);

/* write.c: the stems' nodes, then (after weber_place_leaves) the leaves as organs */
int weber_write_nodes(WeberGen *g, SylSkeleton *sk);
int32_t weber_leaf_node(const WeberGen *g, int id, float dist); /* the node a leaf hangs from */
void weber_write_leaves(WeberGen *g, SylSkeleton *sk);

#endif
