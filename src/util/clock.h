/* Seconds of a clock, for the figures --stats prints: wall (CLOCK_MONOTONIC) and processor
 * time of the whole process (every thread). */
#ifndef SYL_UTIL_CLOCK_H
#define SYL_UTIL_CLOCK_H
#include <time.h>

static inline double clock_seconds(clockid_t id) {
    struct timespec ts;
    clock_gettime(id, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}
static inline double clock_wall(void) { return clock_seconds(CLOCK_MONOTONIC); }
static inline double clock_cpu(void) { return clock_seconds(CLOCK_PROCESS_CPUTIME_ID); }

#endif
