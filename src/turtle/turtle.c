/* The 3D turtle: reads a module string and emits a Skeleton. docs/turtle.md describes every
 * symbol; LANGUAGE.md §5 is the contract.
 *
 * The compiler resolves each symbol into a turtle command once (lang/turtle_commands.h), so
 * reading a module is one table look-up and one switch. The state is kept in floats (cglm); turns by multiples
 * of 90 degrees are exact, and the frame is re-orthonormalised before it is used after a turn. */
#include <cglm/cglm.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "lang/program.h"
#include "lsys/modstr.h"
#include "sylva/skeleton.h"
#include "turtle.h"
#include "util/array.h"
#include "util/budget.h"

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

/* A change of the frame not made yet (run_query): many are never seen, in branches that end
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
                         to it would alias everything in run_query) */
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
    SylOpenFill *open;  /* for env/open.c: light probes go here (syl_turtle_fill) */
    Pending pend[PENDING_MAX]; /* run_query: frame changes to make, in order */
    int npend;
    uint8_t cmd[MAX_SYMBOLS];
    bool warned[MAX_SYMBOLS];
    bool oom;
} Turtle;

/* ---- small helpers ---- */

static const vec3 vertical = {0, 1, 0};

/* Parameter k of sane size (a float can hold it), or def when absent. */
static inline double argd(const double *a, int na, int k, double def) {
    double v = k < na ? a[k] : def;
    if (v > 1e30) v = 1e30;
    if (v < -1e30) v = -1e30;
    return v;
}
static inline float arg(const double *a, int na, int k, double def) { return (float)argd(a, na, k, def); }

/* sin and cos of an angle in degrees, exact at multiples of 90. */
static void sincos_exact(double deg, float *s, float *c) {
    double r = fmod(deg, 360.0);
    if (r < 0) r += 360.0;
    if (r == 0 || r == 90 || r == 180 || r == 270) {
        static const float sn[4] = {0, 1, 0, -1}, cs[4] = {1, 0, -1, 0};
        int q = (int)(r / 90);
        *s = sn[q];
        *c = cs[q];
        return;
    }
    double rad = r * (GLM_PI / 180.0);
    *s = (float)sin(rad);
    *c = (float)cos(rad);
}

/* sin and cos of deg, through the cache (an entry holds the exact values of its angle). */
static inline void turn_sincos(Angle *cache, double deg, float *s, float *c) {
    uint64_t bits;
    memcpy(&bits, &deg, sizeof bits);
    Angle *e = &cache[(bits * 0x9E3779B97F4A7C15u) >> 60 & (ANGLE_CACHE - 1)];
    if (e->deg != deg) {
        sincos_exact(deg, &e->sn, &e->cs);
        e->deg = deg;
    }
    *s = e->sn;
    *c = e->cs;
}

/* Rotate the pair (a, b) in its plane: a' = a cos + b sin, b' = b cos - a sin. */
static inline __attribute__((always_inline)) void rotate_pair(vec3 a, vec3 b, float s, float c) {
    vec3 a2, b2;
    glm_vec3_scale(a, c, a2);
    glm_vec3_muladds(b, s, a2);
    glm_vec3_scale(b, c, b2);
    glm_vec3_muladds(a, -s, b2);
    glm_vec3_copy(a2, a);
    glm_vec3_copy(b2, b);
}

/* Make H, L, U orthonormal again, keeping H's direction and L's plane. */
static void orthonormalise(TState *st) {
    glm_vec3_normalize(st->h);
    glm_vec3_muladds(st->h, -glm_vec3_dot(st->l, st->h), st->l);
    glm_vec3_normalize(st->l);
    glm_vec3_cross(st->h, st->l, st->u);
    st->dirty = 0;
}

/* orthonormalise() in two halves, for run_query: H first, then L and U from it. */
static void orthonormalise_lu(TState *st) {
    glm_vec3_muladds(st->h, -glm_vec3_dot(st->l, st->h), st->l);
    glm_vec3_normalize(st->l);
    glm_vec3_cross(st->h, st->l, st->u);
}

/* After a turn: float rounding builds up over many turns, so tidy up now and then. */
static inline void turned(TState *st) {
    if (++st->dirty >= 32) orthonormalise(st);
}

/* Turn the frame so that H points along h (unit), by the smallest rotation. */
static void aim(TState *st, vec3 h) {
    vec3 axis;
    glm_vec3_cross(st->h, h, axis);
    float sn = glm_vec3_norm(axis), cs = glm_vec3_dot(st->h, h);
    if (sn < 1e-7f) {
        if (cs < 0) { /* opposite: half a turn about U */
            glm_vec3_negate(st->h);
            glm_vec3_negate(st->l);
        }
        return;
    }
    float a = atan2f(sn, cs);
    glm_vec3_rotate(st->h, a, axis);
    glm_vec3_rotate(st->l, a, axis);
    glm_vec3_rotate(st->u, a, axis);
    orthonormalise(st);
}

