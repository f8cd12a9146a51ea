/* sylva render FILE --plants plants-YEAR.csv: a saved ecosystem snapshot rendered as
 * `sylva ecosystem` renders view-YEAR.png, split over the ranks under mpirun
 * (syl_ecosystem_render_snapshot, src/forest/snapshot.c). */
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/testfaults.h"
#include "sylva/ecosystem.h"
#include "sylva/forest.h"

static void before_gather(void *user, int rank) {
    (void)user;
    cli_test_fault_gather(true, rank);
}

int cli_render_snapshot(CliArgs *a, ModelArgs *m, SylDeriveOptions *d, SylRenderOptions *ro) {
    SylEcoMpi *mpi = syl_ecosystem_mpi_start(NULL, NULL, &cli_sink); /* NULL: one process */
    int rank = syl_ecosystem_mpi_rank(mpi);
    SylProgram *p = NULL;
    int st = SYL_OK;
    if (ro->view != SYL_VIEW_AUTO) { /* every rank finds it; rank 0 says it */
        if (rank == 0) fprintf(stderr, "sylva: error: a snapshot's --view is bird or walker\n");
        st = SYL_EUSAGE;
    }
    cli_model_spec(m, a->files[0]);
    if (!st && !(p = cli_compile(m, rank == 0, &st)) && !st) st = SYL_EMODEL;
    /* the picture's name, and the .glb's beside it (NAME.glb for NAME.png) */
    char *out = a->output ? strdup(a->output) : cli_output_name(m, NULL, "png"), *glb = NULL;
    if (out && a->glb && (glb = malloc(strlen(out) + 5))) {
        size_t n = strlen(out);
        memcpy(glb, out, n + 1);
        if (n > 4 && !strcmp(glb + n - 4, ".png")) glb[n - 4] = 0;
        strcat(glb, ".glb");
    }
    if (!st && (!out || (a->glb && !glb))) st = SYL_ELIMIT;
    SylSnapshotOptions so = {.plants = a->plants, .view = (SylForestView)a->eco_view, .render = ro, .png = out,
                             .glb = glb, .threads = d->threads, .mpi = mpi, .before_gather = before_gather,
                             .diag = stderr};
    SylSnapshotStats s;
    st = syl_ecosystem_render_snapshot(p, st, &so, &s);
    if (!st && a->stats) {
        if (rank == 0)
            fprintf(stderr, "view: camera %.3f %.3f %.3f target %.3f %.3f %.3f fov %.3f size %d %d\n", s.camera.eye[0],
                    s.camera.eye[1], s.camera.eye[2], s.camera.target[0], s.camera.target[1], s.camera.target[2],
                    s.camera.fov, s.width, s.height);
        fprintf(stderr, "rank %d: %zu plants, %zu rows in %d bands, %zu bytes gathered; %zu instances drawn (%zu coarse), "
                        "%zu culled; %.3f s wall, %.3f s cpu; %.3f s cpu in all\n",
                rank, s.plants, s.rows, s.bands, s.bytes, s.counts.drawn, s.counts.coarse, s.counts.culled, s.wall, s.cpu,
                cli_cpu_now());
    }
    free(out), free(glb);
    syl_program_free(p);
    syl_ecosystem_mpi_end(mpi);
    return st;
}
