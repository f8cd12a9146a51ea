/* The most nodes and leaves a Pafčo tree can have, from its parameters alone (issue 29): the
 * builder's own walk (build.c) with every random length at its largest, so that a tree past
 * the memory budget is refused before a node of it is made, and the arrays are reserved once. */
#include "pafco/pafco.h"

#include <math.h>

#include "sylva/sylva.h"

typedef struct Count {
    double nodes, branches, last; /* last: the nodes of the last generation's branches */
    double cap;                   /* stop once nodes pass it: the answer is then "too many" */
    int last_gen;
} Count;

/* A branch of generation gen and length at most len, its children included. A child's length
 * falls with its place t = k / m on the parent; with m at its largest, t is at its smallest. */
static void walk(const PafcoParams *P, int gen, double len, Count *c) {
    if (!(len > 0) || c->nodes > c->cap) return;
    long m = lround(P->seg_branch * len);
    if (m < 2) m = 2;
    c->nodes += (double)m, c->branches += 1;
    if (gen == c->last_gen) c->last += (double)m;
    int child = gen + 1;
    if (child > 3 || !P->gen[child - 1]) return;
    double extent = gen == 1 ? P->nextg : 1;
    for (long k = 1; k < m && c->nodes <= c->cap; k++) {
        double t = (double)k / (double)m;
        if (t > extent + 1e-9) break;
        walk(P, child, fmin(P->maxlen[child - 1] * (1 - t), len), c);
    }
}

void pafco_bounds(const PafcoParams *P, double cap, double *nodes, double *leaves) {
    Count c = {.cap = cap, .last_gen = P->gen[1] ? (P->gen[2] ? 3 : 2) : 1};
    const double H = P->height;
    long n = lround(P->seg_trunk * H);
    if (n < 2) n = 2;
    c.nodes = (double)(n + 1);
    double crown = P->crown_ratio <= 1 ? P->crown_ratio * H : H / P->crown_ratio, base = H - crown;
    double longest = P->width_ratio * H;
    for (long i = 1; i < n && c.nodes <= cap; i++) {
        double y = H * (double)i / (double)n;
        if (y < base - 1e-9) continue;
        double f = crown > 0 ? (y - base) / crown : 1;
        double bound = longest * pafco_crown_profile(P->round_crown, f);
        if (bound < 0.01) continue; /* every branch there is shorter than 1 cm: none grows */
        for (int w = 0; w < P->whorl && c.nodes <= cap; w++) walk(P, 1, bound, &c);
    }
    *nodes = c.nodes;
    *leaves = 0;
    if (P->sph_leaves && P->leaf_size > 0) *leaves += (c.branches + 1) * (double)lround(P->sph_count);
    if (P->bil_leaves && P->bil_length > 0) *leaves += c.last;
}

bool pafco_fits(const PafcoParams *P, const Budget *mem, double *nodes, double *leaves, double *bytes, bool *partial) {
    uint64_t used = mem ? syl_budget_used(mem) : 0, limit = mem ? mem->limit : UINT64_MAX;
    double room = limit > used ? (double)(limit - used) : 0, cap = room / sizeof(SylNode) + 1;
    pafco_bounds(P, cap, nodes, leaves);
    if (partial) *partial = *nodes > cap;
    *bytes = *nodes * sizeof(SylNode) + *leaves * sizeof(SylOrgan);
    return *bytes <= room;
}
