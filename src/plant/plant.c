/* syl_plant_build: the pipeline every drawing command runs, above every engine (lsys,
 * turtle, sot, mesh) and using only their public API and the table of kinds (lang/kinds.h,
 * kinds/kinds.h), so that nothing below calls it. */
#include "sylva/plant.h"
#include "sylva/trees.h"
#include "kinds/kinds.h"
#include "lang/kinds.h"
#include "lang/program.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double clock_s(clockid_t id) {
    struct timespec ts;
    clock_gettime(id, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}
static double now(void) { return clock_s(CLOCK_MONOTONIC); }
static double cpu_now(void) { return clock_s(CLOCK_PROCESS_CPUTIME_ID); }

typedef struct StepProgress {
    const SylPlantOptions *opt;
    int steps;
} StepProgress;

static void on_step(void *user, int step, const SylString *s) {
    (void)s;
    const StepProgress *sp = user;
    if (sp->steps > 0 && step < sp->steps) sp->opt->progress(sp->opt->user, (double)step / sp->steps);
}

static int build_grown(const SylProgram *p, bool scene, const SylPlantOptions *opt, const SylMeshOptions *mo,
                       SylBudget *budget, SylPlant *out) {
    SylGrowOptions g = {.years = opt->use_steps ? opt->steps : -1, .use_seed = opt->use_seed, .seed = opt->seed,
                        .threads = opt->threads, .max_metamers = opt->max_metamers, .max_buds = opt->max_buds,
                        .max_modules = opt->max_modules, .max_work = opt->max_work, .max_memory = opt->max_memory,
                        .budget = budget, .diag = opt->diag, .progress = opt->progress, .user = opt->user,
                        .cancel = mo->cancel};
    SylMesh *obstacles = NULL;
    double t0 = now(), c0 = cpu_now();
    int st = scene ? syl_grow_build_scene(p, &g, &out->skeleton, &obstacles) : syl_grow_build(p, &g, &out->skeleton);
    if (opt->progress) opt->progress(opt->user, 1);
    double t1 = now(), c1 = cpu_now();
    out->grow = g.stats;
    out->derive_s = t1 - t0;
    out->derive_cpu_s = c1 - c0;
    if (!st) out->modules = out->skeleton->nnodes;
    if (!st && opt->until == SYL_PLANT_MESH) {
        SylMeshOptions each = *mo; /* a scene's objects are told apart by their vertices' nodes */
        if (scene) each.vertex_nodes = 1;
        st = syl_mesh_build(out->skeleton, &each, &out->mesh);
        if (!st && scene) st = syl_mesh_split(out->mesh, obstacles, out->skeleton, &out->parts, &out->nparts);
        if (!st && scene && !mo->vertex_nodes && !obstacles) { /* as it was asked for */
            free(out->mesh->node);
            out->mesh->node = NULL;
        }
        /* the walls the trees grew around belong in the picture */
        if (!st && obstacles && (st = syl_mesh_append(out->mesh, obstacles)) && opt->diag)
            program_say(p, opt->diag, DIAG_ERROR, NULL, "out of memory adding the obstacles to the mesh");
    }
    out->mesh_s = now() - t1;
    out->mesh_cpu_s = cpu_now() - c1;
    syl_mesh_free(obstacles);
    return st;
}

/* a kind built from its parameters (its row's build, kinds/kinds.c: weber, strands): the
 * skeleton straight from them */
static int build_tree(const KindOps *ops, const SylProgram *p, const SylPlantOptions *opt, const SylMeshOptions *mo,
                      SylBudget *budget, SylPlant *out) {
    SylTreeOptions t = {.use_seed = opt->use_seed, .seed = opt->seed, .threads = opt->threads, .age = opt->age,
                        .levels = opt->levels, .max_memory = opt->max_memory, .budget = budget, .diag = opt->diag,
                        .cancel = mo->cancel};
    double t0 = now(), c0 = cpu_now();
    int st = ops->build(p, &t, &out->skeleton);
    if (opt->progress) opt->progress(opt->user, 1);
    double t1 = now(), c1 = cpu_now();
    out->derive_s = t1 - t0;
    out->derive_cpu_s = c1 - c0;
    if (!st) out->modules = out->skeleton->nnodes;
    if (!st && opt->until == SYL_PLANT_MESH) st = syl_mesh_build(out->skeleton, mo, &out->mesh);
    out->mesh_s = now() - t1;
    out->mesh_cpu_s = cpu_now() - c1;
    return st;
}

