/* The query pass: the turtle's position and frame written into ?P ?H ?L ?U, and what ?E
 * needs collected, reading the string lazily (frame changes made only when read). */
#include <stdlib.h>

#include "turtle/turtle_internal.h"

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
 * re-orthonormalised where draw_string() would do it. */

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
            turtle_rotate_pair(st->h, st->l, q->neg ? -sn : sn, cs);
            break;
        case P_UH:
            turn_sincos(t->angles, q->deg, &sn, &cs);
            turtle_rotate_pair(st->u, st->h, q->neg ? -sn : sn, cs);
            break;
        case P_UL:
            turn_sincos(t->angles, q->deg, &sn, &cs);
            turtle_rotate_pair(st->u, st->l, q->neg ? -sn : sn, cs);
            break;
        case P_NEGATE:
            glm_vec3_negate(st->h);
            glm_vec3_negate(st->l);
            break;
        case P_ORTHO: orthonormalise(st); break;
        default: turtle_orthonormalise_lu(st->h, st->l, st->u); break;
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

/* orthonormalise() when the frame is dirty, as every reader of the frame in draw_string() does. */
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
    if (st->elasticity != 0) turtle_tropism(st);
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

/* The commands fill_queries meets seldom, out of its loop (which then keeps its variables in
 * registers). o: the module's parameters, writable. */
static __attribute__((noinline)) void query_seldom(Turtle *t, TurtleCommand cmd, const double *a, int na, double *o) {
    TState *st = &t->st;
    switch (cmd) {
    case TC_TURN_AROUND: pend(t, P_NEGATE, false, 0); break;
    case TC_LEVEL:
        if (t->npend) flush(t);
        turtle_level(st);
        break;
    case TC_TROPISM: turtle_set_tropism(st, a, na); break;
    case TC_ELASTICITY: st->elasticity = glm_vec3_norm(st->trop) > 0 ? arg(a, na, 0, 0) : 0; break;
    case TC_MOVE_TO:
        for (int k = 0; k < na && k < 3; k++) st->pos[k] = arg(a, na, k, 0);
        detach(t);
        break;
    case TC_HEADING:
        if (t->npend) flush(t);
        turtle_set_heading(t, a, na);
        break;
    case TC_SCALE: st->scale = arg(a, na, 0, 1); break;
    case TC_QUERY_H:
    case TC_QUERY_L:
    case TC_QUERY_U:
        pend_tidy(t);
        if (t->npend) flush(t);
        turtle_query_value(st, cmd, o, na);
        break;
    default: break; /* read as unknown: see resolve_query */
    }
}

static inline void light_probe(Turtle *t, uint32_t par) {
    SylOpenFill *o = t->open;
    if (o->nlight == o->light_cap && !turtle_grow_fill(t, &o->light, &o->light_cap, o->nlight, sizeof *o->light)) return;
    SylLightProbe *q = &o->light[o->nlight++];
    memcpy(q->pos, t->st.pos, sizeof q->pos);
    q->par = par | (t->st.gen == 0 ? SYL_LIGHT_TIP : 0);
}

/* An ?E module: its probe. For scene/open.c only what it answers. */
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
            turtle_query_value(&t->st, cmd, out + (m - par), (int)na);
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

/* Read the string as draw_string() does, but only to write the turtle's state into its query
 * modules (out is s->par, writable) and collect what ?E needs: no skeleton, no polygons
 * (only how many are open: F moves inside one), no organs. The position and frame go
 * through the same float operations as in draw_string(), so the values are the same. */
static int fill_queries(Turtle *t, const SylString *s, double *out) {
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
            i = turtle_branch_end(s, i, &off);
            a = par + off;
            if (i < n) pop_query(t);
            break;
        }
        case TC_POLY_OPEN: npolys++; break;
        case TC_POLY_CLOSE: npolys -= npolys > 0; break;
        case TC_QUERY_P:
            pend_tidy(t); /* the position needs no frame */
            turtle_query_value(&t->st, cmd, out + (m - par), (int)na);
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

static int fill(const SylProgram *p, SylString *s, SylEnvFill *env, SylOpenFill *open) {
    if (env && !env->store && !(env->store = calloc(1, sizeof *env->store))) return SYL_ELIMIT;
    Turtle *t = malloc(sizeof *t);
    if (!t) return SYL_ELIMIT;
    turtle_init(t, p, NULL, NULL);
    t->env = env;
    t->open = env ? open : NULL;
    if (env) env->nends = env->nprobes = 0;
    if (t->open) t->open->nlight = 0, t->open->kinds = 0;
    resolve_query(t);
    bool any = false;
    for (int i = 0; i < p->nsyms && i < MAX_SYMBOLS; i++) any |= (turtle_command_flags(t->cmd[i]) & TF_QUERY) != 0;
    int status = any ? fill_queries(t, s, s->par) : SYL_OK;
    turtle_release(t);
    free(t);
    return status;
}

int syl_turtle_query(const SylProgram *p, SylString *s, SylEnvFill *env) { return fill(p, s, env, NULL); }

void syl_env_fill_free(SylEnvFill *env) {
    if (!env) return;
    free(env->ends);
    free(env->probes);
    free(env->store);
    *env = (SylEnvFill){0};
}

int syl_turtle_fill(const SylProgram *p, SylString *s, SylEnvFill *env, SylOpenFill *open) {
    return fill(p, s, env, open);
}