/* ABOP §2.2: bend H toward T by e |H x T|, carrying L and U along. */
static void tropism(TState *st) {
    if (st->elasticity == 0) return;
    vec3 axis;
    glm_vec3_cross(st->h, st->trop, axis);
    float sn = glm_vec3_norm(axis);
    if (sn < 1e-7f) return;
    float a = st->elasticity * sn;
    float max = atan2f(sn, glm_vec3_dot(st->h, st->trop)); /* never past T */
    if (a > max) a = max;
    glm_vec3_rotate(st->h, a, axis);
    glm_vec3_rotate(st->l, a, axis);
    glm_vec3_rotate(st->u, a, axis);
    orthonormalise(st);
}

static void warn_once(Turtle *t, int sym, const char *what) {
    if (t->warned[sym] || !t->diag) return;
    t->warned[sym] = true;
    fprintf(t->diag, "sylva: warning: %s '%s': ignored\n", what, t->p->syms[sym].name);
}

/* ---- emitting ---- */

static int32_t add_node(Turtle *t, uint8_t kind, int32_t parent, uint32_t module) {
    if (!t->sk) return -1; /* filling queries: no geometry */
    TState *st = &t->st;
    SylNode n;
    glm_vec3_copy(st->pos, n.pos);
    glm_vec3_copy(st->h, n.h);
    glm_vec3_copy(st->l, n.l);
    glm_vec3_copy(st->u, n.u);
    n.radius = fabsf(st->width * st->scale) * 0.5f;
    n.parent = parent;
    n.axis = st->axis;
    n.order = st->order;
    n.kind = kind;
    n.material = st->material;
    n.flags = st->smooth ? SYL_NODE_SMOOTH : 0;
    n.module = module;
    int32_t id = syl_skeleton_add_node(t->sk, &n);
    if (id < 0) t->oom = true;
    return id;
}

/* How far a move of len goes, at the current scale. */
static inline float distance(const TState *st, float len) {
    float d = len * st->scale;
    d = d < 1e30f ? d : 1e30f; /* fminf(1e30f, d), NaN too, without a call */
    return d > -1e30f ? d : -1e30f;
}

/* The turtle moved without drawing: the next segment starts from a new root. */
static void detach(Turtle *t) { t->st.gen = ++t->gens; }

/* Filling queries for the environment: a segment's end, and a ?E module where it stands. */
/* Room for one more in an array of the fill (grown rarely: out of line). */
static bool grow_fill(Turtle *t, void *arrp, size_t *cap, size_t n, size_t size) {
    if (array_reserve(arrp, cap, n + 1, size)) return true;
    t->oom = true;
    return false;
}

static inline void env_end(Turtle *t, const float pos[3]) {
    SylEnvFill *f = t->env;
    if (f->nends == f->ends_cap && !grow_fill(t, &f->ends, &f->ends_cap, f->nends, sizeof *f->ends)) return;
    memcpy(f->ends[f->nends++], pos, 3 * sizeof(float));
}

static inline void env_probe(Turtle *t, size_t par, int na, bool heading) {
    SylEnvFill *f = t->env;
    if (f->nprobes == f->probes_cap && !grow_fill(t, &f->probes, &f->probes_cap, f->nprobes, sizeof *f->probes)) return;
    SylEnvProbe *q = &f->probes[f->nprobes++];
    memcpy(q->pos, t->st.pos, sizeof q->pos);
    if (heading) memcpy(q->h, t->st.h, sizeof q->h);
    else memset(q->h, 0, sizeof q->h);
    q->par = par;
    q->na = na;
    q->tip = t->st.gen == 0;
}

static void draw(Turtle *t, float len, uint32_t module) {
    TState *st = &t->st;
    if (st->dirty) orthonormalise(st);
    if (st->gen) {
        /* A root where the turtle stands. Saved states that moved with this same move stand
         * here too: they share it (the stack's moves never decrease toward its top). */
        st->axis = t->axes++;
        int32_t root = add_node(t, SYL_KIND_ROOT, -1, module);
        for (size_t k = t->depth; k-- && t->stack[k].gen == st->gen;) {
            t->stack[k].node = root;
            t->stack[k].axis = st->axis;
            t->stack[k].gen = 0;
        }
        st->node = root;
        st->gen = 0;
    }
    if (st->branch) {
        st->axis = t->axes++;
        if (st->order < UINT16_MAX) st->order++;
        st->branch = false;
    }
    glm_vec3_muladds(st->h, distance(st, len), st->pos);
    st->node = add_node(t, SYL_KIND_INTERNODE, st->node, module);
    if (t->env) env_end(t, st->pos);
    tropism(st);
}

static void add_vertex(Turtle *t) {
    if (!t->npolys || !t->sk) return;
    if (t->nverts == t->vertcap) {
        size_t c = t->vertcap ? t->vertcap * 2 : 64;
        vec3 *v = realloc(t->verts, c * sizeof *v);
        if (!v) {
            t->oom = true;
            return;
        }
        t->verts = v;
        t->vertcap = c;
    }
    glm_vec3_copy(t->st.pos, t->verts[t->nverts++]);
}

static void move(Turtle *t, float len, bool vertex) {
    TState *st = &t->st;
    glm_vec3_muladds(st->h, distance(st, len), st->pos);
    detach(t);
    if (vertex) add_vertex(t);
}

