/* A pool of threads that lives as long as its owner (one derivation): the threads are
 * started on the first run that needs them and wait between runs, so a pass of a few
 * hundred microseconds does not pay for creating them. No global state: each owner its own. */
#ifndef SYL_POOL_H
#define SYL_POOL_H

typedef struct Pool Pool;

/* A pool of up to `threads` (1..256) threads, the caller's included; NULL when refused. */
Pool *pool_new(int threads);
/* fn(ctx, k) for k = 0..n-1 (n <= the pool's threads), k = 0 on the calling thread; returns
 * when all have. A thread that cannot start leaves its k to the caller, after k = 0. */
void pool_run(Pool *p, int n, void (*fn)(void *ctx, int k), void *ctx);
void pool_free(Pool *p);

#endif
