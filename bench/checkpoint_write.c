/* bench/run's section mpi: the time to write and to read back a checkpoint of N synthetic
 * plants (sylva ecosystem --checkpoint). Usage: checkpoint_write N PATH; prints
 * "write: WALL CPU" and "read: WALL CPU" (seconds) and "bytes: B". */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "sylva/ecosystem.h"

static double now(clockid_t c) {
    struct timespec ts;
    clock_gettime(c, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

int main(int argc, char **argv) {
    if (argc != 3) return 2;
    size_t n = (size_t)strtoull(argv[1], NULL, 10);
    SylEcoPlant *p = calloc(n ? n : 1, sizeof *p);
    static SylEcoYear years[100];
    if (!p) return 3;
    for (size_t j = 0; j < n; j++)
        p[j] = (SylEcoPlant){.id = 1 + 3 * (uint64_t)j, .x = (float)(j % 10000), .z = (float)(j / 10000), .height = 5,
                             .vigour = 0.5f, .age = 40, .species = (uint8_t)(j % 4)};
    for (int y = 0; y < 100; y++) years[y].year = y + 1;
    SylEcoCheckpoint c = {.model_hash = 1, .year = 100, .years = years, .plants = p, .nplants = n};
    double w = now(CLOCK_MONOTONIC), u = now(CLOCK_PROCESS_CPUTIME_ID);
    if (syl_ecosystem_checkpoint_write(argv[2], &c, stderr)) return 4;
    printf("write: %.3f %.3f\n", now(CLOCK_MONOTONIC) - w, now(CLOCK_PROCESS_CPUTIME_ID) - u);
    free(p);
    SylEcoCheckpoint r;
    w = now(CLOCK_MONOTONIC), u = now(CLOCK_PROCESS_CPUTIME_ID);
    if (syl_ecosystem_checkpoint_read(argv[2], &r, stderr)) return 4;
    printf("read: %.3f %.3f\n", now(CLOCK_MONOTONIC) - w, now(CLOCK_PROCESS_CPUTIME_ID) - u);
    printf("bytes: %llu\n", (unsigned long long)(64 + 100 * 644 + n * sizeof(SylEcoPlant) + 8));
    syl_ecosystem_checkpoint_free(&r);
    return 0;
}