static void open_poly(Turtle *t) {
    if (t->npolys == t->polycap) {
        size_t c = t->polycap ? t->polycap * 2 : 16;
        Poly *p = realloc(t->polys, c * sizeof *p);
        if (!p) {
            t->oom = true;
            return;
        }
        t->polys = p;
        t->polycap = c;
    }
    t->polys[t->npolys++].first = t->nverts;
}

static void close_poly(Turtle *t, uint32_t module) {
    if (!t->npolys) return;
    size_t first = t->polys[--t->npolys].first;
    size_t n = t->nverts - first;
    if (t->sk && n >= 3 && n <= UINT32_MAX &&
        syl_skeleton_add_polygon(t->sk, (const float(*)[3])t->verts + first, (uint32_t)n, t->st.node,
                                 t->st.material, module) < 0)
        t->oom = true;
    t->nverts = first;
}

static void add_organ(Turtle *t, uint8_t kind, float size, uint32_t module) {
    TState *st = &t->st;
    if (!t->sk) return;
    if (st->dirty) orthonormalise(st);
    SylOrgan o;
    glm_vec3_copy(st->pos, o.pos);
    glm_vec3_copy(st->h, o.h);
    glm_vec3_copy(st->l, o.l);
    glm_vec3_copy(st->u, o.u);
    o.size = size * st->scale;
    o.node = st->node;
    o.kind = kind;
    o.material = st->material;
    /* Material 0 is bark, the default: a leaf or a flower nobody coloured gets its own. */
    if (o.material == 0 && (kind == SYL_KIND_LEAF || kind == SYL_KIND_NEEDLE)) o.material = SYL_MATERIAL_LEAF;
    if (o.material == 0 && kind == SYL_KIND_FLOWER) o.material = SYL_MATERIAL_FLOWER;
    o.module = module;
    if (syl_skeleton_add_organ(t->sk, &o) < 0) t->oom = true;
}

/* @Tp(x, y, z[, e]): the tropism's direction (zero: none) and its elasticity. */
static void set_tropism(TState *st, const double *a, int na) {
    if (na >= 3) {
        vec3 tr = {arg(a, na, 0, 0), arg(a, na, 1, 0), arg(a, na, 2, 0)};
        if (glm_vec3_norm(tr) > 1e-12f) glm_vec3_normalize_to(tr, st->trop);
        else glm_vec3_zero(st->trop);
    }
    if (na >= 4) st->elasticity = arg(a, na, 3, 0);
    if (glm_vec3_norm(st->trop) == 0) st->elasticity = 0;
}

static void push(Turtle *t) {
    if (t->depth == t->cap) {
        size_t c = t->cap ? t->cap * 2 : 64;
        TState *s = realloc(t->stack, c * sizeof *s);
        if (!s) {
            t->oom = true;
            return;
        }
        t->stack = s;
        t->cap = c;
    }
    t->stack[t->depth++] = t->st;
    t->st.branch = true;
}

static void pop(Turtle *t) {
    if (t->depth) t->st = t->stack[--t->depth];
}

static uint8_t clamp_material(double v) {
    if (!(v > 0)) return 0;
    if (v >= 255) return 255;
    return (uint8_t)v;
}

static void set_heading(Turtle *t, const double *a, int na) {
    TState *st = &t->st;
    if (na < 3) return;
    vec3 h = {arg(a, na, 0, 0), arg(a, na, 1, 0), arg(a, na, 2, 0)};
    if (!(glm_vec3_norm(h) > 1e-12f)) return;
    glm_vec3_normalize(h);
    if (st->dirty) orthonormalise(st);
    if (na >= 6) {
        vec3 u = {arg(a, na, 3, 0), arg(a, na, 4, 0), arg(a, na, 5, 0)};
        glm_vec3_muladds(h, -glm_vec3_dot(u, h), u); /* the part of u across h */
        if (glm_vec3_norm(u) > 1e-6f) {
            glm_vec3_normalize(u);
            glm_vec3_copy(h, st->h);
            glm_vec3_copy(u, st->u);
            glm_vec3_cross(u, h, st->l); /* H x L = U */
            return;
        }
    }
    aim(st, h);
}

/* `$`: roll about H so that L is horizontal (ABOP: L = V x H / |V x H|). */
static void level(TState *st) {
    if (st->dirty) orthonormalise(st);
    vec3 l;
    glm_vec3_cross((float *)vertical, st->h, l);
    if (glm_vec3_norm(l) < 1e-6f) return; /* heading vertical: any roll is level */
    glm_vec3_normalize(l);
    glm_vec3_copy(l, st->l);
    glm_vec3_cross(st->h, st->l, st->u);
}

/* Index of the `]` closing the branch module i is in (n when i is on the main axis); *off is
 * advanced past the parameters of the skipped modules. */
static size_t branch_end(const SylString *s, size_t i, size_t *off) {
    size_t depth = 0;
    for (i++; i < s->n; i++) {
        unsigned sym = CODE_SYM(s->code[i]);
        if (sym == SYM_CLOSE) {
            if (depth == 0) return i;
            depth--;
        } else if (sym == SYM_OPEN) {
            depth++;
        }
        *off += CODE_ARITY(s->code[i]);
    }
    return i;
}

