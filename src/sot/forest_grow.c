/* Shoot growth: every bud with metamers to grow this year adds them one at a time, all
 * buds of all trees in step (Tázlar 2018 §3.8): a space-colonization round, each bud's
 * direction (in parallel), then the new metamers and their lateral buds (in bud order). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sot/direction.h"
#include "sot/forest_internal.h"
#include "sot/geometry.h"
#include "sot/phyllotaxis.h"
#include "util/array.h"
#include "util/parallel.h"
#include "util/rng.h"
#include "lang/program.h"

bool forest_space_scratch(Forest *f, size_t n) {
    if (n <= f->sbcap) return true;
    size_t cap = f->sbcap ? f->sbcap : 1024;
    while (cap < n) cap *= 2;
    SpaceBud *sb = realloc(f->sb, cap * sizeof *sb);
    if (!sb) return false;
    f->sb = sb;
    SpaceResult *sr = realloc(f->sr, cap * sizeof *sr);
    if (!sr) return false;
    f->sr = sr;
    uint32_t *sc = realloc(f->sb_cand, cap * sizeof *sc);
    if (!sc) return false;
    f->sb_cand = sc;
    f->sbcap = cap;
    return true;
}

void forest_space_bud(const Tree *t, const Bud *b, SpaceBud *out) {
    const GrowParams *P = &t->P;
    memcpy(out->pos, t->nodes[b->node].pos, sizeof out->pos);
    memcpy(out->dir, b->dir, sizeof out->dir);
    out->reach = P->perception * P->internode;
    out->cos_half = cosf(0.5f * P->cone * SOT_DEG);
    out->markers = (uint32_t)P->markers;
    out->key = b->key;
}

static bool push_candidate(Forest *f, int32_t tree, int32_t bud) {
    if (f->ncand == f->ccap) {
        size_t cap = f->ccap ? 2 * f->ccap : 1024;
        if (!budget_charge(f->mem, (cap - f->ccap) * sizeof *f->cand)) return false;
        f->charged += (cap - f->ccap) * sizeof *f->cand;
        Candidate *c = realloc(f->cand, cap * sizeof *c);
        if (!c) return false;
        f->cand = c;
        f->ccap = cap;
    }
    memset(&f->cand[f->ncand], 0, sizeof *f->cand);
    f->cand[f->ncand].tree = tree;
    f->cand[f->ncand++].bud = bud;
    return true;
}

static int space_step(Forest *f, int year, int step) {
    size_t n = 0;
    for (size_t c = 0; c < f->ncand; c++) n += f->trees[f->cand[c].tree].P.space != SPACEM_OFF;
    if (!n) return SYL_OK;
    if (!forest_space_scratch(f, n)) return SYL_ELIMIT;
    size_t m = 0;
    for (size_t c = 0; c < f->ncand; c++) {
        const Tree *t = &f->trees[f->cand[c].tree];
        if (t->P.space == SPACEM_OFF) continue;
        forest_space_bud(t, &t->buds[f->cand[c].bud], &f->sb[m]);
        f->sb_cand[m++] = (uint32_t)c;
    }
    SpaceQuery q = {.variant = f->space_variant, .occupancy = f->env.occupancy, .ground = f->env.ground, .nodes = &f->env.occupied,
                    .obstacles = &f->env.obstacles, .cloud = &f->env.cloud,
                    .round = (uint64_t)year << 20 | (uint64_t)(step + 1), .threads = f->threads};
    int st = space_round(&q, f->sb, n, f->sr);
    if (st) return st;
    for (size_t k = 0; k < n; k++) {
        Candidate *c = &f->cand[f->sb_cand[k]];
        memcpy(c->space, f->sr[k].dir, sizeof c->space);
        c->spaced = f->sr[k].count > 0;
    }
    return SYL_OK;
}

typedef struct StepJob {
    Forest *f;
    int year, step;
} StepJob;

static void directions(void *arg, size_t lo, size_t hi, int thread) {
    (void)thread;
    StepJob *j = arg;
    Forest *f = j->f;
    const Env *e = &f->env;
    for (size_t i = lo; i < hi; i++) {
        Candidate *c = &f->cand[i];
        const Tree *t = &f->trees[c->tree];
        const GrowParams *P = &t->P;
        const Bud *b = &t->buds[c->bud];
        const Node *nd = &t->nodes[b->node];
        if (P->space != SPACEM_OFF && !c->spaced) { /* no free space in view: no growth */
            c->blocked = 1;
            continue;
        }
        vec3 light = {0, 0, 0};
        if (P->light == LIGHT_SHADOW && P->w_light > 0) {
            shadow_gradient(&e->shadow, nd->pos, light);
            if (!sot_normalize(light)) glm_vec3_zero(light);
        }
        Rng r = rng_stream(b->key, (uint64_t)j->year, (uint64_t)j->step, 2);
        bool trunk = b->kind == BUD_APICAL && nd->order == 0;
        sot_direction(P, b->dir, c->space, light, trunk, &r, c->dir);
        for (int k = 0; k < 3; k++) c->to[k] = nd->pos[k] + b->seg * c->dir[k];
        c->blocked = env_below_ground(e, c->to) || obstacles_blocked(&e->obstacles, nd->pos, c->to, 0.25f * b->seg);
    }
}

