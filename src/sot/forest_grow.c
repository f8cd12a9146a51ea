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
#include "util/parallel.h"

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
    for (int k = 0; k < P->laterals; k++) {
        Bud lat = {.node = id, .key = tree_child_key(b.key, (uint64_t)k + 1), .born = (uint16_t)year,
                   .kind = BUD_LATERAL, .alive = 1};
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
    for (int step = 0; f->ncand; step++) {
        double t0 = forest_now();
        int st = space_step(f, year, step);
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
