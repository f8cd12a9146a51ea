/* A saved ecosystem snapshot rendered as `sylva ecosystem` renders view-YEAR.png
 * (sylva/forest.h, syl_ecosystem_render_snapshot; `sylva render FILE --plants CSV`). Under
 * mpirun the picture's rows are cut into bands dealt round the ranks (band b to rank b mod N,
 * for balance: the sky is cheap, the forest dear); every rank holds the whole instanced scene
 * and renders its bands as windows of the picture on it (syl_render_draw_instances: bands starting
 * at multiples of SYL_RENDER_BLOCK rows have the whole picture's bytes), rank 0 gathers them
 * and writes the PNG. */
#include <stdlib.h>
#include <string.h>

#include "eco/eco.h"
#include "util/clock.h"
#include "util/diag.h"
#include "util/outgroup.h"
#include "sylva/forest.h"
#include "sylva/texture.h"

/* Bands of rows: one in one process (the ecosystem's own render), else 4 per rank, each at
 * least a row of ray packets high. */
static int bands_of(int height, int nranks) {
    int b = nranks > 1 ? 4 * nranks : 1, most = height / SYL_RENDER_BLOCK;
    return b < most ? b : most > 1 ? most : 1;
}

/* A band's first row: a multiple of SYL_RENDER_BLOCK, so that its ray packets are the whole
 * picture's and its pixels the same bytes. */
static int band_row(int b, int nbands, int height) {
    if (b >= nbands) return height;
    return (int)((int64_t)b * height / nbands) / SYL_RENDER_BLOCK * SYL_RENDER_BLOCK;
}

/* Every rank's status to all (every rank makes the same calls): the worst, so that every
 * rank stops or none. A rank other than 0 that failed says why (its diagnostics, kept in
 * said) unless rank 0 failed too, which has said it once; rank 0 says how many ranks failed
 * when it did not (to out, the caller's sink). After a failure every rank's st is the worst: nothing is said twice. */
static int agree(SylEcoMpi *mpi, int st, const SylSink *out, FILE *said, char *const *text, const size_t *len) {
    int rank = syl_ecosystem_mpi_rank(mpi), nranks = syl_ecosystem_mpi_size(mpi);
    int64_t v[7] = {0}; /* a flag per status, rank 0 failed, ranks failed */
    if (st > 0 && st < 5) v[st] = 1;
    v[5] = st && rank == 0, v[6] = st != 0;
    eco_mpi_sum(mpi, v, 7);
    int worst = SYL_OK;
    for (int k = 4; k > 0; k--)
        if (v[k] && !worst) worst = k;
    if (worst && !v[5] && rank == 0)
        sink_error(out, "%lld of the %d ranks could not do their part (the same files on every node?)", (long long)v[6],
                   nranks);
    if (st && !v[5] && rank > 0 && said) {
        fflush(said);
        int n = (int)*len - (*len && (*text)[*len - 1] == '\n'); /* the record's text ends without it */
        sink_error(out, "rank %d of %d could not do its part:\n%.*s", rank, nranks, n, *text ? *text : "");
    }
    return worst;
}

