/* Rule-made shoots: see shoot_rule.h. The plan is read with the turtle's commands and frame
 * operations (turtle/frame.h): it only places things relative to a metamer, so it keeps no
 * skeleton and no tropism. */
#include "sot/shoot_rule.h"

#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lang/kinds.h"
#include "lang/program.h"
#include "lsys/derive.h"
#include "sylva/skeleton.h"
#include "turtle/frame.h"
#include "util/array.h"

/* What a module is to the plan: one of the turtle's commands it reads (TF_PLAN in
 * lang/turtle_commands.h), or one of the growth-only symbols I (a metamer) and B (a bud). */
enum { PLAN_METAMER = TC_COUNT, PLAN_BUD };
_Static_assert(PLAN_BUD <= UINT8_MAX, "a plan command in a byte");

struct ShootRule {
    SylProgram *p;
    int shoot, arity;      /* the symbol rewritten, and its parameters (at most 4) */
    bool buds;
    double angle; /* turns are made from the angle in double, as the turtle makes them */
    float step, width, widthfactor;
    uint8_t cmd[MAX_SYMBOLS];
    uint64_t max_modules, max_work; /* of each shoot's derivation */
    SylBudget *mem;
    ShootDeriveFn begin;   /* NULL: lsys_derive_begin without queries */
};

/* The arity of the first production for `shoot` (produce or decompose), or -1. */
static int shoot_arity(const SylProgram *q, int sym) {
    for (int t = TABLE_PRODUCE; t <= TABLE_DECOMPOSE; t++)
        for (int i = 0; i < q->tables[t].nrules; i++)
            if (CODE_SYM(q->tables[t].rules[i].pred) == sym) return CODE_ARITY(q->tables[t].rules[i].pred);
    return -1;
}

const char *shoot_rule_check(const SylProgram *q) {
    if (!q) return "does not compile";
    if (!lang_kind_is(syl_program_kind(q), KF_RULES)) return "is not an lsystem";
    int sym = syl_program_symbol_find(q, "shoot");
    int arity = sym >= 0 ? shoot_arity(q, sym) : -1;
    if (arity < 0) return "has no production for shoot(n, vigor, order, year)";
    if (arity > 4) return "rewrites shoot with more than 4 parameters (n, vigor, order, year)";
    return NULL;
}

ShootRule *shoot_rule_new(const SylProgram *grow, const char *model) {
    int status = 0;
    SylProgram *q = syl_compile_model(grow, model, NULL, &status);
    if (!q || shoot_rule_check(q)) {
        syl_program_free(q);
        return NULL;
    }
    ShootRule *r = calloc(1, sizeof *r);
    if (!r) {
        syl_program_free(q);
        return NULL;
    }
    r->p = q;
    r->shoot = syl_program_symbol_find(q, "shoot");
    r->arity = shoot_arity(q, r->shoot);
    r->angle = q->angle;
    r->step = (float)q->step;
    r->width = (float)q->width;
    r->widthfactor = (float)q->widthfactor;
    for (int i = 0; i < q->nsyms && i < MAX_SYMBOLS; i++) {
        unsigned cmd = q->syms[i].turtle;
        r->cmd[i] = !strcmp(q->syms[i].name, "I")   ? PLAN_METAMER
                    : !strcmp(q->syms[i].name, "B") ? PLAN_BUD
                    : turtle_command_flags(cmd) & TF_PLAN ? (uint8_t)cmd
                                                          : TC_NONE;
    }
    /* B placed anywhere in the model (a rule or the axiom) means the rule places the buds */
    int b = syl_program_symbol_find(q, "B");
    for (int t = 0; b >= 0 && t < TABLE_COUNT && !r->buds; t++)
        for (int i = 0; i < q->tables[t].nrules && !r->buds; i++)
            for (int k = 0; k < q->tables[t].rules[i].nsucc; k++)
                if (CODE_SYM(q->tables[t].rules[i].succ[k]) == b) r->buds = true;
    return r;
}

void shoot_rule_limits(ShootRule *r, uint64_t max_modules, uint64_t max_work, SylBudget *mem) {
    r->max_modules = max_modules;
    r->max_work = max_work;
    r->mem = mem;
}

void shoot_rule_derive_with(ShootRule *r, ShootDeriveFn begin) { r->begin = begin; }

void shoot_rule_free(ShootRule *r) {
    if (!r) return;
    syl_program_free(r->p);
    free(r);
}

bool shoot_rule_places_buds(const ShootRule *r) { return r->buds; }

void shoot_rule_colours(const ShootRule *r, bool set[256], float rgb[256][3]) {
    for (int i = 0; i < 256; i++) {
        set[i] = r->p->colour_set[i];
        if (set[i]) memcpy(rgb[i], r->p->colours[i], sizeof rgb[i]);
    }
}

