/* Tree storage: see tree.h. */
#include "sot/tree.h"
#include "util/array.h"

#include <stdlib.h>
#include <string.h>

#include "util/rng.h"

bool tree_init(Tree *t, const GrowParams *P, int index, const float base[3], int start_year) {
    memset(t, 0, sizeof *t);
    t->P = *P;
    t->index = index;
    t->start_year = start_year;
    memcpy(t->base, base, sizeof t->base);
    Node root = {.pos = {base[0], base[1], base[2]}, .h = {0, 1, 0}, .l = {1, 0, 0}, .parent = -1, .main = -1,
                 .axis = t->axes++, .born = 0};
    Bud bud = {.dir = {0, 1, 0}, .node = 0, .kind = BUD_APICAL, .alive = 1, .born = 0, .plan = -1,
               .key = rng_stream(P->seed, 0x5eed, 0, 0).key};
    if (P->rule[0] && P->from && !(t->rule = shoot_rule_new(P->from, P->rule))) return false;
    t->P.from = NULL; /* it need not outlive this call */
    return tree_add_node(t, &root) == 0 && tree_add_bud(t, &bud) == 0;
}

bool tree_reserve(Tree *t, void *arrp, size_t *cap, size_t need, size_t elem) {
    if (need <= *cap) return true;
    size_t c = *cap ? *cap * 2 : 1024;
    while (c < need) c *= 2;
    uint64_t more = (uint64_t)(c - *cap) * elem;
    if (!budget_charge(t->mem, more)) return false;
    size_t old = *cap;
    if (!array_reserve(arrp, cap, need, elem)) {
        budget_release(t->mem, more);
        return false;
    }
    t->charged += (uint64_t)(*cap - old) * elem;
    return true;
}

void tree_free(Tree *t) {
    budget_release(t->mem, t->charged);
    free(t->nodes);
    free(t->buds);
    free(t->acc);
    free(t->acc2);
    free(t->acc3);
    if (!t->rule_shared) shoot_rule_free(t->rule);
    for (size_t i = 0; i < t->plans_cap; i++) shoot_plan_free(&t->plans[i]);
    free(t->plans);
    free(t->organs);
    free(t->twigs);
    memset(t, 0, sizeof *t);
}

int32_t tree_add_node(Tree *t, const Node *n) {
    if (t->n >= INT32_MAX - 1 || !tree_reserve(t, &t->nodes, &t->cap, t->n + 1, sizeof *n)) return -1;
    t->nodes[t->n] = *n;
    return (int32_t)t->n++;
}

int32_t tree_add_bud(Tree *t, const Bud *b) {
    if (t->nb >= INT32_MAX - 1 || !tree_reserve(t, &t->buds, &t->bcap, t->nb + 1, sizeof *b)) return -1;
    t->buds[t->nb] = *b;
    return (int32_t)t->nb++;
}

bool tree_scratch(Tree *t) {
    if (t->n <= t->scratch_cap) return true;
    size_t cap = t->cap;
    uint64_t more = 3 * (uint64_t)(cap - t->scratch_cap) * sizeof(double);
    if (!budget_charge(t->mem, more)) return false;
    t->charged += more; /* released with the tree, even when a realloc below fails */
    double *a = realloc(t->acc, cap * sizeof *a);
    if (!a) return false;
    t->acc = a;
    double *b = realloc(t->acc2, cap * sizeof *b);
    if (!b) return false;
    t->acc2 = b;
    double *c = realloc(t->acc3, cap * sizeof *c);
    if (!c) return false;
    t->acc3 = c;
    t->scratch_cap = cap;
    return true;
}

bool tree_compact(Tree *t, float *dead) {
    int32_t *map = malloc((t->n ? t->n : 1) * sizeof *map);
    if (!map) return false;
    /* one pass: a node's main child (after it in the array) is remapped in its moved parent
     * when reached, to -1 when shed; until then the parent holds the old index, which no
     * later child's can equal once it has become a new one (new indices do not grow past old) */
    size_t k = 0;
    for (size_t i = 0; i < t->n; i++) {
        Node *nd = &t->nodes[i];
        int32_t p = nd->parent >= 0 ? map[nd->parent] : -1;
        Node *parent = p >= 0 ? &t->nodes[p] : NULL;
        if (nd->flags & NODE_DEAD) {
            map[i] = -1;
            if (parent && parent->main == (int32_t)i) parent->main = -1;
            if (dead) memcpy(dead, nd->pos, sizeof nd->pos), dead += 3;
            continue;
        }
        map[i] = (int32_t)k;
        if (parent && parent->main == (int32_t)i) parent->main = (int32_t)k;
        Node moved = *nd;
        moved.parent = p;
        t->nodes[k++] = moved;
    }
    t->n = k;
    size_t j = 0;
    for (size_t i = 0; i < t->nb; i++) {
        Bud b = t->buds[i];
        if (!b.alive || map[b.node] < 0) continue;
        b.node = map[b.node];
        t->buds[j++] = b;
    }
    t->nb = j;
    /* what the shoot rule hung on shed metamers goes with them */
    j = 0;
    for (size_t i = 0; i < t->norgans; i++) {
        TreeOrgan o = t->organs[i];
        if (map[o.node] < 0) continue;
        o.node = map[o.node];
        t->organs[j++] = o;
    }
    t->norgans = j;
    int32_t *tmap = malloc((t->ntwigs ? t->ntwigs : 1) * sizeof *tmap);
    if (!tmap) {
        free(map);
        return false;
    }
    j = 0;
    for (size_t i = 0; i < t->ntwigs; i++) {
        TreeTwig w = t->twigs[i];
        tmap[i] = -1;
        if (map[w.node] < 0 || (w.parent >= 0 && tmap[w.parent] < 0)) continue;
        w.node = map[w.node];
        if (w.parent >= 0) w.parent = tmap[w.parent];
        tmap[i] = (int32_t)j;
        t->twigs[j++] = w;
    }
    free(tmap);
    t->ntwigs = j;
    free(map);
    return true;
}

void tree_compact_buds(Tree *t) {
    size_t j = 0;
    for (size_t i = 0; i < t->nb; i++)
        if (t->buds[i].alive) t->buds[j++] = t->buds[i];
    t->nb = j;
}