int syl_ecosystem_render_snapshot(const SylProgram *p, int status, const SylSnapshotOptions *o, SylSnapshotStats *stats) {
    SylEcoMpi *mpi = o->mpi;
    int rank = syl_ecosystem_mpi_rank(mpi), nranks = syl_ecosystem_mpi_size(mpi);
    /* every rank finds the same faults, which rank 0 says; another rank's are kept, to be said
     * when it alone failed (agree) */
    char *said = NULL;
    size_t said_len = 0;
    SylSink text;
    const SylSink *out = diag_sink(&text, o->diag, o->sink); /* the caller's */
    /* rank 0 reports to out; another rank keeps its text in said */
    FILE *diag = rank == 0 ? o->diag : open_memstream(&said, &said_len), *kept = rank == 0 ? NULL : diag;
    SylSink kept_text;
    const SylSink *sink = rank == 0 ? out : diag_sink(&kept_text, diag, NULL);
    const SylSink *sub_sink = rank == 0 ? o->sink : NULL; /* for the options that take diag too */
    SylEcoModel *model = calloc(1, sizeof *model); /* 14 kB: off the stack, and not shared between calls */
    SylTerrain *t = NULL;
    SylForest *forest = NULL;
    SylEcoPlant *plants = NULL;
    uint8_t *mine = NULL, *all = NULL, *rgb = NULL;
    size_t *lens = NULL, nplants = 0;
    int st = status;
    if (!st && !p) st = SYL_EUSAGE;
    if (!st && !model) st = SYL_ELIMIT;
    if (!st && syl_program_kind(p) != SYL_MODEL_ECOSYSTEM) {
        sink_error(sink, "--plants renders an ecosystem block's plants; '%s' is a %s (name one: FILE:Model)",
                   syl_program_name(p), syl_model_kind_name(syl_program_kind(p)));
        st = SYL_EUSAGE;
    }
    SylEcoOptions eo = {.threads = o->threads, .diag = diag, .sink = sub_sink};
    if (!st) st = syl_ecosystem_load(p, &eo, model, &t);
    if (!st) st = syl_ecosystem_table_read(o->plants, model, t, &plants, &nplants, sink);
    if (!st) st = syl_forest_new(p, model, t, &(SylForestOptions){.threads = o->threads, .diag = diag, .sink = sub_sink}, &forest);
    st = agree(mpi, st, out, kept, &said, &said_len); /* before rendering: no work for a failed job */
    SylRenderOptions ro = *o->render;
    int w = ro.width ? ro.width : 1280, h = ro.height ? ro.height : 720;
    ro.width = w, ro.height = h;
    int nbands = bands_of(h, nranks);
    size_t rows = 0; /* this rank's */
    for (int b = rank; b < nbands; b += nranks) rows += (size_t)(band_row(b + 1, nbands, h) - band_row(b, nbands, h));
    size_t row_bytes = (size_t)w * 3;
    if (!st && !(mine = malloc(rows * row_bytes + 1))) st = SYL_ELIMIT;
    int (*windows)[4] = NULL, nwin = 0; /* this rank's bands, rendered on one scene */
    if (!st && !(windows = malloc((size_t)(nbands / nranks + 1) * sizeof *windows))) st = SYL_ELIMIT;
    for (int b = rank; !st && b < nbands; b += nranks) {
        int *win = windows[nwin++];
        win[0] = 0, win[1] = band_row(b, nbands, h), win[2] = w, win[3] = band_row(b + 1, nbands, h);
    }
    SylRenderCamera cam = {0};
    SylRenderCounts counts = {0};
    double c0 = clock_cpu(), t0 = clock_wall();
    if (!st) syl_forest_camera(forest, o->view, w, h, &cam);
    if (!st && nwin) st = syl_forest_render(forest, plants, nplants, &cam, &ro, (const int(*)[4])windows, nwin, mine, &counts);
    double cpu = clock_cpu() - c0, wall = clock_wall() - t0;
    if (mpi && o->before_gather) o->before_gather(o->user, rank);
    if (!st && !(lens = calloc((size_t)nranks, sizeof *lens))) st = SYL_ELIMIT;
    st = agree(mpi, st, out, kept, &said, &said_len);
    if (!st) st = eco_mpi_gather(mpi, mine, rows * row_bytes, &all, lens);
    if (!st && rank == 0) { /* each rank's bands, in its order, into their rows */
        if (!(rgb = malloc((size_t)h * row_bytes))) st = SYL_ELIMIT;
        size_t from = 0;
        for (int r = 0; !st && r < nranks; r++) {
            size_t got = 0;
            for (int b = r; b < nbands; b += nranks) {
                int y0 = band_row(b, nbands, h), y1 = band_row(b + 1, nbands, h);
                size_t len = (size_t)(y1 - y0) * row_bytes;
                if (got + len > lens[r]) break;
                memcpy(rgb + (size_t)y0 * row_bytes, all + from + got, len);
                got += len;
            }
            if (got != lens[r]) {
                sink_error(sink, "rank %d sent %zu bytes of picture, not %zu", r, lens[r], got);
                st = SYL_EIO;
            }
            from += lens[r];
        }
        /* The .glb and the PNG are one transaction (util/outgroup.h): when the PNG cannot be
         * written, the .glb is taken back, the file that was there before put back. */
        OutGroup outs = {0};
        if (!st && o->glb)
            st = !outgroup_add(&outs, o->glb, sink) ? SYL_EIO : syl_forest_write_glb(forest, plants, nplants, 0, o->glb, sink);
        if (!st) st = outgroup_add(&outs, o->png, sink) ? syl_png_write(o->png, rgb, w, h, sink) : SYL_EIO;
        if (st) outgroup_undo(&outs);
        else outgroup_commit(&outs);
    }
    st = agree(mpi, st, out, kept, &said, &said_len); /* rank 0's writes: every rank exits with their status */
    if (kept) fclose(kept);
    free(said);
    if (stats)
        *stats = (SylSnapshotStats){.camera = cam, .width = w, .height = h, .plants = nplants, .rows = rows,
                                    .bands = nwin, .bytes = rows * row_bytes, .counts = counts, .wall = wall, .cpu = cpu};
    free(rgb), free(all), free(lens), free(mine), free(plants), free(windows);
    syl_forest_free(forest);
    syl_terrain_free(t);
    free(model);
    return st;
}