/* Each symbol's command, as the compiler resolved it (a copy: the loops read it per module). */
static void resolve(Turtle *t) {
    memset(t->cmd, TC_NONE, sizeof t->cmd);
    for (int i = 0; i < t->p->nsyms && i < MAX_SYMBOLS; i++) t->cmd[i] = t->p->syms[i].turtle;
}

static void init(Turtle *t, const SylProgram *p, SylSkeleton *sk, FILE *diag) {
    memset(t, 0, sizeof *t);
    t->p = p;
    t->sk = sk;
    t->diag = diag;
    t->angle = p->angle;
    for (int k = 0; k < ANGLE_CACHE; k++) t->angles[k] = (Angle){.deg = 0, .sn = 0, .cs = 1};
    t->step = p->step;
    t->widthfactor = p->widthfactor;
    TState *st = &t->st;
    glm_vec3_copy((vec3){0, 1, 0}, st->h);
    glm_vec3_copy((vec3){-1, 0, 0}, st->l);
    glm_vec3_copy((vec3){0, 0, 1}, st->u);
    st->width = (float)fmax(0, fmin(p->width, 1e30));
    st->scale = 1;
    st->node = -1;
    st->gen = ++t->gens; /* the start counts as a move: the first segment makes the root */
    vec3 tr = {arg(p->tropism, 4, 0, 0), arg(p->tropism, 4, 1, 0), arg(p->tropism, 4, 2, 0)};
    if (glm_vec3_norm(tr) > 0 && isfinite(p->tropism[3])) {
        glm_vec3_normalize_to(tr, st->trop);
        st->elasticity = arg(p->tropism, 4, 3, 0);
    }
    resolve(t);
}

static void release(Turtle *t) {
    free(t->stack);
    free(t->polys);
    free(t->verts);
}

/* The nodes a string draws: segments, plus at most one root per move or per segment. A
 * bound good enough that the node array, reserved once, rarely grows (`%` is not followed). */
static uint64_t count_nodes(const Turtle *t, const SylString *s) {
    uint64_t draws = 0, moves = 1, polys = 0;
    for (size_t i = 0; i < s->n; i++) {
        switch (t->cmd[CODE_SYM(s->code[i])]) {
        case TC_F: case TC_G: *(polys ? &moves : &draws) += 1; break;
        case TC_f: case TC_g: case TC_MOVE_TO: moves++; break;
        case TC_POLY_OPEN: polys++; break;
        case TC_POLY_CLOSE: polys -= polys > 0; break;
        default: break;
        }
    }
    return draws + (moves < draws ? moves : draws);
}

static void reserve_nodes(SylSkeleton *sk, uint64_t want) {
    if (want == 0 || want > INT32_MAX) return;
    SylNode *nodes = realloc(sk->nodes, want * sizeof *nodes);
    if (!nodes) return; /* grow as needed instead */
    sk->nodes = nodes;
    sk->node_cap = want;
}

/* The value of one query module: position or a frame vector. */
static void query(const TState *st, TurtleCommand c, double *out, int na) {
    const float *v = c == TC_QUERY_P ? st->pos : c == TC_QUERY_H ? st->h : c == TC_QUERY_L ? st->l : st->u;
    /* the turtle computes in float: residues of rotations (6e-17, -0) read as 0 */
    for (int k = 0; k < na && k < 3; k++) out[k] = fabsf(v[k]) < 1e-6f ? 0.0 : (double)v[k];
}

