/* Parallel for over contiguous chunks, one per thread. */
#include "util/parallel.h"

#include "util/pool.h"

#include <pthread.h>
#include <stdbool.h>
#include <unistd.h>

typedef struct Chunk {
    ParFn fn;
    void *ctx;
    size_t lo, hi;
    int thread;
} Chunk;

static void *run_chunk(void *arg) {
    Chunk *c = arg;
    c->fn(c->ctx, c->lo, c->hi, c->thread);
    return NULL;
}

int par_threads(int threads) {
    if (threads > 0) return threads > 256 ? 256 : threads;
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > 256 ? 256 : (int)n;
}

/* A pool for the one run: its threads start, run and are joined as pool_run's are, so the
 * two ways of running k = 0..n-1 side by side stay one mechanism. */
void par_run(int n, void (*fn)(void *ctx, int k), void *ctx) {
    if (n > 256) n = 256;
    Pool *p = n > 1 ? pool_new(n) : NULL;
    if (!p) { /* one job, or no memory for the pool: each on the caller */
        for (int k = 0; k < n; k++) fn(ctx, k);
        return;
    }
    pool_run(p, n, fn, ctx);
    pool_free(p);
}

void par_for(int threads, size_t n, size_t min_per_thread, ParFn fn, void *ctx) {
    if (n == 0) return;
    int t = par_threads(threads);
    if (min_per_thread < 1) min_per_thread = 1;
    if ((size_t)t > n / min_per_thread) t = (int)(n / min_per_thread);
    if (t <= 1) {
        fn(ctx, 0, n, 0);
        return;
    }
    enum { MAX = 256 };
    Chunk ch[MAX];
    pthread_t th[MAX];
    int started[MAX] = {0};
    for (int i = 0; i < t; i++)
        ch[i] = (Chunk){fn, ctx, n * (size_t)i / (size_t)t, n * (size_t)(i + 1) / (size_t)t, i};
    for (int i = 1; i < t; i++) started[i] = pthread_create(&th[i], NULL, run_chunk, &ch[i]) == 0;
    run_chunk(&ch[0]);
    for (int i = 1; i < t; i++) {
        if (started[i]) pthread_join(th[i], NULL);
        else run_chunk(&ch[i]);
    }
}
