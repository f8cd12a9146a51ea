/* Growth as a sequence of plants (sylva animate): an L-system's steps from one derivation, a
 * grown plant's years and a strands tree's ages, each frame built as syl_plant_build would. */
#include "sylva/plant.h"
#include "lang/kinds.h"
#include "lang/program.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

enum { STRANDS_AGES = 10 }; /* a strands tree's frames when no count is given */

struct SylGrowth {
    const SylProgram *p;
    SylPlantOptions opt;
    SylMeshOptions mesh;   /* opt.mesh points here */
    SylModelKind kind;
    bool scene;
    int count;
    SylString **strings;   /* L-systems: each step's string, as the turtle reads it */
    SylPlant last;         /* grown plants: the last frame, built to learn the count */
    bool have_last;
};

/* Derive once, keeping each step's string after the `interpret` rules. */
static int derive_steps(SylGrowth *g) {
    const SylPlantOptions *o = &g->opt;
    SylDeriveOptions d = {.steps = o->use_steps ? o->steps : -1, .use_seed = o->use_seed, .seed = o->seed,
                          .threads = o->threads, .max_modules = o->max_modules, .max_work = o->max_work,
                          .max_memory = o->max_memory, .budget = o->budget, .diag = o->diag};
    int n = o->use_steps ? o->steps : syl_program_steps(g->p);
    if (n < 0) n = 0;
    g->strings = calloc((size_t)n + 1, sizeof *g->strings);
    if (!g->strings) {
        program_say(g->p, o->diag, DIAG_ERROR, NULL, "out of memory");
        return SYL_ELIMIT;
    }
    SylDeriver *dv = NULL;
    int st = syl_derive_begin(g->p, &d, NULL, &dv);
    for (int k = 0; !st && k <= n; k++) {
        if (k > 0) st = syl_derive_step(dv);
        if (!st) st = syl_interpret(g->p, syl_deriver_string(dv), &d, &g->strings[k]);
        if (!st) g->count = k + 1;
        if (!st && o->progress) o->progress(o->user, (double)(k + 1) / (n + 1));
    }
    if (dv) {
        int end = syl_derive_end(dv, NULL);
        if (!st) st = end;
    }
    return st;
}

/* The options of frame k: its years (grown) or age (strands). */
static SylPlantOptions frame_options(const SylGrowth *g, int k) {
    SylPlantOptions o = g->opt;
    o.progress = NULL;
    if (lang_kind_is(g->kind, KF_AGES)) {
        o.age = (double)(k + 1) / g->count; /* the seam: ages k/N, S' = t^2 S in the generator */
    } else {
        o.use_steps = 1;
        o.steps = k + 1; /* years 1..N */
    }
    return o;
}

int syl_growth_new(const SylProgram *p, const SylPlantOptions *opt, SylGrowth **out) {
    static const SylPlantOptions defaults = {0};
    if (!opt) opt = &defaults;
    *out = NULL;
    SylGrowth *g = calloc(1, sizeof *g);
    if (!g) {
        program_say(p, opt->diag, DIAG_ERROR, NULL, "out of memory");
        return SYL_ELIMIT;
    }
    g->p = p;
    g->opt = *opt;
    g->opt.until = SYL_PLANT_MESH;
    g->mesh = opt->mesh ? *opt->mesh : (SylMeshOptions){.threads = opt->threads, .diag = opt->diag};
    g->opt.mesh = &g->mesh;
    g->kind = syl_program_kind(p);
    int nscene = 0;
    g->scene = lang_kind_is(g->kind, KF_UNNAMED) || (opt->scene && syl_program_scene(p, &nscene));
    int st = SYL_OK;
    if (g->scene || lang_kind_is(g->kind, KF_GROWS)) {
        /* the last year first: it tells the count (a scene's plants may each have their own) */
        st = syl_plant_build(p, &g->opt, &g->last);
        g->have_last = !st;
        if (!st) g->count = g->last.grow.years;
        if (!st && g->count < 1) {
            program_say(p, opt->diag, DIAG_ERROR, NULL, "'%s' grows for no year: nothing to animate",
                                   syl_program_name(p));
            st = SYL_EUSAGE;
        }
    } else if (lang_kind_is(g->kind, KF_AGES)) {
        g->count = opt->use_steps ? opt->steps : STRANDS_AGES;
        if (g->count < 1) {
            program_say(p, opt->diag, DIAG_ERROR, NULL, "%s %s tree needs at least one age to animate",
                        lang_kind_article(g->kind), lang_kind_keyword(g->kind));
            st = SYL_EUSAGE;
        }
    } else if (lang_kind_is(g->kind, KF_RULES)) {
        st = derive_steps(g);
    } else if (lang_kind_is(g->kind, KF_NOT_A_PLANT)) {
        lang_kind_refuse(p, opt->diag, syl_program_name(p), g->kind, true);
        st = SYL_EUSAGE;
    } else {
        program_say(p, opt->diag, DIAG_ERROR, NULL, "'%s' is %s %s: it is built full grown and has no growth to animate",
                    syl_program_name(p), lang_kind_article(g->kind), syl_model_kind_name(g->kind));
        st = SYL_EUSAGE;
    }
    if (st) {
        syl_growth_free(g);
        return st;
    }
    *out = g;
    return SYL_OK;
}

int syl_growth_count(const SylGrowth *g) { return g->count; }

int syl_growth_label(const SylGrowth *g, int k) { return g->strings ? k : k + 1; }

int syl_growth_build(SylGrowth *g, int k, SylPlant *out) {
    memset(out, 0, sizeof *out);
    if (k < 0 || k >= g->count) return SYL_EUSAGE;
    if (g->strings) { /* draw and mesh the kept string */
        const SylPlantOptions *o = &g->opt;
        out->kind = g->kind;
        out->modules = syl_string_length(g->strings[k]);
        SylTurtleOptions t = {.diag = o->diag, .max_memory = o->max_memory, .budget = o->budget,
                              .use_seed = o->use_seed, .seed = o->seed};
        int st = syl_turtle_draw(g->p, g->strings[k], &t, &out->skeleton);
        if (!st) st = syl_mesh_build(out->skeleton, &g->mesh, &out->mesh);
        if (st) syl_plant_free(out);
        return st;
    }
    if (k == g->count - 1 && g->have_last) { /* handed over once */
        *out = g->last;
        memset(&g->last, 0, sizeof g->last);
        g->have_last = false;
        return SYL_OK;
    }
    SylPlantOptions o = frame_options(g, k);
    return syl_plant_build(g->p, &o, out);
}

void syl_growth_free(SylGrowth *g) {
    if (!g) return;
    for (int k = 0; g->strings && k < g->count; k++) syl_string_free(g->strings[k]);
    free(g->strings);
    syl_plant_free(&g->last);
    free(g);
}