/* Read the string and build the skeleton. */
static int run(Turtle *t, const SylString *s) {
    TState *st = &t->st;
    const uint16_t *code = s->code;
    const double *par = s->par;
    size_t off = 0;
    for (size_t i = 0; i < s->n && !t->oom; i++) {
        uint16_t c = code[i];
        int sym = CODE_SYM(c), na = CODE_ARITY(c);
        const double *a = na ? par + off : NULL; /* par is NULL in a string without parameters */
        off += (size_t)na;
        TurtleCommand cmd = t->cmd[sym];
        if (cmd == TC_NONE) continue;
        if (na) {
            bool finite = true;
            for (int k = 0; k < na; k++) finite &= isfinite(a[k]) != 0;
            if (!finite && cmd < TC_QUERY_P) {
                t->bad++;
                continue;
            }
        }
        uint32_t module = (uint32_t)i;
        float sn = 0, cs = 1;
        if (cmd >= TC_LEFT && cmd <= TC_ROLL_RIGHT) { /* most turns are by the model's angle */
            turn_sincos(t->angles, argd(a, na, 0, t->angle), &sn, &cs);
        }
        switch (cmd) {
        case TC_NONE: break;
        case TC_F:
        case TC_G:
            if (t->npolys) move(t, arg(a, na, 0, t->step), cmd == TC_F);
            else draw(t, arg(a, na, 0, t->step), module);
            break;
        case TC_f:
        case TC_g: move(t, arg(a, na, 0, t->step), cmd == TC_f && t->npolys); break;
        case TC_LEFT:
        case TC_RIGHT:
            rotate_pair(st->h, st->l, cmd == TC_LEFT ? sn : -sn, cs); /* H toward L */
            turned(st);
            break;
        case TC_DOWN:
        case TC_UP:
            rotate_pair(st->u, st->h, cmd == TC_DOWN ? sn : -sn, cs); /* H toward -U */
            turned(st);
            break;
        case TC_ROLL_LEFT:
        case TC_ROLL_RIGHT:
            rotate_pair(st->u, st->l, cmd == TC_ROLL_LEFT ? sn : -sn, cs); /* L toward -U */
            turned(st);
            break;
        case TC_TURN_AROUND:
            glm_vec3_negate(st->h);
            glm_vec3_negate(st->l);
            break;
        case TC_LEVEL: level(st); break;
        case TC_PUSH: push(t); break;
        case TC_POP: pop(t); break;
        case TC_CUT:
            i = branch_end(s, i, &off);
            if (i < s->n) pop(t);
            break;
        case TC_WIDTH:
            if (na) st->width = fmaxf(0, arg(a, na, 0, 0));
            else st->width = (float)fmin(st->width * t->widthfactor, 1e30);
            break;
        case TC_MATERIAL:
        case TC_MATERIAL_NEXT:
            st->material = na ? clamp_material(a[0]) : clamp_material(st->material + 1.0);
            break;
        case TC_MATERIAL_PREV:
            st->material = na ? clamp_material(a[0]) : clamp_material(st->material - 1.0);
            break;
        case TC_POLY_OPEN: open_poly(t); break;
        case TC_VERTEX: add_vertex(t); break;
        case TC_POLY_CLOSE: close_poly(t, module); break;
        case TC_LEAF: add_organ(t, SYL_KIND_LEAF, arg(a, na, 0, t->step), module); break;
        case TC_PETAL: add_organ(t, SYL_KIND_FLOWER, arg(a, na, 0, t->step), module); break;
        case TC_NEEDLE: add_organ(t, SYL_KIND_NEEDLE, arg(a, na, 0, t->step), module); break;
        case TC_SURFACE_UNKNOWN: warn_once(t, sym, "not a predefined surface (~leaf, ~petal, ~flower, ~needle)"); break;
        case TC_SPHERE: add_organ(t, SYL_KIND_SPHERE, arg(a, na, 0, st->width), module); break;
        case TC_TROPISM: set_tropism(st, a, na); break;
        case TC_ELASTICITY:
            st->elasticity = glm_vec3_norm(st->trop) > 0 ? arg(a, na, 0, 0) : 0;
            break;
        case TC_MOVE_TO:
            for (int k = 0; k < na && k < 3; k++) st->pos[k] = arg(a, na, k, 0);
            detach(t);
            break;
        case TC_HEADING: set_heading(t, a, na); break;
        case TC_SCALE: st->scale = arg(a, na, 0, 1); break;
        case TC_SMOOTH_ON: st->smooth = true; break;
        case TC_SMOOTH_OFF: st->smooth = false; break;
        case TC_QUERY_P:
        case TC_QUERY_H:
        case TC_QUERY_L:
        case TC_QUERY_U:
        case TC_QUERY_E: break; /* filled by run_query */
        case TC_COUNT: break;
        }
    }
    return t->oom ? SYL_ELIMIT : SYL_OK;
}

/* Filling queries, only what moves or turns the turtle counts: widths, materials, organs and
 * unknown surfaces change nothing a query reads (organs and vertices are not even kept
 * without a skeleton), so they are read as unknown symbols, and ?E too when nobody collects. */
static void resolve_query(Turtle *t) {
    for (int i = 0; i < MAX_SYMBOLS; i++) {
        unsigned cmd = t->cmd[i];
        if (!(turtle_command_flags(cmd) & (TF_MOVES | TF_TURNS | TF_STACK | TF_STEERS | TF_QUERY)) ||
            (cmd == TC_QUERY_E && !t->env))
            t->cmd[i] = TC_NONE;
    }
}

/* ---- filling queries ----
 * The turtle's frame changes only when something reads it: turns, `|` and re-orthonormalising
 * wait in t->pend until a segment, a move, `[`, `$`, @R or a query of the frame needs the frame,
 * and are dropped at `]` (the frame they would have made is never seen). Made later, in the
 * same order, they give the same floats; dirty is counted as they are queued, so the frame is
 * re-orthonormalised where run() would do it. */

/* Make the frame changes waiting (orthonormalise's dirty = 0 is already counted). */
static void flush(Turtle *t) {
    TState *st = &t->st;
    uint32_t dirty = st->dirty;
    for (int k = 0; k < t->npend; k++) {
        const Pending *q = &t->pend[k];
        float sn, cs;
        switch (q->op) {
        case P_HL:
            turn_sincos(t->angles, q->deg, &sn, &cs);
            rotate_pair(st->h, st->l, q->neg ? -sn : sn, cs);
            break;
        case P_UH:
            turn_sincos(t->angles, q->deg, &sn, &cs);
            rotate_pair(st->u, st->h, q->neg ? -sn : sn, cs);
            break;
        case P_UL:
            turn_sincos(t->angles, q->deg, &sn, &cs);
            rotate_pair(st->u, st->l, q->neg ? -sn : sn, cs);
            break;
        case P_NEGATE:
            glm_vec3_negate(st->h);
            glm_vec3_negate(st->l);
            break;
        case P_ORTHO: orthonormalise(st); break;
        default: orthonormalise_lu(st); break;
        }
    }
    st->dirty = dirty;
    t->npend = 0;
}

