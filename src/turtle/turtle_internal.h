/* The turtle's state and the operations its two readers share: the drawing turtle
 * (turtle_draw.c) and the query pass (turtle_query.c). Internal to src/turtle/. */
#ifndef SYL_TURTLE_INTERNAL_H
#define SYL_TURTLE_INTERNAL_H
#include <cglm/cglm.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "lang/program.h"
#include "lsys/modstr.h"
#include "sylva/skeleton.h"
#include "turtle/frame.h"
#include "turtle/turtle.h"

/* The loops test ranges of commands: the six turns follow each other, the queries come last. */
_Static_assert(TC_RIGHT == TC_LEFT + 1 && TC_DOWN == TC_LEFT + 2 && TC_UP == TC_LEFT + 3 &&
                   TC_ROLL_LEFT == TC_LEFT + 4 && TC_ROLL_RIGHT == TC_LEFT + 5,
               "the turns in a row");
_Static_assert(TC_QUERY_P + 5 == TC_COUNT, "the queries last");

/* A turn's angle, its sine and cosine. Rules turn by a few angles (the model's, constants of
 * the rules), so a small cache keyed by the angle saves most sin and cos calls. */
typedef struct Angle {
    double deg;
    float sn, cs;
} Angle;
enum { ANGLE_CACHE = 16 };

/* A change of the frame not made yet (fill_queries): many are never seen, in branches that end
 * with queries that read only the position. */
typedef struct Pending {
    uint32_t op;  /* P_* */
    bool neg;     /* turn by -deg: the other way */
    double deg;   /* the angle of a turn */
} Pending;
enum { P_HL, P_UH, P_UL, P_NEGATE, P_ORTHO, P_ORTHO_LU };
enum { PENDING_MAX = 32 };

/* Everything `[` saves and `]` restores. */
typedef struct TState {
    vec3 pos, h, l, u;
    vec3 trop;        /* unit tropism direction */
    float elasticity; /* 0: no tropism */
    float width;      /* diameter, before scaling */
    float scale;      /* @D */
    int32_t node;     /* the last node on this path, -1 before the first */
    uint64_t gen;     /* nonzero: moved away from `node` without drawing (the move's number) */
    int32_t axis;
    uint16_t order;
    uint8_t material;
    bool branch;      /* after `[`, before the first segment: the next segment starts an axis */
    bool smooth;      /* inside @Gc ... @Ge */
    uint32_t dirty;   /* turns since the frame was last orthonormalised (not a char: stores
                         to it would alias everything in fill_queries) */
} TState;

typedef struct Poly {
    size_t first; /* into Turtle.verts */
} Poly;

typedef struct Turtle {
    const SylProgram *p;
    SylSkeleton *sk;
    FILE *diag;
    TState st;
    TState *stack;
    size_t depth, cap;
    Poly *polys;
    size_t npolys, polycap;
    vec3 *verts;
    size_t nverts, vertcap;
    uint64_t gens;      /* moves so far */
    int32_t axes;       /* axis ids handed out */
    double angle, step, widthfactor;
    Angle angles[ANGLE_CACHE]; /* recent angles turned by, and their sines and cosines */
    uint64_t bad;       /* modules skipped for non-finite parameters */
    SylEnvFill *env;    /* filling queries: segment ends and ?E modules are collected here */
    SylOpenFill *open;  /* for scene/open.c: light probes go here (syl_turtle_fill) */
    Pending pend[PENDING_MAX]; /* fill_queries: frame changes to make, in order */
    int npend;
    uint8_t cmd[MAX_SYMBOLS];
    bool warned[MAX_SYMBOLS];
    bool oom;
} Turtle;

/* ---- small helpers ---- */

/* Parameter k of sane size (a float can hold it), or def when absent. */
static inline double argd(const double *a, int na, int k, double def) {
    double v = k < na ? a[k] : def;
    if (v > 1e30) v = 1e30;
    if (v < -1e30) v = -1e30;
    return v;
}
static inline float arg(const double *a, int na, int k, double def) { return (float)argd(a, na, k, def); }

