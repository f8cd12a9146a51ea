/* A pool of threads waiting between runs on one condition variable. */
#include "util/pool.h"

#include <pthread.h>
#include <stdbool.h>
#include <stdlib.h>

struct Pool;

typedef struct Worker {
    struct Pool *pool;
    int k;
    pthread_t th;
} Worker;

struct Pool {
    pthread_mutex_t mu;
    pthread_cond_t go, done;
    int threads, started;   /* started: workers 1..started-1 run */
    unsigned long gen;      /* one more for each run */
    int n, pending;         /* this run's k count, and the workers not finished with it */
    bool quit;
    void (*fn)(void *ctx, int k);
    void *ctx;
    Worker w[];
};

static void *worker_main(void *arg) {
    Worker *w = arg;
    struct Pool *p = w->pool;
    unsigned long seen = 0;
    pthread_mutex_lock(&p->mu);
    for (;;) {
        while (!p->quit && p->gen == seen) pthread_cond_wait(&p->go, &p->mu);
        if (p->quit) break;
        seen = p->gen;
        if (w->k >= p->n) continue; /* not needed in this run */
        void (*fn)(void *, int) = p->fn;
        void *ctx = p->ctx;
        pthread_mutex_unlock(&p->mu);
        fn(ctx, w->k);
        pthread_mutex_lock(&p->mu);
        if (--p->pending == 0) pthread_cond_signal(&p->done);
    }
    pthread_mutex_unlock(&p->mu);
    return NULL;
}

Pool *pool_new(int threads) {
    if (threads < 1) threads = 1;
    if (threads > 256) threads = 256;
    struct Pool *p = calloc(1, sizeof *p + sizeof(Worker) * (size_t)threads);
    if (!p) return NULL;
    p->threads = threads;
    p->started = 1;
    pthread_mutex_init(&p->mu, NULL);
    pthread_cond_init(&p->go, NULL);
    pthread_cond_init(&p->done, NULL);
    return p;
}

void pool_run(Pool *p, int n, void (*fn)(void *ctx, int k), void *ctx) {
    if (n > p->threads) n = p->threads;
    if (n <= 1) {
        if (n == 1) fn(ctx, 0);
        return;
    }
    /* the workers are started when first needed, in order: one that fails stops the rest */
    while (p->started < n) {
        Worker *w = &p->w[p->started];
        w->pool = p;
        w->k = p->started;
        if (pthread_create(&w->th, NULL, worker_main, w)) break;
        p->started++;
    }
    int m = p->started < n ? p->started : n; /* k = 1..m-1 run on workers */
    pthread_mutex_lock(&p->mu);
    p->fn = fn;
    p->ctx = ctx;
    p->n = m;
    p->pending = m - 1;
    p->gen++;
    pthread_cond_broadcast(&p->go);
    pthread_mutex_unlock(&p->mu);
    fn(ctx, 0);
    for (int k = m; k < n; k++) fn(ctx, k);
    pthread_mutex_lock(&p->mu);
    while (p->pending) pthread_cond_wait(&p->done, &p->mu);
    pthread_mutex_unlock(&p->mu);
}

void pool_free(Pool *p) {
    if (!p) return;
    pthread_mutex_lock(&p->mu);
    p->quit = true;
    pthread_cond_broadcast(&p->go);
    pthread_mutex_unlock(&p->mu);
    for (int k = 1; k < p->started; k++) pthread_join(p->w[k].th, NULL);
    pthread_mutex_destroy(&p->mu);
    pthread_cond_destroy(&p->go);
    pthread_cond_destroy(&p->done);
    free(p);
}