/* The frame changes waiting, as far as H: a last re-orthonormalising is made for H alone,
 * L and U left waiting (a segment needs H; a branch of turns and light queries after it
 * drops the rest). */
static void flush_h(Turtle *t) {
    if (t->pend[t->npend - 1].op != P_ORTHO) {
        flush(t);
        return;
    }
    t->npend--;
    flush(t);
    glm_vec3_normalize(t->st.h);
    t->pend[t->npend++] = (Pending){.op = P_ORTHO_LU};
}

static inline void pend(Turtle *t, uint32_t op, bool neg, double deg) {
    if (t->npend == PENDING_MAX) flush(t);
    t->pend[t->npend++] = (Pending){.op = op, .neg = neg, .deg = deg};
}

/* orthonormalise() when the frame is dirty, as every reader of the frame in run() does. */
static inline void pend_tidy(Turtle *t) {
    if (t->st.dirty) {
        pend(t, P_ORTHO, false, 0);
        t->st.dirty = 0;
    }
}

/* A turn (its sine and cosine are looked up when it is made: most never are). */
static inline void pend_turn(Turtle *t, uint32_t op, bool neg, double deg) {
    pend(t, op, neg, deg);
    if (++t->st.dirty >= 32) { /* turned() */
        pend(t, P_ORTHO, false, 0);
        t->st.dirty = 0;
    }
}

/* draw() without the skeleton: the frame, the segment's end, tropism, and the moves that
 * the stack shares (a query's `tip` reads them). */
static inline void draw_query(Turtle *t, float len) {
    TState *st = &t->st;
    pend_tidy(t);
    if (t->npend) {
        if (st->elasticity != 0) flush(t); /* tropism turns the whole frame */
        else flush_h(t);
    }
    if (st->gen) {
        for (size_t k = t->depth; k-- && t->stack[k].gen == st->gen;) t->stack[k].gen = 0;
        st->gen = 0;
    }
    glm_vec3_muladds(st->h, distance(st, len), st->pos);
    if (t->env) env_end(t, st->pos);
    if (st->elasticity != 0) tropism(st);
}

static inline void move_query(Turtle *t, float len) {
    if (t->npend) flush(t);
    glm_vec3_muladds(t->st.h, distance(&t->st, len), t->st.pos);
    detach(t);
}

/* `]` (and `%`): the frame changes waiting are never seen. */
static inline void pop_query(Turtle *t) {
    if (!t->depth) return; /* an unmatched `]` keeps the state */
    t->npend = 0;
    pop(t);
}

/* Whether v[0..n) are all finite: an exponent of all ones (inf, NaN) carries into bit 63. */
static inline bool all_finite(const double *v, unsigned n) {
    uint64_t odd = 0;
    for (unsigned k = 0; k < n; k++) {
        uint64_t bits;
        memcpy(&bits, v + k, sizeof bits);
        odd |= (bits & 0x7ff0000000000000u) + ((uint64_t)1 << 52);
    }
    return !(odd >> 63);
}

/* The commands run_query meets seldom, out of its loop (which then keeps its variables in
 * registers). o: the module's parameters, writable. */
static __attribute__((noinline)) void query_seldom(Turtle *t, TurtleCommand cmd, const double *a, int na, double *o) {
    TState *st = &t->st;
    switch (cmd) {
    case TC_TURN_AROUND: pend(t, P_NEGATE, false, 0); break;
    case TC_LEVEL:
        if (t->npend) flush(t);
        level(st);
        break;
    case TC_TROPISM: set_tropism(st, a, na); break;
    case TC_ELASTICITY: st->elasticity = glm_vec3_norm(st->trop) > 0 ? arg(a, na, 0, 0) : 0; break;
    case TC_MOVE_TO:
        for (int k = 0; k < na && k < 3; k++) st->pos[k] = arg(a, na, k, 0);
        detach(t);
        break;
    case TC_HEADING:
        if (t->npend) flush(t);
        set_heading(t, a, na);
        break;
    case TC_SCALE: st->scale = arg(a, na, 0, 1); break;
    case TC_QUERY_H:
    case TC_QUERY_L:
    case TC_QUERY_U:
        pend_tidy(t);
        if (t->npend) flush(t);
        query(st, cmd, o, na);
        break;
    default: break; /* read as unknown: see resolve_query */
    }
}

static inline void light_probe(Turtle *t, uint32_t par) {
    SylOpenFill *o = t->open;
    if (o->nlight == o->light_cap && !grow_fill(t, &o->light, &o->light_cap, o->nlight, sizeof *o->light)) return;
    SylLightProbe *q = &o->light[o->nlight++];
    memcpy(q->pos, t->st.pos, sizeof q->pos);
    q->par = par | (t->st.gen == 0 ? SYL_LIGHT_TIP : 0);
}

