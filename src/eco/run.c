/* syl_ecosystem_run: the block, its terrain and its factors, then the simulation. */
#include <errno.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "eco/eco.h"
#include "lang/program.h"

static void cannot_use(const SylProgram *p, const SylSink *sink, const char *file) {
    int n = 0;
    const SylDirective *d = syl_program_directives(p, &n);
    for (int i = 0; i < n; i++)
        if (!strcmp(d[i].name, "terrain") && d[i].nargs) {
            directive_error_to(p, sink, &d[i], &d[i].args[0], "cannot use the terrain \"%s\"", file);
            return;
        }
}

/* The block's DEM, read as the run reads it (and its factors computed when compute is set),
 * counted against budget (NULL: its own); its errors to sink, else the program's, else diag. */
static int read_terrain(const SylProgram *p, const SylEcoModel *m, int threads, SylBudget *budget, bool compute,
                        FILE *diag, const SylSink *sink, SylTerrain **terrain) {
    const SylSink *said = diag_sink(&(SylSink){0}, diag, sink);
    char *path = NULL; /* beside the program's file unless absolute */
    int refused = syl_program_file(p, m->terrain, &path);
    if (refused == SYL_EIO) program_say_to(p, said, DIAG_ERROR, NULL, "cannot read the terrain '%s': %s", m->terrain, syl_file_refused);
    if (refused) return refused;
    SylTerrain *t = NULL;
    SylTerrainOptions to = {.cell = m->cell, .height_lo = m->height_lo, .height_hi = m->height_hi,
                            .latitude = m->latitude, .sun_set = m->latitude_set, .threads = threads, .diag = diag,
                            .sink = sink ? sink : program_sink(p), .budget = budget, .wind_from = m->wind_from, .wind_set = m->wind_set,
                            .measures = m->measures == SYL_ECO_ZAMUDA ? SYL_TERRAIN_ZAMUDA : SYL_TERRAIN_GIS};
    int st = syl_terrain_read(path, &to, &t);
    if (st == SYL_EIO && (said || program_sink(p))) /* the reader named the file: say which line of the model names it */
        cannot_use(p, said, m->terrain);
    if (!st && compute) st = syl_terrain_compute(t, &to);
    free(path);
    if (st) syl_terrain_free(t);
    else *terrain = t;
    return st;
}

int syl_ecosystem_load(const SylProgram *p, const SylEcoOptions *o, SylEcoModel *m, SylTerrain **terrain) {
    FILE *diag = o->diag;
    *terrain = NULL;
    if (syl_program_kind(p) != SYL_MODEL_ECOSYSTEM) {
        program_say(p, diag, DIAG_ERROR, NULL, "'%s' is a %s, not an ecosystem block", syl_program_name(p),
                          syl_model_kind_name(syl_program_kind(p)));
        return SYL_EUSAGE;
    }
    if (syl_ecosystem_read(p, m, opt_sink(o))) return SYL_EMODEL;
    return read_terrain(p, m, o->threads, o->budget, true, diag, o->sink, terrain);
}

int syl_ecosystem_check_terrain(const SylProgram *p, const SylSink *sink) {
    if (syl_program_kind(p) != SYL_MODEL_ECOSYSTEM) return 0;
    SylEcoModel *m = malloc(sizeof *m);
    SylTerrain *t = NULL;
    int st = !m ? SYL_ELIMIT : syl_ecosystem_read(p, m, NULL) ? SYL_EMODEL : SYL_OK;
    char *path = NULL;
    if (!st && !syl_program_file(p, m->terrain, &path) && access(path, R_OK)) {
        /* a warning, as a scene's unreadable files: the DEM may yet be made */
        program_say_to(p, sink, DIAG_WARNING, syl_program_path(p), "the terrain \"%s\" cannot be read: %s", m->terrain, strerror(errno));
    } else if (!st) {
        st = read_terrain(p, m, 1, NULL, false, NULL, program_sink(p) ? program_sink(p) : sink, &t);
    }
    free(path);
    syl_terrain_free(t);
    free(m);
    return st != SYL_OK;
}

int syl_ecosystem_run(const SylProgram *p, const SylEcoOptions *o, SylEcoModel *model_out, SylTerrain **terrain_out,
                      SylEcoStats *stats) {
    if (terrain_out) *terrain_out = NULL;
    SylEcoModel *m = model_out ? model_out : malloc(sizeof *m);
    if (!m) return SYL_ELIMIT;
    SylTerrain *t = NULL;
    int st = syl_ecosystem_load(p, o, m, &t);
    if (!st) st = syl_ecosystem_simulate(m, t, o, stats);
    if (terrain_out && !st) *terrain_out = t;
    else syl_terrain_free(t);
    if (!model_out) free(m);
    return st;
}
