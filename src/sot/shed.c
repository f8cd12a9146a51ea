/* Shedding and pipe radii: see shed.h. */
#include "sot/shed.h"

#include <math.h>
#include <string.h>

bool pipe_areas(Tree *t) {
    if (!tree_scratch(t)) return false;
    double *A = t->acc, *kids = t->acc2;
    const double tip = pow(t->P.tip_radius, t->P.pipe_exponent);
    for (size_t i = 0; i < t->n; i++) A[i] = t->nodes[i].pipe, kids[i] = 0;
    for (size_t i = t->n; i-- > 0;) {
        if (kids[i] == 0) A[i] += tip;
        int32_t p = t->nodes[i].parent;
        if (p >= 0) A[p] += A[i], kids[p] += 1;
    }
    return true;
}

/* A node's light: from the shadow grid when there is one, else as forest_node_light left it. */
static inline __attribute__((always_inline)) double node_light(const Tree *t, size_t i, const ShadowGrid *g) {
    if (!g) return t->nodes[i].light;
    float q = g->p.full - shadow_value(g, shadow_index(g, t->nodes[i].pos)) + g->p.a; /* shadow_light */
    return q > 0 ? q : 0;
}

size_t shed_mark(Tree *t, const ShadowGrid *shadow) {
    const GrowParams *P = &t->P;
    bool by_light = P->shed_threshold > 0, bare = P->bare_trunk > 0;
    if (!by_light && !bare) return 0;
    if (!tree_scratch(t)) return (size_t)-1;
    double *A = t->acc, *light = t->acc2, *count = t->acc3;
    /* light, size and pipe area of every branch, toward the base in one pass. A node's sums
     * start from its own values when its first child (the last in the array) reaches it,
     * so the additions run in the same order as from sums set up front; a node no child
     * reached (count still 0) is a tip. */
    const double tip = pow(P->tip_radius, P->pipe_exponent);
    memset(count, 0, t->n * sizeof *count);
    for (size_t i = t->n; i-- > 1;) {
        const Node *nd = &t->nodes[i];
        if (count[i] == 0) A[i] = (double)nd->pipe + tip, light[i] = node_light(t, i, shadow), count[i] = 1;
        int32_t p = nd->parent;
        if (count[p] == 0) {
            A[p] = t->nodes[p].pipe + A[i];
            light[p] = node_light(t, (size_t)p, shadow) + light[i];
            count[p] = 1 + count[i];
        } else {
            A[p] += A[i];
            light[p] += light[i];
            count[p] += count[i];
        }
    }
    /* from the base up: a failing branch goes whole */
    size_t marked = 0;
    for (size_t i = 1; i < t->n; i++) {
        Node *nd = &t->nodes[i];
        const Node *parent = &t->nodes[nd->parent];
        if (parent->flags & NODE_DEAD) {
            nd->flags |= NODE_DEAD;
            marked++;
            continue;
        }
        if (!(nd->flags & NODE_LATERAL)) continue;
        bool shed = by_light && light[i] < P->shed_threshold * count[i];
        if (bare && parent->order == 0 && parent->pos[1] - t->base[1] < P->bare_trunk) shed = true;
        if (!shed) continue;
        nd->flags |= NODE_DEAD;
        marked++;
        t->nodes[nd->parent].pipe += (float)A[i];
        t->shed_branches++;
    }
    if (bare)
        for (size_t i = 0; i < t->nb; i++) {
            Bud *b = &t->buds[i];
            const Node *nd = &t->nodes[b->node];
            if (b->kind == BUD_LATERAL && nd->order == 0 && nd->pos[1] - t->base[1] < P->bare_trunk) b->alive = 0;
        }
    t->shed_metamers += marked;
    return marked;
}