/* An ?E module: its probe. For env/open.c only what it answers. */
static inline void query_env(Turtle *t, const double *a, int na, size_t at) {
    pend_tidy(t);
    if (!t->open) {
        if (t->npend) flush(t);
        env_probe(t, at, na, true);
        return;
    }
    unsigned kind = syl_env_kind_bit(a, na);
    t->open->kinds |= kind;
    if (na < 2 || !kind) return; /* not answered */
    if (kind == 1 && at < SYL_LIGHT_TIP) {
        light_probe(t, (uint32_t)at); /* the position alone */
    } else if (kind == 1) {
        env_probe(t, at, na, false);
    } else { /* crowding and distance look along the heading (sky: read again, see open.c) */
        if (t->npend) flush(t);
        env_probe(t, at, na, true);
    }
}

/* A branch that only turns and asks where it stands (?P, light) changes nothing seen after
 * its `]`, and nobody sees its turns: its queries are answered at the position of its `[`
 * and it is skipped, without saving and restoring the state. Returns the index of its `]`
 * (n when the string ends first), *ap past its parameters; 0 when the branch does more
 * (what it collected is then taken back, and the turtle reads it as usual). */
/* What a dead branch may hold besides its queries: a bit per command. */
_Static_assert(TC_QUERY_E < 64, "a bit per command in a uint64_t");
static const uint64_t skip_dead = (uint64_t)1 << TC_NONE | (uint64_t)1 << TC_LEFT | (uint64_t)1 << TC_RIGHT |
                                  (uint64_t)1 << TC_DOWN | (uint64_t)1 << TC_UP | (uint64_t)1 << TC_ROLL_LEFT |
                                  (uint64_t)1 << TC_ROLL_RIGHT;

static size_t dead_branch(Turtle *t, const SylString *s, const double *par, size_t i, const double **ap,
                          double *out) {
    const uint16_t *code = s->code;
    const double *a = *ap;
    size_t n = s->n, nlight = t->open ? t->open->nlight : 0;
    for (i++; i < n; i++) {
        unsigned c = code[i], na = CODE_ARITY(c);
        TurtleCommand cmd = t->cmd[CODE_SYM(c)];
        a += na;
        const double *m = a - na;
        if (skip_dead >> cmd & 1) continue;
        if (cmd == TC_POP) break;
        if (cmd == TC_QUERY_P) {
            query(&t->st, cmd, out + (m - par), (int)na);
            continue;
        }
        if (cmd != TC_QUERY_E || !t->open) return t->open ? (t->open->nlight = nlight, 0) : 0;
        unsigned kind = syl_env_kind_bit(m, (int)na); /* as query_env */
        t->open->kinds |= kind;
        if (na < 2 || !kind) continue; /* not answered */
        if (kind != 1 || (size_t)(m - par) >= SYL_LIGHT_TIP) { /* needs the heading, or room */
            t->open->nlight = nlight;
            return 0;
        }
        light_probe(t, (uint32_t)(m - par));
    }
    *ap = a;
    return i;
}

/* Read the string as run() does, but only to write the turtle's state into its query
 * modules (out is s->par, writable) and collect what ?E needs: no skeleton, no polygons
 * (only how many are open: F moves inside one), no organs. The position and frame go
 * through the same float operations as in run(), so the values are the same. */
static int run_query(Turtle *t, const SylString *s, double *out) {
    /* A string without parameters has none (par NULL): offsets are then taken from a
     * stand-in, as pointer arithmetic on NULL is undefined even by zero. */
    double none[1] = {0};
    if (!out) out = none;
    const uint16_t *code = s->code;
    const double *par = s->par ? s->par : out, *a = par;
    const uint8_t *cmds = t->cmd;
    size_t n = s->n, npolys = 0;
    t->npend = 0;
    for (size_t i = 0; i < n; i++) { /* t->oom is looked at where memory is taken */
        unsigned c = code[i], na = CODE_ARITY(c);
        TurtleCommand cmd = cmds[CODE_SYM(c)];
        a += na; /* past this module's parameters: they are a[-na .. -1] */
        if (cmd == TC_NONE) continue;
        const double *m = a - na;
        if (na && cmd < TC_QUERY_P && !all_finite(m, na)) continue;
        switch (cmd) {
        case TC_F:
        case TC_G:
            if (npolys) {
                move_query(t, arg(m, (int)na, 0, t->step));
                break;
            }
            draw_query(t, arg(m, (int)na, 0, t->step));
            if (t->oom) return SYL_ELIMIT;
            break;
        case TC_f:
        case TC_g: move_query(t, arg(m, (int)na, 0, t->step)); break;
        case TC_LEFT:
        case TC_RIGHT: pend_turn(t, P_HL, cmd == TC_RIGHT, argd(m, (int)na, 0, t->angle)); break; /* H toward L */
        case TC_DOWN:
        case TC_UP: pend_turn(t, P_UH, cmd == TC_UP, argd(m, (int)na, 0, t->angle)); break; /* H toward -U */
        case TC_ROLL_LEFT:
        case TC_ROLL_RIGHT: pend_turn(t, P_UL, cmd == TC_ROLL_RIGHT, argd(m, (int)na, 0, t->angle)); break; /* L toward -U */
        case TC_PUSH: {
            size_t end = dead_branch(t, s, par, i, &a, out);
            if (end) {
                i = end;
            } else {
                if (t->npend) flush(t);
                push(t);
            }
            if (t->oom) return SYL_ELIMIT;
            break;
        }
        case TC_POP: pop_query(t); break;
        case TC_CUT: {
            size_t off = (size_t)(a - par);
            i = branch_end(s, i, &off);
            a = par + off;
            if (i < n) pop_query(t);
            break;
        }
        case TC_POLY_OPEN: npolys++; break;
        case TC_POLY_CLOSE: npolys -= npolys > 0; break;
        case TC_QUERY_P:
            pend_tidy(t); /* the position needs no frame */
            query(&t->st, cmd, out + (m - par), (int)na);
            break;
        case TC_QUERY_E:
            query_env(t, m, (int)na, (size_t)(m - par));
            if (t->oom) return SYL_ELIMIT;
            break;
        default: query_seldom(t, cmd, m, (int)na, out + (m - par)); break;
        }
    }
    return t->oom ? SYL_ELIMIT : SYL_OK;
}

