/* The plant pipeline for grow blocks and scenes: grow (a progress bar per year), mesh, and
 * add a scene's obstacles to the mesh so pictures show the walls the trees grew around. */
#include <stdlib.h>

#include "cli.h"

int cli_grow_plant(SylProgram *p, bool scene, const ModelArgs *m, SylDeriveOptions *d, const SylMeshOptions *mo,
                   Plant *out) {
    /* -n is the years here: the limit of --years and of `years`, with the same message */
    if (d->steps > SYL_GROW_MAX_YEARS) {
        char arg[32];
        double v;
        snprintf(arg, sizeof arg, "%d", d->steps);
        cli_integer("-n", arg, 0, SYL_GROW_MAX_YEARS, &v);
        syl_program_free(p);
        return SYL_EUSAGE;
    }
    Progress bar;
    cli_progress_start(&bar, "growing");
    SylGrowOptions g = {.years = d->steps, .use_seed = d->use_seed, .seed = d->seed, .threads = d->threads,
                        .max_metamers = m->max_metamers, .max_buds = m->max_buds, .max_modules = d->max_modules,
                        .max_work = d->max_work, .max_memory = d->max_memory, .budget = d->budget,
                        .diag = stderr, .progress = cli_progress, .user = &bar};
    SylMesh *obstacles = NULL;
    double t0 = cli_now();
    int status = scene ? syl_grow_scene(p, &g, &out->sk, &obstacles) : syl_grow(p, &g, &out->sk);
    cli_progress(&bar, 1);
    syl_program_free(p);
    double t1 = cli_now();
    out->grown = true;
    out->grow = g.stats;
    out->derive_s = t1 - t0;
    if (!status) out->modules = out->sk->nnodes;
    if (!status && mo) {
        status = syl_mesh_build(out->sk, mo, &out->mesh);
        if (!status && obstacles && (status = syl_mesh_append(out->mesh, obstacles)))
            fprintf(stderr, "sylva: error: out of memory adding the obstacles to the mesh\n");
    }
    out->mesh_s = cli_now() - t1;
    syl_mesh_free(obstacles);
    if (status) cli_plant_free(out);
    return status;
}