/* ---- shoot rules ---- */

/* The things bud bi's plan hangs on metamer k, whose end is node (frame h, l there). False
 * when out of memory; *end when the plan ends the axis here. */
static bool hang(Tree *t, int32_t bi, int k, int32_t node, const float h[3], const float l[3], int year, bool *end) {
    ShootPlan *plan = &t->plans[t->buds[bi].plan];
    float o[3], u[3];
    memcpy(o, t->nodes[node].pos, sizeof o);
    glm_vec3_cross((float *)h, (float *)l, u);
    for (uint32_t i = t->buds[bi].cursor; i < plan->n && plan->a[i].metamer == k; i++) {
        Attach *a = &plan->a[i];
        t->buds[bi].cursor = i + 1;
        float ah[3], al[3];
        shoot_to_world(o, h, l, u, a->h, false, ah);
        shoot_to_world(o, h, l, u, a->l, false, al);
        if (a->kind == ATT_BUD) {
            Bud lat = {.node = node, .key = tree_child_key(t->buds[bi].key, (uint64_t)i + 1), .born = (uint16_t)year,
                       .kind = BUD_LATERAL, .alive = 1, .plan = -1};
            memcpy(lat.dir, ah, sizeof lat.dir);
            if (sot_normalize(lat.dir) && tree_add_bud(t, &lat) < 0) return false;
        } else if (a->kind == ATT_ORGAN) {
            TreeOrgan g = {.size = a->size, .node = node, .born = (uint16_t)year, .kind = a->organ, .material = a->material};
            shoot_to_world(o, h, l, u, a->pos, true, g.pos);
            memcpy(g.h, ah, sizeof g.h);
            memcpy(g.l, al, sizeof g.l);
            if (!tree_reserve(t, &t->organs, &t->organs_cap, t->norgans + 1, sizeof g)) return false;
            t->organs[t->norgans++] = g;
        } else if (a->kind == ATT_TWIG) {
            TreeTwig w = {.radius = a->size, .node = node, .born = (uint16_t)year, .material = a->material,
                          .parent = a->parent >= 0 ? plan->a[a->parent].placed : -1};
            shoot_to_world(o, h, l, u, a->from, true, w.from);
            shoot_to_world(o, h, l, u, a->pos, true, w.to);
            memcpy(w.h, ah, sizeof w.h);
            memcpy(w.l, al, sizeof w.l);
            w.detached = a->parent < 0 && glm_vec3_norm2(a->from) > 0;
            if (!tree_reserve(t, &t->twigs, &t->twigs_cap, t->ntwigs + 1, sizeof w)) return false;
            a->placed = (int32_t)t->ntwigs;
            t->twigs[t->ntwigs++] = w;
        } else *end = true;
    }
    return true;
}

typedef struct PlanJob {
    Forest *f;
    int year;
    int *status; /* per candidate */
} PlanJob;

static uint64_t shoot_seed(const Bud *b, int year) { return rng_stream(b->key, (uint64_t)year, 0x5400, 0).key; }

