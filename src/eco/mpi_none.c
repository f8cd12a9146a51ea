/* A build without MPI (make MPI=0, or no mpicc): one process, no ranks (mpi.c is the real one). */
#include "sylva/ecosystem.h"

SylEcoMpi *syl_eco_mpi_start(int *argc, char ***argv) {
    (void)argc, (void)argv;
    return NULL;
}
int syl_eco_mpi_rank(const SylEcoMpi *mpi) { return (void)mpi, 0; }
int syl_eco_mpi_size(const SylEcoMpi *mpi) { return (void)mpi, 1; }
const SylEcoExchange *syl_eco_mpi_exchange(SylEcoMpi *mpi, int ntiles, int rebalance) {
    (void)mpi, (void)ntiles, (void)rebalance;
    return NULL;
}
void syl_eco_mpi_traffic(const SylEcoMpi *mpi, uint64_t *plants_sent, uint64_t *bytes_sent, uint64_t *halo_received,
                         uint64_t *plants_moved, uint64_t *barriers) {
    (void)mpi;
    *plants_sent = *bytes_sent = *halo_received = *plants_moved = *barriers = 0;
}
void syl_eco_mpi_abort(SylEcoMpi *mpi, int code, const char *message) { (void)mpi, (void)code, (void)message; }
void syl_eco_mpi_end(SylEcoMpi *mpi) { (void)mpi; }
