/* The turtle's state: its start, exact turns, tropism, headings, levelling and the stack. */
#include <stdlib.h>

#include "turtle/turtle_internal.h"
#include "util/array.h"

static const vec3 vertical = {0, 1, 0};

/* sin and cos of an angle in degrees, exact at multiples of 90. */
void turtle_sincos(double deg, float *s, float *c) {
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

void turtle_tropism(TState *st) {
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

void turtle_set_tropism(TState *st, const double *a, int na) {
    if (na >= 3) {
        vec3 tr = {arg(a, na, 0, 0), arg(a, na, 1, 0), arg(a, na, 2, 0)};
        if (glm_vec3_norm(tr) > 1e-12f) glm_vec3_normalize_to(tr, st->trop);
        else glm_vec3_zero(st->trop);
    }
    if (na >= 4) st->elasticity = arg(a, na, 3, 0);
    if (glm_vec3_norm(st->trop) == 0) st->elasticity = 0;
}

bool turtle_grow_stack(Turtle *t) {
    size_t c = t->cap ? t->cap * 2 : 64;
    TState *s = realloc(t->stack, c * sizeof *s);
    if (!s) {
        t->oom = true;
        return false;
    }
    t->stack = s;
    t->cap = c;
    return true;
}

bool turtle_grow_fill(Turtle *t, void *arrp, size_t *cap, size_t n, size_t size) {
    if (array_reserve(arrp, cap, n + 1, size)) return true;
    t->oom = true;
    return false;
}

void turtle_set_heading(Turtle *t, const double *a, int na) {
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

/* ABOP: L = V x H / |V x H|. */
void turtle_level(TState *st) {
    if (st->dirty) orthonormalise(st);
    vec3 l;
    glm_vec3_cross((float *)vertical, st->h, l);
    if (glm_vec3_norm(l) < 1e-6f) return; /* heading vertical: any roll is level */
    glm_vec3_normalize(l);
    glm_vec3_copy(l, st->l);
    glm_vec3_cross(st->h, st->l, st->u);
}

size_t turtle_branch_end(const SylString *s, size_t i, size_t *off) {
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

void turtle_init(Turtle *t, const SylProgram *p, SylSkeleton *sk, FILE *diag) {
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

void turtle_release(Turtle *t) {
    free(t->stack);
    free(t->polys);
    free(t->verts);
}

void turtle_query_value(const TState *st, TurtleCommand c, double *out, int na) {
    const float *v = c == TC_QUERY_P ? st->pos : c == TC_QUERY_H ? st->h : c == TC_QUERY_L ? st->l : st->u;
    /* the turtle computes in float: residues of rotations (6e-17, -0) read as 0 */
    for (int k = 0; k < na && k < 3; k++) out[k] = fabsf(v[k]) < 1e-6f ? 0.0 : (double)v[k];
}
