/* A build without MPI (make MPI=0, or no mpicc): one process, no ranks (mpi.c is the real one). */
#include <stdlib.h>
#include <string.h>

#include "eco/eco.h"

SylEcoMpi *syl_ecosystem_mpi_start(int *argc, char ***argv, const SylSink *sink) {
    (void)argc, (void)argv, (void)sink;
    return NULL;
}
int syl_ecosystem_mpi_rank(const SylEcoMpi *mpi) { return (void)mpi, 0; }
int syl_ecosystem_mpi_size(const SylEcoMpi *mpi) { return (void)mpi, 1; }
const SylEcoExchange *syl_ecosystem_mpi_exchange(SylEcoMpi *mpi, int ntiles, int rebalance) {
    (void)mpi, (void)ntiles, (void)rebalance;
    return NULL;
}
void syl_ecosystem_mpi_traffic(const SylEcoMpi *mpi, uint64_t *plants_sent, uint64_t *bytes_sent, uint64_t *halo_received,
                         uint64_t *plants_moved, uint64_t *barriers) {
    (void)mpi;
    *plants_sent = *bytes_sent = *halo_received = *plants_moved = *barriers = 0;
}
void eco_mpi_sum(SylEcoMpi *mpi, int64_t *v, size_t n) { (void)mpi, (void)v, (void)n; }
int eco_mpi_gather(SylEcoMpi *mpi, const void *mine, size_t n, uint8_t **all, size_t *lens) {
    (void)mpi;
    lens[0] = n;
    if (!(*all = malloc(n ? n : 1))) return SYL_ELIMIT;
    memcpy(*all, mine, n);
    return SYL_OK;
}
void syl_ecosystem_mpi_end(SylEcoMpi *mpi) { (void)mpi; }