static int build_lsystem(const SylProgram *p, const SylPlantOptions *opt, const SylMeshOptions *mo,
                         SylBudget *budget, SylPlant *out) {
    StepProgress sp = {.opt = opt, .steps = opt->use_steps ? opt->steps : syl_program_steps(p)};
    SylDeriveOptions d = {.steps = opt->use_steps ? opt->steps : -1, .use_seed = opt->use_seed, .seed = opt->seed,
                          .threads = opt->threads, .max_modules = opt->max_modules,
                          .max_work = opt->max_work, .max_memory = opt->max_memory, .budget = budget,
                          .diag = opt->diag,
                          .on_step = opt->progress ? on_step : NULL, .user = &sp, .cancel = mo->cancel};
    double t0 = now(), c0 = cpu_now();
    SylString *derived = NULL;
    int st = syl_derive(p, &d, &derived);
    if (opt->progress) opt->progress(opt->user, 1);
    if (!st) st = syl_interpret(p, derived, &d, &out->string);
    syl_string_free(derived);
    double t1 = now();
    out->derive_s = t1 - t0;
    out->derive_cpu_s = cpu_now() - c0;
    out->rewritten = d.rewritten;
    if (!st) out->modules = syl_string_length(out->string);
    if (!st && opt->until != SYL_PLANT_STRING) {
        st = syl_turtle_draw(p, out->string, &(SylTurtleOptions){.diag = opt->diag, .max_memory = opt->max_memory, .budget = budget,
                                                                     .use_seed = opt->use_seed, .seed = opt->seed,
                                                                     .cancel = mo->cancel}, &out->skeleton);
        if (opt->drop_string) {
            syl_string_free(out->string);
            out->string = NULL;
        }
    }
    double t2 = now(), c2 = cpu_now();
    out->turtle_s = t2 - t1;
    if (!st && opt->until == SYL_PLANT_MESH) st = syl_mesh_build(out->skeleton, mo, &out->mesh);
    out->mesh_s = now() - t2;
    out->mesh_cpu_s = cpu_now() - c2;
    return st;
}

int syl_plant_build(const SylProgram *p, const SylPlantOptions *opt, SylPlant *out) {
    static const SylPlantOptions defaults = {0};
    if (!opt) opt = &defaults;
    memset(out, 0, sizeof *out);
    SylMeshOptions mo = opt->mesh ? *opt->mesh : (SylMeshOptions){.threads = opt->threads, .diag = opt->diag};
    /* The caller's budget is shared by every engine; without one, each engine keeps its own
     * limit of max_memory (a budget made here could not outlive the mesh it counts). */
    SylBudget *budget = opt->budget ? opt->budget : mo.budget;
    if (!mo.budget) mo.budget = budget;
    if (!mo.sink) mo.sink = program_sink(p); /* the mesher's records: the program's sink */
    if (!mo.max_memory) mo.max_memory = opt->max_memory;
    if (opt->cancel) mo.cancel = opt->cancel; /* every engine of the build asks the same */
    SylModelKind kind = syl_program_kind(p);
    const KindOps *ops = kinds_ops(kind);
    int nscene = 0;
    bool scene = lang_kind_is(kind, KF_UNNAMED) || (opt->scene && syl_program_scene(p, &nscene));
    if (!scene && lang_kind_is(kind, KF_NOT_A_PLANT)) {
        lang_kind_refuse(p, opt->diag, syl_program_name(p), kind, true);
        return SYL_EUSAGE;
    }
    out->kind = scene ? SYL_MODEL_SCENE : kind;
    if (opt->until == SYL_PLANT_STRING && !lang_kind_is(out->kind, KF_STRING)) {
        program_say(p, opt->diag, DIAG_ERROR, NULL, "'%s' is %s %s, not an lsystem: it has no string",
                    syl_program_name(p), lang_kind_article(out->kind), syl_model_kind_name(out->kind));
        return SYL_EUSAGE;
    }
    int st;
    if (scene || lang_kind_is(kind, KF_GROWS)) st = build_grown(p, scene, opt, &mo, budget, out);
    else if (ops->build) st = build_tree(ops, p, opt, &mo, budget, out);
    else st = build_lsystem(p, opt, &mo, budget, out); /* KF_RULES: test_kinds holds every other kind to one above */
    if (st) syl_plant_free(out);
    return st;
}

void syl_plant_free(SylPlant *pl) {
    if (!pl) return;
    syl_mesh_free(pl->mesh);
    syl_mesh_parts_free(pl->parts, pl->nparts);
    syl_skeleton_free(pl->skeleton);
    syl_string_free(pl->string);
    memset(pl, 0, sizeof *pl);
}
