/* Parallel for: split [0, n) into contiguous chunks, one per thread. Each index is handled
 * by exactly one call, and work that writes only to its own indices gives the same result
 * whatever the thread count. Threads are started per call and joined before it returns. */
#ifndef SYL_PARALLEL_H
#define SYL_PARALLEL_H
#include <stddef.h>

/* fn(ctx, lo, hi, thread) handles indices lo..hi-1; thread is 0..threads-1. threads <= 0:
 * all cores. Fewer than min_per_thread indices per thread: fewer threads. */
typedef void (*ParFn)(void *ctx, size_t lo, size_t hi, int thread);
void par_for(int threads, size_t n, size_t min_per_thread, ParFn fn, void *ctx);
int par_threads(int threads); /* threads <= 0: the number of cores (at most 256): the one count */
/* fn(ctx, k) for k = 0..n-1 at once: k = 0 on the calling thread, each other on a thread of its
 * own (one that cannot start runs on the caller after k = 0); returns when all have. For work
 * that is not a range of indices: workers taking tiles from a queue, jobs beside the caller's. */
void par_run(int n, void (*fn)(void *ctx, int k), void *ctx);

#endif
