/* D8 flow (O'Callaghan & Mark 1984) on the filled heights, and its accumulation. Each cell
 * drains to the neighbour of the steepest drop per distance (a diagonal is √2 cells away);
 * a cell with no lower neighbour — on a flat, or in a filled depression — drains to the cell
 * the flood reached it from, which leads to the spill point; an edge cell with no lower
 * neighbour drains off the grid. Accumulation follows the directions from the sources down
 * (Kahn's order by the number of cells draining in), so it needs no sorting. */
#include <math.h>
#include <stdlib.h>

#include "terrain/terrain.h"
#include "util/budget.h"
#include "util/parallel.h"

typedef struct Job {
    const Terrain *t;
    const float *filled;
    const uint8_t *parent;
    uint8_t *dir;
} Job;

static void rows(void *ctx, size_t lo, size_t hi, int thread) {
    (void)thread;
    const Job *j = ctx;
    int nx = j->t->nx, nz = j->t->nz;
    for (size_t k = lo; k < hi; k++)
        for (int i = 0; i < nx; i++) {
            size_t c = k * (size_t)nx + (size_t)i;
            double best = 0;
            int to = -1;
            for (int d = 0; d < 8; d++) {
                int ni = i + terrain_d8_di[d], nk = (int)k + terrain_d8_dk[d];
                if (ni < 0 || nk < 0 || ni >= nx || nk >= nz) continue;
                double drop = (double)j->filled[c] - j->filled[(size_t)nk * (size_t)nx + (size_t)ni];
                if (d & 1) drop *= M_SQRT1_2;
                if (drop > best) best = drop, to = d; /* the first of equal drops */
            }
            j->dir[c] = to >= 0 ? (uint8_t)to : j->parent[c];
        }
}

void terrain_d8(const Terrain *t, const float *filled, const uint8_t *parent, uint8_t *dir, int threads) {
    Job j = {t, filled, parent, dir};
    par_for(threads, (size_t)t->nz, 16, rows, &j);
}

static size_t down(const Terrain *t, size_t c, uint8_t d) {
    size_t nx = (size_t)t->nx;
    return (size_t)((long)(c / nx) + terrain_d8_dk[d]) * nx + (size_t)((long)(c % nx) + terrain_d8_di[d]);
}

int terrain_accumulate(Terrain *t, const uint8_t *dir, float *acc, const SylSink *sink) {
    size_t n = (size_t)t->nx * (size_t)t->nz;
    uint64_t bytes = (uint64_t)n * (sizeof(uint32_t) + 1);
    if (!budget_charge(terrain_budget(t), bytes)) {
        sink_error(sink, "the flow accumulation needs more than the memory limit (--max-memory)");
        return SYL_ELIMIT;
    }
    uint8_t *in = calloc(n, 1); /* at most 8 neighbours drain into a cell */
    uint32_t *queue = malloc(n * sizeof *queue);
    if (!in || !queue) {
        free(in), free(queue);
        budget_release(terrain_budget(t), bytes);
        sink_error(sink, "out of memory for the flow accumulation");
        return SYL_ELIMIT;
    }
    for (size_t c = 0; c < n; c++) {
        acc[c] = 1;
        if (dir[c] != TERRAIN_OUT) in[down(t, c, dir[c])]++;
    }
    size_t head = 0, tail = 0;
    for (size_t c = 0; c < n; c++)
        if (!in[c]) queue[tail++] = (uint32_t)c;
    while (head < tail) {
        size_t c = queue[head++];
        if (dir[c] == TERRAIN_OUT) continue;
        size_t m = down(t, c, dir[c]);
        acc[m] += acc[c];
        if (!--in[m]) queue[tail++] = (uint32_t)m;
    }
    free(in), free(queue);
    budget_release(terrain_budget(t), bytes);
    return SYL_OK;
}
