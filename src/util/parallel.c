/* Parallel for over contiguous chunks, one per thread. */
#include "util/parallel.h"

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

typedef struct Job {
    void (*fn)(void *ctx, int k);
    void *ctx;
    int k;
} Job;

static void *run_job(void *arg) {
    Job *j = arg;
    j->fn(j->ctx, j->k);
    return NULL;
}

void par_run(int n, void (*fn)(void *ctx, int k), void *ctx) {
    enum { MAX = 256 };
    if (n > MAX) n = MAX;
    Job job[MAX];
    pthread_t th[MAX];
    bool started[MAX] = {false};
    for (int k = 0; k < n; k++) job[k] = (Job){fn, ctx, k};
    for (int k = 1; k < n; k++) started[k] = pthread_create(&th[k], NULL, run_job, &job[k]) == 0;
    if (n > 0) fn(ctx, 0);
    for (int k = 1; k < n; k++) {
        if (started[k]) pthread_join(th[k], NULL);
        else fn(ctx, k);
    }
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