/* sin and cos of deg, through the cache (an entry holds the exact values of its angle). */
static inline void turn_sincos(Angle *cache, double deg, float *s, float *c) {
    uint64_t bits;
    memcpy(&bits, &deg, sizeof bits);
    Angle *e = &cache[(bits * 0x9E3779B97F4A7C15u) >> 60 & (ANGLE_CACHE - 1)];
    if (e->deg != deg) {
        turtle_sincos(deg, &e->sn, &e->cs);
        e->deg = deg;
    }
    *s = e->sn;
    *c = e->cs;
}

/* Make H, L, U orthonormal again (turtle_orthonormalise), and count the frame tidy. */
static inline void orthonormalise(TState *st) {
    turtle_orthonormalise(st->h, st->l, st->u);
    st->dirty = 0;
}

/* After a turn: float rounding builds up over many turns, so tidy up now and then. */
static inline void turned(TState *st) {
    if (++st->dirty >= TURTLE_TIDY_TURNS) orthonormalise(st);
}

/* How far a move of len goes, at the current scale. */
static inline float distance(const TState *st, float len) {
    float d = len * st->scale;
    d = d < 1e30f ? d : 1e30f; /* fminf(1e30f, d), NaN too, without a call */
    return d > -1e30f ? d : -1e30f;
}

/* The turtle moved without drawing: the next segment starts from a new root. */
static inline void detach(Turtle *t) { t->st.gen = ++t->gens; }

/* Filling queries for the environment: a segment's end, and a ?E module where it stands. */
/* What a fill keeps for the library alone (SylEnvFill.store): its arrays' room. */
struct SylEnvFillStore {
    size_t ends_cap, probes_cap;
};
/* Room for one more in an array of the fill (grown rarely: out of line). */
bool turtle_grow_fill(Turtle *t, void *arrp, size_t *cap, size_t n, size_t size);

static inline void env_end(Turtle *t, const float pos[3]) {
    SylEnvFill *f = t->env;
    if (f->nends == f->store->ends_cap && !turtle_grow_fill(t, &f->ends, &f->store->ends_cap, f->nends, sizeof *f->ends)) return;
    memcpy(f->ends[f->nends++], pos, 3 * sizeof(float));
}

static inline void env_probe(Turtle *t, size_t par, int na, bool heading) {
    SylEnvFill *f = t->env;
    if (f->nprobes == f->store->probes_cap && !turtle_grow_fill(t, &f->probes, &f->store->probes_cap, f->nprobes, sizeof *f->probes)) return;
    SylEnvProbe *q = &f->probes[f->nprobes++];
    memcpy(q->pos, t->st.pos, sizeof q->pos);
    if (heading) memcpy(q->h, t->st.h, sizeof q->h);
    else memset(q->h, 0, sizeof q->h);
    q->par = par;
    q->na = na;
    q->tip = t->st.gen == 0;
}

/* `[`: save the state (the stack grows out of line, rarely). */
bool turtle_grow_stack(Turtle *t);
static inline void push(Turtle *t) {
    if (t->depth == t->cap && !turtle_grow_stack(t)) return;
    t->stack[t->depth++] = t->st;
    t->st.branch = true;
}

static inline void pop(Turtle *t) {
    if (t->depth) t->st = t->stack[--t->depth];
}

/* ---- turtle_frame.c ---- */

/* ABOP §2.2: bend H toward T by e |H x T|, carrying L and U along (none without elasticity). */
void turtle_tropism(TState *st);
/* @Tp(x, y, z[, e]): the tropism's direction (zero: none) and its elasticity. */
void turtle_set_tropism(TState *st, const double *a, int na);
/* @R(hx, hy, hz[, ux, uy, uz]): the heading, and the up vector. */
void turtle_set_heading(Turtle *t, const double *a, int na);
/* `$`: roll about H so that L is horizontal. */
void turtle_level(TState *st);
/* Index of the `]` closing the branch module i is in (n when i is on the main axis); *off is
 * advanced past the parameters of the skipped modules. */
size_t turtle_branch_end(const SylString *s, size_t i, size_t *off);
/* The start: the program's settings, each symbol's command; sk NULL when filling queries. */
void turtle_init(Turtle *t, const SylProgram *p, SylSkeleton *sk, FILE *diag);
void turtle_release(Turtle *t);
/* The value of one query module (?P, ?H, ?L, ?U): position or a frame vector. */
void turtle_query_value(const TState *st, TurtleCommand c, double *out, int na);

#endif
