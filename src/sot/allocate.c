/* Allocation: see allocate.h. */
#include "sot/allocate.h"

#include <math.h>
#include <stdlib.h>

#include "sot/phyllotaxis.h"

void alloc_demand(Tree *t, int year) {
    const GrowParams *P = &t->P;
    for (size_t i = 0; i < t->nb; i++) {
        Bud *b = &t->buds[i];
        b->z = 0;
        b->v = 0;
        b->len = 0;
        if (!alloc_candidate(b, year)) continue;
        float g = b->kind == BUD_LATERAL ? phyl_gravimorphism(P, t->nodes[b->node].h, b->dir) : 1;
        float c = P->sensitivity;
        b->z = g * (c == 1 ? b->q : c == 0 ? 1 : powf(b->q, c));
    }
}

static bool borchert_honda(Tree *t, int year) {
    const double lambda = t->P.lambda;
    if (!tree_scratch(t)) return false;
    double *demand = t->acc, *fm = t->acc2, *fl = t->acc3;
    for (size_t i = 0; i < t->n; i++) demand[i] = fm[i] = 0;
    for (size_t i = 0; i < t->nb; i++) { /* fm holds each node's apical demand for now */
        const Bud *b = &t->buds[i];
        if (!alloc_candidate(b, year)) continue;
        demand[b->node] += b->z;
        if (b->kind == BUD_APICAL) fm[b->node] += b->z;
    }
    for (size_t i = t->n; i-- > 1;) demand[t->nodes[i].parent] += demand[i];
    for (size_t i = 0; i < t->n; i++) {
        const Node *nd = &t->nodes[i];
        double v;
        if (nd->parent < 0) v = t->P.alpha * demand[i];
        else v = (t->nodes[nd->parent].main == (int32_t)i ? fm[nd->parent] : fl[nd->parent]) * demand[i];
        double M = nd->main >= 0 ? demand[nd->main] : fm[i], L = demand[i] - M;
        if (L < 0) L = 0;
        double den = lambda * M + (1 - lambda) * L;
        /* per unit of demand: the main axis' share and the laterals' */
        fm[i] = den > 0 ? v * lambda / den : 0;
        fl[i] = den > 0 ? v * (1 - lambda) / den : 0;
    }
    for (size_t i = 0; i < t->nb; i++) {
        Bud *b = &t->buds[i];
        if (!alloc_candidate(b, year)) continue;
        b->v = (b->kind == BUD_APICAL ? fm[b->node] : fl[b->node]) * b->z;
    }
    return true;
}

typedef struct Ranked {
    float z;
    uint32_t bud;
} Ranked;

static int by_demand(const void *a, const void *b) {
    const Ranked *x = a, *y = b;
    if (x->z != y->z) return x->z > y->z ? -1 : 1;
    return x->bud < y->bud ? -1 : x->bud > y->bud;
}

static bool priority(Tree *t, int year) {
    const GrowParams *P = &t->P;
    size_t n = 0;
    for (size_t i = 0; i < t->nb; i++) n += alloc_candidate(&t->buds[i], year);
    if (!n) return true;
    Ranked *r = malloc(n * sizeof *r);
    if (!r) return false;
    size_t k = 0;
    double total = 0;
    for (size_t i = 0; i < t->nb; i++)
        if (alloc_candidate(&t->buds[i], year)) {
            r[k++] = (Ranked){t->buds[i].z, (uint32_t)i};
            total += t->buds[i].z;
        }
    qsort(r, n, sizeof *r, by_demand);
    double sum = 0;
    for (size_t j = 0; j < n; j++) {
        double x = n > 1 ? (double)j / (double)(n - 1) : 0;
        double w = P->kappa > 0 && x < P->kappa ? P->wmax - (P->wmax - P->wmin) * x / P->kappa : P->wmin;
        t->buds[r[j].bud].v = w * r[j].z; /* the weighted demand, for now */
        sum += w * r[j].z;
    }
    double scale = sum > 0 ? P->alpha * total / sum : 0;
    for (size_t j = 0; j < n; j++) t->buds[r[j].bud].v *= scale;
    free(r);
    return true;
}

bool alloc_resources(Tree *t, int year) {
    return t->P.alloc == ALLOC_PRIORITY ? priority(t, year) : borchert_honda(t, year);
}

void alloc_shoots(Tree *t, int year) {
    const GrowParams *P = &t->P;
    double vmax = 0;
    for (size_t i = 0; i < t->nb; i++)
        if (alloc_candidate(&t->buds[i], year) && t->buds[i].v > vmax) vmax = t->buds[i].v;
    for (size_t i = 0; i < t->nb; i++) {
        Bud *b = &t->buds[i];
        b->len = 0;
        b->seg = P->internode;
        if (!alloc_candidate(b, year) || !(b->v > 0)) continue;
        if (P->shoot == SHOOT_RELATIVE) {
            b->len = (int32_t)floor(b->v / (vmax * (1 + 1e-9) + 1e-300) * (P->shoot_max + 1));
        } else {
            double n = floor(b->v);
            if (n > P->shoot_max) n = P->shoot_max;
            b->len = (int32_t)n;
            if (n > 0) b->seg = P->internode * (float)fmin(b->v / n, 2.0);
        }
        if (b->len > P->shoot_max) b->len = P->shoot_max;
    }
}
