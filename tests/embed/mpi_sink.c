/* The MPI transport reports through the caller's diag, not stderr: under mpirun -np 2 with
 * SYLVA_RANK_TIMEOUT=1, rank 1 stops itself (SIGSTOP) and rank 0, waiting on it in a sum, ends
 * the job (exit code SYL_EIO, 4) after saying why to its sink, which prints the record. */
#include <signal.h>
#include <stdio.h>

#include <sylva/ecosystem.h>

static void report(void *user, const SylDiagnostic *d) {
    (void)user;
    printf("record %d %s\n", (int)d->severity, d->message);
    fflush(stdout);
}

int main(int argc, char **argv) {
    SylSink sink = {report, NULL};
    FILE *diag = syl_sink_open(&sink);
    SylEcoMpi *mpi = syl_eco_mpi_start(&argc, &argv, diag);
    if (!mpi) {
        printf("not under mpirun, or no MPI\n");
        return 0;
    }
    if (syl_eco_mpi_rank(mpi) == 1) raise(SIGSTOP);
    int64_t v = 1;
    syl_eco_mpi_sum(mpi, &v, 1); /* rank 0 waits here for ever, but for the watchdog */
    syl_eco_mpi_end(mpi);
    return 0;
}