int syl_turtle(const SylProgram *p, const SylString *s, const SylTurtleOptions *opt, SylSkeleton **out) {
    *out = NULL;
    FILE *diag = opt ? opt->diag : NULL;
    SylSkeleton *sk = syl_skeleton_new(p->name);
    Turtle *t = malloc(sizeof *t);
    if (!sk || !t) {
        free(t);
        syl_skeleton_free(sk);
        if (diag) fprintf(diag, "sylva: error: out of memory in the turtle\n");
        return SYL_ELIMIT;
    }
    for (int i = 0; i < 256; i++)
        if (p->colour_set[i]) {
            memcpy(sk->materials[i].rgb, p->colours[i], sizeof sk->materials[i].rgb);
            sk->materials[i].kind = i == 0 ? SYL_MATERIAL_BARK
                                    : i == 1 ? SYL_MATERIAL_LEAF
                                    : i == 2 ? SYL_MATERIAL_FLOWER
                                             : SYL_MATERIAL_PLAIN;
        }
    init(t, p, sk, diag);
    /* the nodes are counted before they are drawn: the caller's budget keeps them counted
     * until the skeleton is freed, one of max_memory checks them alone */
    uint64_t want = count_nodes(t, s), bytes = want * sizeof(SylNode);
    Budget own, *mem = opt && opt->budget ? opt->budget : &own;
    budget_init(&own, opt ? opt->max_memory : 0);
    if (!budget_charge(mem, bytes)) {
        if (diag)
            fprintf(diag, "sylva: error: the skeleton would need %llu nodes (%llu MB), more than --max-memory "
                          "allows (%llu MB%s); raise the limit with --max-memory\n",
                    (unsigned long long)want, (unsigned long long)(bytes >> 20),
                    (unsigned long long)budget_limit_mb(mem), mem == &own ? "" : " in all");
        release(t);
        free(t);
        syl_skeleton_free(sk);
        return SYL_ELIMIT;
    }
    if (mem != &own) sk->budget = mem, sk->charged = bytes;
    reserve_nodes(sk, want);
    int status = run(t, s);
    if (status == SYL_OK && t->bad && diag)
        fprintf(diag, "sylva: warning: the turtle skipped %llu module%s with a parameter that is not a finite number\n",
                (unsigned long long)t->bad, t->bad == 1 ? "" : "s");
    if (status != SYL_OK) {
        if (diag) fprintf(diag, "sylva: error: out of memory in the turtle\n");
        syl_skeleton_free(sk);
        sk = NULL;
    }
    release(t);
    free(t);
    *out = sk;
    return status;
}

static int fill(const SylProgram *p, SylString *s, SylEnvFill *env, SylOpenFill *open) {
    Turtle *t = malloc(sizeof *t);
    if (!t) return SYL_ELIMIT;
    init(t, p, NULL, NULL);
    t->env = env;
    t->open = env ? open : NULL;
    if (env) env->nends = env->nprobes = 0;
    if (t->open) t->open->nlight = 0, t->open->kinds = 0;
    resolve_query(t);
    bool any = false;
    for (int i = 0; i < p->nsyms && i < MAX_SYMBOLS; i++) any |= (turtle_command_flags(t->cmd[i]) & TF_QUERY) != 0;
    int status = any ? run_query(t, s, s->par) : SYL_OK;
    release(t);
    free(t);
    return status;
}

int syl_turtle_query(const SylProgram *p, SylString *s, SylEnvFill *env) { return fill(p, s, env, NULL); }

int syl_turtle_fill(const SylProgram *p, SylString *s, SylEnvFill *env, SylOpenFill *open) {
    return fill(p, s, env, open);
}