void shoot_plan_free(ShootPlan *plan) {
    free(plan->a);
    memset(plan, 0, sizeof *plan);
}

/* ---- reading the plan ---- */

typedef struct State {
    vec3 pos, h, l, u;
    float width;
    uint8_t material;
    int32_t twig;     /* the last twig drawn on this path, -1: none */
    uint32_t dirty;   /* turns since the frame was last orthonormalised, as the turtle counts */
} State;

typedef struct Reader {
    const ShootRule *r;
    ShootPlan *plan;
    State st;
    State *stack;     /* the states `[` saved, as the turtle's stack grows */
    size_t depth, cap;
    int metamer;
    float roll;       /* degrees: the top-level rolls so far */
    bool oom;
} Reader;

/* The frame made orthonormal where the turtle would make it: before it is read after a turn. */
static void tidy(State *st) {
    if (!st->dirty) return;
    turtle_orthonormalise(st->h, st->l, st->u);
    st->dirty = 0;
}

/* A turn command by deg, as the turtle turns. */
static void turn(State *st, TurtleCommand cmd, double deg) {
    float s, c;
    turtle_sincos(deg, &s, &c);
    turtle_turn(cmd, s, c, st->h, st->l, st->u);
    if (++st->dirty >= TURTLE_TIDY_TURNS) tidy(st);
}

/* The frame at a metamer's end: along the shoot, turned by the rolls so far. */
static void reset(Reader *rd) {
    State *st = &rd->st;
    glm_vec3_zero(st->pos);
    glm_vec3_copy((vec3){1, 0, 0}, st->h);
    glm_vec3_copy((vec3){0, 1, 0}, st->l);
    glm_vec3_copy((vec3){0, 0, 1}, st->u);
    float s, c;
    turtle_sincos(rd->roll, &s, &c);
    turtle_turn(TC_ROLL_RIGHT, s, c, st->h, st->l, st->u);
    st->dirty = 0;
    st->twig = -1;
}

static void push(Reader *rd) {
    if (rd->depth == rd->cap && !array_reserve(&rd->stack, &rd->cap, rd->depth + 1, sizeof *rd->stack)) {
        rd->oom = true;
        return;
    }
    rd->stack[rd->depth++] = rd->st;
}

static Attach *attach(Reader *rd, AttachKind kind) {
    tidy(&rd->st);
    ShootPlan *p = rd->plan;
    if (!array_reserve(&p->a, &p->cap, p->n + 1, sizeof *p->a)) {
        rd->oom = true;
        return NULL;
    }
    Attach *a = &p->a[p->n++];
    memset(a, 0, sizeof *a);
    a->kind = (uint8_t)kind;
    a->metamer = (uint16_t)(rd->metamer < UINT16_MAX ? rd->metamer : UINT16_MAX);
    a->parent = -1;
    a->material = rd->st.material;
    glm_vec3_copy(rd->st.pos, a->pos);
    glm_vec3_copy(rd->st.h, a->h);
    glm_vec3_copy(rd->st.l, a->l);
    return a;
}

static float arg(const double *a, int na, float def) {
    return na && isfinite(a[0]) ? (float)fmax(-1e6, fmin(1e6, a[0])) : def;
}

/* A command's first parameter, or its default (lang/turtle_commands.h); in double, for turns. */
static double argd(const ShootRule *r, unsigned cmd, const double *a, int na) {
    if (na && isfinite(a[0])) return fmax(-1e6, fmin(1e6, a[0]));
    TurtleDefault d = turtle_command_default(cmd);
    return d == TA_ANGLE ? r->angle : d == TA_STEP ? r->step : 0;
}

static void organ(Reader *rd, uint8_t kind, float size) {
    Attach *a = attach(rd, ATT_ORGAN);
    if (!a) return;
    a->organ = kind;
    a->size = size;
    if (a->material == 0) a->material = kind == SYL_KIND_FLOWER ? SYL_MATERIAL_FLOWER : SYL_MATERIAL_LEAF;
}

static void draw(Reader *rd, float len) {
    State *st = &rd->st;
    tidy(st);
    vec3 from;
    glm_vec3_copy(st->pos, from);
    glm_vec3_muladds(st->h, len, st->pos);
    Attach *a = attach(rd, ATT_TWIG);
    if (!a) return;
    glm_vec3_copy(from, a->from);
    a->parent = st->twig;
    a->size = 0.5f * st->width;
    st->twig = (int32_t)(rd->plan->n - 1);
}

