/* The in-process transport of SylEcoExchange: a mailbox per (channel, receiver, sender)
 * that a post replaces. The driver's join of its threads is the barrier. An MPI transport
 * would post with MPI_Isend and take after MPI_Waitall. */
#include <stdlib.h>
#include <string.h>

#include "eco/eco.h"

typedef struct Box {
    SylEcoPlant *p;
    size_t n, cap;
} Box;

struct EcoLocal {
    int ntiles;
    int failed;
    Box *box; /* [channel][to][from] */
};

static Box *box_of(EcoLocal *l, int channel, int to, int from) {
    return &l->box[((size_t)channel * l->ntiles + (size_t)to) * l->ntiles + (size_t)from];
}

static void local_post(void *ctx, int channel, int from, int to, const SylEcoPlant *p, size_t n) {
    EcoLocal *l = ctx;
    Box *b = box_of(l, channel, to, from);
    if (n > b->cap) {
        size_t cap = n + n / 2 + 16;
        SylEcoPlant *q = realloc(b->p, cap * sizeof *q);
        if (!q) {
            __atomic_store_n(&l->failed, 1, __ATOMIC_RELAXED);
            b->n = 0;
            return;
        }
        b->p = q;
        b->cap = cap;
    }
    if (n) memcpy(b->p, p, n * sizeof *p);
    b->n = n;
}

static void local_barrier(void *ctx) { (void)ctx; }

static const SylEcoPlant *local_take(void *ctx, int channel, int to, int from, size_t *n) {
    Box *b = box_of(ctx, channel, to, from);
    *n = b->n;
    return b->p;
}

EcoLocal *eco_local_new(int ntiles, SylEcoExchange *ops) {
    EcoLocal *l = calloc(1, sizeof *l);
    if (!l) return NULL;
    l->ntiles = ntiles;
    l->box = calloc((size_t)2 * ntiles * ntiles, sizeof *l->box);
    if (!l->box) {
        free(l);
        return NULL;
    }
    *ops = (SylEcoExchange){.post = local_post, .barrier = local_barrier, .take = local_take, .ctx = l};
    return l;
}

bool eco_local_failed(const EcoLocal *l) { return l && __atomic_load_n(&l->failed, __ATOMIC_RELAXED); }

size_t eco_local_bytes(const EcoLocal *l) {
    size_t b = 0;
    for (size_t i = 0; l && i < (size_t)2 * l->ntiles * l->ntiles; i++) b += l->box[i].cap * sizeof(SylEcoPlant);
    return b;
}

void eco_local_free(EcoLocal *l) {
    if (!l) return;
    for (size_t i = 0; i < (size_t)2 * l->ntiles * l->ntiles; i++) free(l->box[i].p);
    free(l->box);
    free(l);
}
