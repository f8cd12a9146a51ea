/* syl_ecosystem_run: the block, its terrain and its factors, then the simulation. */
#include <libgen.h>
#include <stdlib.h>
#include <string.h>

#include "eco/eco.h"

/* The DEM's path: as written when absolute, else beside the program's file. */
static char *terrain_path(const SylProgram *p, const char *file) {
    if (file[0] == '/') return strdup(file);
    char *prog = strdup(syl_program_path(p));
    if (!prog) return NULL;
    const char *dir = dirname(prog);
    size_t n = strlen(dir) + strlen(file) + 2;
    char *out = malloc(n);
    if (out && !strcmp(dir, ".")) snprintf(out, n, "%s", file);
    else if (out) snprintf(out, n, "%s/%s", dir, file);
    free(prog);
    return out;
}

int syl_ecosystem_load(const SylProgram *p, const SylEcoOptions *o, SylEcoModel *m, SylTerrain **terrain) {
    FILE *diag = o->diag;
    *terrain = NULL;
    if (syl_program_kind(p) != SYL_MODEL_ECOSYSTEM) {
        if (diag) fprintf(diag, "sylva: error: '%s' is a %s, not an ecosystem block\n", syl_program_name(p),
                          syl_model_kind_name(syl_program_kind(p)));
        return SYL_EUSAGE;
    }
    if (syl_ecosystem_read(p, m, diag)) return SYL_EMODEL;
    char *path = terrain_path(p, m->terrain);
    if (!path) return SYL_ELIMIT;
    SylTerrain *t = NULL;
    SylTerrainOptions to = {.cell = m->cell, .height_lo = m->height_lo, .height_hi = m->height_hi,
                            .latitude = m->latitude, .sun_set = m->latitude_set, .threads = o->threads, .diag = diag,
                            .budget = o->budget};
    int st = syl_terrain_read(path, &to, &t);
    if (!st) st = syl_terrain_compute(t, &to);
    free(path);
    if (st) syl_terrain_free(t);
    else *terrain = t;
    return st;
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