/* The end of the branch open at module i (its `]`), or s's end. */
static size_t skip_branch(const SylString *s, size_t i) {
    int depth = 0;
    for (; i < syl_string_length(s); i++) {
        int sym = syl_string_module(s, i, NULL, NULL);
        if (sym == SYM_OPEN) depth++;
        else if (sym == SYM_CLOSE && depth-- == 0) return i;
    }
    return i;
}

static void read_plan(Reader *rd, const SylString *s) {
    const ShootRule *r = rd->r;
    size_t n = syl_string_length(s);
    reset(rd);
    for (size_t i = 0; i < n && !rd->oom; i++) {
        int na;
        const double *a;
        int sym = syl_string_module(s, i, &na, &a);
        State *st = &rd->st;
        bool top = rd->depth == 0;
        unsigned cmd = r->cmd[sym];
        switch (cmd) {
        case PLAN_METAMER:
        case TC_F:
            if (top) {
                rd->metamer++;
                reset(rd);
            } else draw(rd, arg(a, na, r->step));
            break;
        case TC_f:
            glm_vec3_muladds(st->h, arg(a, na, r->step), st->pos);
            st->twig = -1;
            break;
        case TC_LEFT:
        case TC_RIGHT:
        case TC_DOWN:
        case TC_UP:
        case TC_ROLL_LEFT:
        case TC_ROLL_RIGHT: {
            double deg = argd(r, cmd, a, na);
            turn(st, (TurtleCommand)cmd, deg);
            if (top && (cmd == TC_ROLL_LEFT || cmd == TC_ROLL_RIGHT))
                rd->roll = fmodf(rd->roll + (float)(cmd == TC_ROLL_RIGHT ? deg : -deg), 360);
            break;
        }
        case TC_TURN_AROUND: turtle_turn(TC_TURN_AROUND, 0, 1, st->h, st->l, st->u); break;
        case TC_PUSH: push(rd); break;
        case TC_POP:
            if (rd->depth) rd->st = rd->stack[--rd->depth]; /* an unmatched ] ends nothing */
            break;
        case TC_CUT:
            if (top) attach(rd, ATT_END);
            else i = skip_branch(s, i + 1) - 1; /* the ] is read next */
            if (top) i = n;
            break;
        case TC_WIDTH: st->width = na ? fmaxf(0, arg(a, na, 0)) : st->width * r->widthfactor; break;
        case TC_MATERIAL: st->material = (uint8_t)fmax(0, fmin(255, arg(a, na, st->material + 1.0f))); break;
        case TC_LEAF: organ(rd, SYL_KIND_LEAF, (float)argd(r, cmd, a, na)); break;
        case TC_PETAL: organ(rd, SYL_KIND_FLOWER, (float)argd(r, cmd, a, na)); break;
        case TC_NEEDLE: organ(rd, SYL_KIND_NEEDLE, (float)argd(r, cmd, a, na)); break;
        case PLAN_BUD: attach(rd, ATT_BUD); break;
        default: break; /* not read by the plan */
        }
    }
    rd->plan->metamers = rd->metamer;
}

int shoot_rule_plan(const ShootRule *r, const double args[4], uint64_t seed, ShootPlan *plan, FILE *diag) {
    plan->n = 0;
    plan->metamers = 0;
    SylString *start = syl_string_new(), *out = NULL;
    if (!start || syl_string_push(start, r->shoot, r->arity, args)) {
        syl_string_free(start);
        return SYL_ELIMIT;
    }
    /* a shoot is small: a runaway rule stops here, not at the whole machine's memory */
    SylDeriveOptions d = {.steps = -1, .use_seed = 1, .seed = seed, .threads = 1,
                          .max_modules = r->max_modules ? r->max_modules : 1000000, .max_memory = 256u << 20,
                          .max_work = r->max_work, .budget = r->mem, .diag = diag};
    SylDeriver *dv = NULL;
    int st = r->begin ? r->begin(r->p, &d, start, &dv) : lsys_derive_begin(r->p, &d, start, NULL, &dv);
    if (dv) lsys_deriver_keep_cuts(dv); /* a `%` at the top level is read below: the axis ends */
    for (int k = 1; k <= syl_program_steps(r->p) && !st; k++) st = syl_derive_step(dv);
    if (dv) st = syl_derive_end(dv, &out);
    syl_string_free(start);
    if (st) return st;
    Reader *rd = calloc(1, sizeof *rd);
    if (!rd) {
        syl_string_free(out);
        return SYL_ELIMIT;
    }
    rd->r = r;
    rd->plan = plan;
    rd->st.width = r->width;
    read_plan(rd, out);
    st = rd->oom ? SYL_ELIMIT : SYL_OK;
    free(rd->stack);
    free(rd);
    syl_string_free(out);
    return st;
}
