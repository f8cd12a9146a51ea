/* Depression filling by priority-flood (Barnes, Lehman & Mulla 2014, "Priority-Flood: an
 * optimal depression-filling and watershed-labeling algorithm", their Algorithm 2): the
 * edge cells seed a min-heap; the lowest open cell is taken, and each neighbour not yet
 * reached is raised to at least its height. A raised neighbour (in a depression, or on a
 * flat) goes to a plain queue that is emptied first, which spares the heap. Ties in the
 * heap are broken by the order cells entered it, so the result is one and the same. */
#include <stdlib.h>
#include <string.h>

#include "terrain/terrain.h"
#include "util/budget.h"

const int terrain_d8_di[8] = {1, 1, 0, -1, -1, -1, 0, 1};
const int terrain_d8_dk[8] = {0, 1, 1, 1, 0, -1, -1, -1};

typedef struct Item {
    float h;
    uint32_t seq, cell;
} Item;

static bool before(const Item *a, const Item *b) { return a->h < b->h || (a->h == b->h && a->seq < b->seq); }

static void push(Item *heap, size_t *n, Item it) {
    size_t c = (*n)++;
    while (c > 0) {
        size_t p = (c - 1) / 2;
        if (!before(&it, &heap[p])) break;
        heap[c] = heap[p];
        c = p;
    }
    heap[c] = it;
}

static Item pop(Item *heap, size_t *n) {
    Item top = heap[0], last = heap[--*n];
    size_t c = 0;
    for (;;) {
        size_t l = 2 * c + 1, best = c;
        const Item *b = &last;
        if (l < *n && before(&heap[l], b)) best = l, b = &heap[l];
        if (l + 1 < *n && before(&heap[l + 1], b)) best = l + 1;
        if (best == c) break;
        heap[c] = heap[best];
        c = best;
    }
    if (*n) heap[c] = last;
    return top;
}

int terrain_fill(Terrain *t, float *filled, uint8_t *parent, const SylSink *sink) {
    size_t nx = (size_t)t->nx, nz = (size_t)t->nz, n = nx * nz;
    /* Each cell enters the heap or the queue once: n items and n cells at most. */
    uint64_t bytes = (uint64_t)n * (sizeof(Item) + sizeof(uint32_t) + 1);
    if (!budget_charge(terrain_budget(t), bytes)) {
        sink_error(sink, "filling the terrain's depressions needs more than the memory limit "
                                "(--max-memory)\n");
        return SYL_ELIMIT;
    }
    Item *heap = malloc(n * sizeof *heap);
    uint32_t *queue = malloc(n * sizeof *queue);
    uint8_t *done = calloc(n, 1);
    if (!heap || !queue || !done) {
        free(heap), free(queue), free(done);
        budget_release(terrain_budget(t), bytes);
        sink_error(sink, "out of memory filling the terrain's depressions");
        return SYL_ELIMIT;
    }
    memcpy(filled, t->height, n * sizeof(float));
    size_t nh = 0, qhead = 0, qtail = 0;
    uint32_t seq = 0;
    for (size_t k = 0; k < nz; k++)
        for (size_t i = 0; i < nx; i++)
            if (k == 0 || i == 0 || k == nz - 1 || i == nx - 1) {
                size_t c = k * nx + i;
                done[c] = 1;
                parent[c] = TERRAIN_OUT;
                push(heap, &nh, (Item){filled[c], seq++, (uint32_t)c});
            }
    while (qhead < qtail || nh) {
        size_t c = qhead < qtail ? queue[qhead++] : pop(heap, &nh).cell;
        int i = (int)(c % nx), k = (int)(c / nx);
        for (int d = 0; d < 8; d++) {
            int ni = i + terrain_d8_di[d], nk = k + terrain_d8_dk[d];
            if (ni < 0 || nk < 0 || ni >= (int)nx || nk >= (int)nz) continue;
            size_t m = (size_t)nk * nx + (size_t)ni;
            if (done[m]) continue;
            done[m] = 1;
            parent[m] = (uint8_t)((d + 4) & 7); /* from m back to c */
            if (filled[m] <= filled[c]) {
                filled[m] = filled[c];
                queue[qtail++] = (uint32_t)m;
            } else push(heap, &nh, (Item){filled[m], seq++, (uint32_t)m});
        }
    }
    free(heap), free(queue), free(done);
    budget_release(terrain_budget(t), bytes);
    return SYL_OK;
}
