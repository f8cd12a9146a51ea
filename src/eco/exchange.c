/* The in-process transport of SylEcoExchange: a mailbox per (channel, receiver, sender)
 * that a post replaces, holding the sender's pointer. The driver's join of its threads is the
 * barrier. An MPI transport would post with MPI_Isend and take after MPI_Waitall. */
#include <stdlib.h>
#include <string.h>

#include "eco/eco.h"

typedef struct Box {
    const SylEcoPlant *p;
    size_t n;
} Box;

struct EcoLocal {
    int ntiles;
    Box *box; /* [channel][to][from] */
};

static Box *box_of(EcoLocal *l, int channel, int to, int from) {
    return &l->box[((size_t)channel * l->ntiles + (size_t)to) * l->ntiles + (size_t)from];
}

/* In one process nothing needs copying: the sender's buffer stays put until the receiver
 * has taken it (the driver's next phase). */
static void local_post(void *ctx, int channel, int from, int to, const SylEcoPlant *p, size_t n) {
    Box *b = box_of(ctx, channel, to, from);
    b->p = p;
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

void eco_local_free(EcoLocal *l) {
    if (!l) return;
    free(l->box);
    free(l);
}
