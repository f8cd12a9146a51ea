/* The 3D turtle: reads a module string and emits a Skeleton. docs/turtle.md describes every
 * symbol and is its contract.
 *
 * The compiler resolves each symbol into a turtle command once (lang/turtle_commands.h), so
 * reading a module is one table look-up and one switch. The state is kept in floats (cglm);
 * turns by multiples of 90 degrees are exact, and the frame is re-orthonormalised before it is
 * used after a turn (turtle_frame.c). */
#include <stdlib.h>

#include "lang/textures.h"
#include "turtle/turtle_internal.h"
#include "skeleton/store.h"
#include "util/budget.h"
#include "lang/program.h"

static void warn_once(Turtle *t, int sym, const char *what) {
    if (t->warned[sym] || !program_heard(t->p, t->diag)) return;
    t->warned[sym] = true;
    program_say(t->p, t->diag, DIAG_WARNING, NULL, "%s '%s': ignored", what, t->p->syms[sym].name);
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
    if (st->elasticity != 0) turtle_tropism(st);
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

static uint8_t clamp_material(double v) {
    if (!(v > 0)) return 0;
    if (v >= 255) return 255;
    return (uint8_t)v;
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
    (void)skeleton_reserve_nodes(sk, (size_t)want); /* when it fails: grow as needed instead */
}

/* Read the string and build the skeleton (SYL_ECANCELED when cancel says so: asked every
 * 65,536 modules, a few milliseconds of reading). */
static int draw_string(Turtle *t, const SylString *s, const SylCancel *cancel) {
    TState *st = &t->st;
    const uint16_t *code = s->code;
    const double *par = s->par;
    size_t off = 0;
    for (size_t i = 0; i < s->n && !t->oom; i++) {
        if (!(i & 0xffff) && syl_cancelled(cancel)) return SYL_ECANCELED;
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
        case TC_DOWN:
        case TC_UP:
        case TC_ROLL_LEFT:
        case TC_ROLL_RIGHT:
            turtle_turn(cmd, sn, cs, st->h, st->l, st->u);
            turned(st);
            break;
        case TC_TURN_AROUND: turtle_turn(cmd, 0, 1, st->h, st->l, st->u); break;
        case TC_LEVEL: turtle_level(st); break;
        case TC_PUSH: push(t); break;
        case TC_POP: pop(t); break;
        case TC_CUT:
            i = turtle_branch_end(s, i, &off);
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
        case TC_DISC: add_organ(t, SYL_KIND_DISC, arg(a, na, 0, st->width), module); break;
        case TC_TROPISM: turtle_set_tropism(st, a, na); break;
        case TC_ELASTICITY:
            st->elasticity = glm_vec3_norm(st->trop) > 0 ? arg(a, na, 0, 0) : 0;
            break;
        case TC_MOVE_TO:
            for (int k = 0; k < na && k < 3; k++) st->pos[k] = arg(a, na, k, 0);
            detach(t);
            break;
        case TC_HEADING: turtle_set_heading(t, a, na); break;
        case TC_SCALE: st->scale = arg(a, na, 0, 1); break;
        case TC_SMOOTH_ON: st->smooth = true; break;
        case TC_SMOOTH_OFF: st->smooth = false; break;
        case TC_QUERY_P:
        case TC_QUERY_H:
        case TC_QUERY_L:
        case TC_QUERY_U:
        case TC_QUERY_E: break; /* filled by fill_queries */
        case TC_COUNT: break;
        }
    }
    return t->oom ? SYL_ELIMIT : SYL_OK;
}

int syl_turtle_draw(const SylProgram *p, const SylString *s, const SylTurtleOptions *opt, SylSkeleton **out) {
    *out = NULL;
    FILE *diag = opt ? opt->diag : NULL;
    SylSkeleton *sk = syl_skeleton_new(p->name);
    Turtle *t = malloc(sizeof *t);
    if (!sk || !t) {
        free(t);
        syl_skeleton_free(sk);
        program_say(p, diag, DIAG_ERROR, NULL, "out of memory in the turtle");
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
    turtle_init(t, p, sk, diag);
    /* the nodes are counted before they are drawn: the caller's budget keeps them counted
     * until the skeleton is freed, one of max_memory checks them alone */
    uint64_t want = count_nodes(t, s), bytes = want * sizeof(SylNode);
    Budget own, *mem = budget_use(&own, opt ? opt->max_memory : 0, opt ? opt->budget : NULL);
    if (!budget_charge(mem, bytes)) {
        program_say(p, diag, DIAG_ERROR, NULL, "the skeleton would need %llu nodes (%llu MB), more than --max-memory "
                          "allows (%llu MB%s); raise the limit with --max-memory",
                    (unsigned long long)want, (unsigned long long)(bytes >> 20),
                    (unsigned long long)budget_limit_mb(mem), mem == &own ? "" : " in all");
        turtle_release(t);
        free(t);
        syl_skeleton_free(sk);
        return SYL_ELIMIT;
    }
    if (mem != &own) skeleton_charge(sk, mem, bytes);
    reserve_nodes(sk, want);
    int status = draw_string(t, s, opt ? opt->cancel : NULL);
    if (status == SYL_OK) status = lang_textures_apply(p, sk, opt && opt->use_seed ? opt->seed : p->seed, diag);
    if (status == SYL_OK && t->bad)
        program_say(p, diag, DIAG_WARNING, NULL, "the turtle skipped %llu module%s with a parameter that is not a finite number",
                (unsigned long long)t->bad, t->bad == 1 ? "" : "s");
    if (status != SYL_OK) {
        if (status == SYL_ELIMIT) program_say(p, diag, DIAG_ERROR, NULL, "out of memory in the turtle");
        syl_skeleton_free(sk);
        sk = NULL;
    }
    turtle_release(t);
    free(t);
    *out = sk;
    return status;
}