static void shoot_args(const Tree *t, const Bud *b, int year, double args[4]) {
    const Node *nd = &t->nodes[b->node];
    args[0] = b->len;
    args[1] = b->v;
    args[2] = nd->order + (b->kind == BUD_LATERAL);
    args[3] = year - t->start_year;
}

static void derive_plans(void *arg, size_t lo, size_t hi, int thread) {
    (void)thread;
    PlanJob *j = arg;
    for (size_t c = lo; c < hi; c++) {
        Tree *t = &j->f->trees[j->f->cand[c].tree];
        const Bud *b = &t->buds[j->f->cand[c].bud];
        if (!t->rule) continue;
        double args[4];
        shoot_args(t, b, j->year, args);
        j->status[c] = shoot_rule_plan(t->rule, args, shoot_seed(b, j->year), &t->plans[b->plan], NULL);
    }
}

/* Room for one plan per candidate of a tree with a rule (buffers kept from year to year). */
static bool plan_slots(Forest *f) {
    for (int i = 0; i < f->ntrees; i++) f->trees[i].nplans = 0;
    for (size_t c = 0; c < f->ncand; c++) {
        Tree *t = &f->trees[f->cand[c].tree];
        if (!t->rule) continue;
        if (t->nplans == t->plans_cap) {
            size_t cap = t->plans_cap ? 2 * t->plans_cap : 64;
            ShootPlan *p = realloc(t->plans, cap * sizeof *p);
            if (!p) return false;
            memset(p + t->plans_cap, 0, (cap - t->plans_cap) * sizeof *p);
            t->plans = p;
            t->plans_cap = cap;
        }
        t->buds[f->cand[c].bud].plan = (int32_t)t->nplans++;
        t->buds[f->cand[c].bud].cursor = 0;
        t->buds[f->cand[c].bud].grown = 0;
    }
    return true;
}

/* Every shoot of a tree with a rule gets its plan: the rule may shorten it, and what it
 * hangs on the shoot's base is hung now. Candidates left with nothing to grow go. */
static int make_plans(Forest *f, int year) {
    bool any = false;
    for (int i = 0; i < f->ntrees; i++) any |= f->trees[i].rule != NULL;
    if (!any) return SYL_OK;
    if (!plan_slots(f)) return SYL_ELIMIT;
    int *status = calloc(f->ncand ? f->ncand : 1, sizeof *status);
    if (!status) return SYL_ELIMIT;
    PlanJob j = {f, year, status};
    double t0 = forest_now();
    par_for(f->threads, f->ncand, 16, derive_plans, &j);
    if (f->stats) {
        f->stats->rule_s += forest_now() - t0;
        for (size_t c = 0; c < f->ncand; c++) f->stats->rule_shoots += f->trees[f->cand[c].tree].rule != NULL;
    }
    size_t keep = 0;
    int st = SYL_OK;
    for (size_t c = 0; c < f->ncand && !st; c++) {
        Candidate *cd = &f->cand[c];
        Tree *t = &f->trees[cd->tree];
        if (!t->rule) {
            f->cand[keep++] = *cd;
            continue;
        }
        if (status[c]) { /* derive it again to say why, in order, once */
            Bud *b = &t->buds[cd->bud];
            double args[4];
            shoot_args(t, b, year, args);
            diag_say(f->diag, f->sink, DIAG_ERROR, NULL, "the shoot rule failed on shoot(%g, %g, %g, %g) in year %d%s:", args[0],
                        args[1], args[2], args[3], year,
                        status[c] == SYL_ELIMIT ? " (a shoot's string may hold a million modules)" : "");
            shoot_rule_plan(t->rule, args, shoot_seed(b, year), &t->plans[b->plan], f->diag);
            st = status[c];
            f->reported = true;
            break;
        }
        Bud *b = &t->buds[cd->bud];
        const Node *nd = &t->nodes[b->node];
        float h[3], l[3];
        memcpy(h, b->dir, sizeof h);
        sot_transport(nd->h, nd->l, h, l);
        bool end = false;
        if (!hang(t, cd->bud, 0, b->node, h, l, year, &end)) st = SYL_ELIMIT;
        b = &t->buds[cd->bud];
        int m = t->plans[b->plan].metamers;
        if (m < b->len) b->len = m;
        if (b->len > 0) f->cand[keep++] = *cd;
        else if (end) b->alive = 0; /* a shoot of no metamers that ends its axis: a flower, say */
    }
    free(status);
    f->ncand = keep;
    return st;
}

