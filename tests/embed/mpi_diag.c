/* The MPI transport reports to the caller's sink, not stderr: under mpirun -np 2 with
 * SYLVA_RANK_TIMEOUT=1, rank 1 stops itself (SIGSTOP) and rank 0, waiting on it in the
 * snapshot render's agreement on a status (every rank calls it, a failed compile too: p NULL),
 * ends the job (exit code SYL_EIO, 4) after saying why to the sink it was given: the text sink
 * of the file LOG, which every rank opens to append to.
 *   mpi_diag LOG */
#include <signal.h>
#include <stdio.h>

#include <sylva/forest.h>

int main(int argc, char **argv) {
    if (argc < 2) return 2;
    FILE *diag = fopen(argv[1], "a");
    if (!diag) return 2;
    setvbuf(diag, NULL, _IONBF, 0);
    SylSink sink = {syl_diagnostic_print, diag};
    SylEcoMpi *mpi = syl_ecosystem_mpi_start(&argc, &argv, &sink);
    if (!mpi) {
        printf("not under mpirun, or no MPI\n");
        return 0;
    }
    if (syl_ecosystem_mpi_rank(mpi) == 1) raise(SIGSTOP);
    SylSnapshotStats stats;
    /* rank 0 waits here for ever, but for the watchdog */
    syl_ecosystem_render_snapshot(NULL, SYL_EMODEL, &(SylSnapshotOptions){.render = &(SylRenderOptions){0}, .mpi = mpi, .diag = diag}, &stats);
    syl_ecosystem_mpi_end(mpi);
    fclose(diag);
    return 0;
}