/* The metamer candidate c grows: a node, its lateral buds, and the bud moves to its tip. */
static bool add_metamer(Forest *f, const Candidate *c, int year) {
    Tree *t = &f->trees[c->tree];
    const GrowParams *P = &t->P;
    Bud b = t->buds[c->bud];
    const Node *parent = &t->nodes[b.node];
    Node nd = {.parent = b.node, .main = -1, .born = (uint16_t)year};
    memcpy(nd.pos, c->to, sizeof nd.pos);
    memcpy(nd.h, c->dir, sizeof nd.h);
    sot_transport(parent->h, parent->l, nd.h, nd.l);
    if (b.kind == BUD_LATERAL) {
        nd.flags = NODE_LATERAL;
        nd.axis = t->axes++;
        nd.order = parent->order < UINT16_MAX ? parent->order + 1 : parent->order;
        nd.rank = 0;
    } else {
        nd.axis = parent->axis;
        nd.order = parent->order;
        nd.rank = parent->rank < UINT16_MAX ? parent->rank + 1 : parent->rank;
    }
    int32_t id = tree_add_node(t, &nd);
    if (id < 0) return false;
    if (b.kind == BUD_APICAL) t->nodes[b.node].main = id;
    int laterals = t->rule && shoot_rule_places_buds(t->rule) ? 0 : P->laterals;
    for (int k = 0; k < laterals; k++) {
        Bud lat = {.node = id, .key = tree_child_key(b.key, (uint64_t)k + 1), .born = (uint16_t)year,
                   .kind = BUD_LATERAL, .alive = 1, .plan = -1};
        phyl_lateral_dir(P, &t->nodes[id], k, lat.dir);
        if (tree_add_bud(t, &lat) < 0) return false;
    }
    Bud *moved = &t->buds[c->bud];
    moved->node = id;
    memcpy(moved->dir, c->dir, sizeof moved->dir);
    moved->kind = BUD_APICAL;
    moved->key = tree_child_key(b.key, 0);
    moved->len--;
    t->grown++;
    if (b.plan >= 0) {
        bool end = false;
        int k = ++t->buds[c->bud].grown;
        float h[3], l[3];
        memcpy(h, t->nodes[id].h, sizeof h);
        memcpy(l, t->nodes[id].l, sizeof l);
        if (!hang(t, c->bud, k, id, h, l, year, &end)) return false;
        if (end && t->buds[c->bud].len == 0) t->buds[c->bud].alive = 0;
    }
    if (f->env.cloud_on) markers_kill_near(&f->env.cloud, c->to);
    return true;
}

int forest_grow(Forest *f, int year) {
    f->ncand = 0;
    for (int i = 0; i < f->ntrees; i++) {
        const Tree *t = &f->trees[i];
        if (t->start_year >= year) continue;
        for (size_t k = 0; k < t->nb; k++)
            if (t->buds[k].alive && t->buds[k].len > 0 && !push_candidate(f, i, (int32_t)k)) return SYL_ELIMIT;
    }
    int st = make_plans(f, year);
    if (st) return st;
    for (int step = 0; f->ncand; step++) {
        double t0 = forest_now();
        st = space_step(f, year, step);
        if (st) return st;
        double dt = forest_now() - t0;
        if (f->stats) f->stats->space_s += dt, f->stats->growth_s -= dt; /* growth_s is taken whole by the caller */
        StepJob j = {f, year, step};
        par_for(f->threads, f->ncand, 512, directions, &j);
        size_t keep = 0;
        for (size_t c = 0; c < f->ncand; c++) {
            Candidate *cd = &f->cand[c];
            Bud *b = &f->trees[cd->tree].buds[cd->bud];
            if (cd->blocked) b->len = 0;
            else if (!add_metamer(f, cd, year)) return SYL_ELIMIT;
            if (f->trees[cd->tree].buds[cd->bud].len > 0) f->cand[keep++] = *cd;
        }
        f->ncand = keep;
        if (forest_too_many(f, year)) return SYL_ELIMIT; /* before a runaway year fills memory */
    }
    return SYL_OK;
}
