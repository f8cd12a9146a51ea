/* syl_grow_build: one `grow` model alone, its base at the origin. */
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "lang/textures.h"
#include "sot/forest.h"
#include "sot/forest_internal.h"
#include "sot/output.h"
#include "sylva/grow.h"
#include "lang/program.h"

int syl_grow_build(const SylProgram *p, SylGrowOptions *opt, SylSkeleton **out) {
    static const SylGrowOptions defaults = {.years = -1};
    SylGrowOptions local;
    if (!opt) {
        local = defaults;
        opt = &local;
    }
    *out = NULL;
    memset(&opt->stats, 0, sizeof opt->stats);
    double t0 = forest_now();
    if (syl_program_kind(p) != SYL_MODEL_GROW) {
        program_say(p, opt->diag, DIAG_ERROR, NULL, "'%s' is not a grow block", syl_program_name(p));
        return SYL_EUSAGE;
    }
    GrowParams P;
    if (grow_params_read(p, &P, opt->diag)) return SYL_EMODEL;
    if (opt->years >= 0) P.years = opt->years;
    if (opt->use_seed) P.seed = opt->seed;
    Forest f;
    if (opt->years > SYL_GROW_MAX_YEARS) {
        program_say(p, opt->diag, DIAG_ERROR, NULL, "at most %d years, not %d", SYL_GROW_MAX_YEARS, opt->years);
        return SYL_EUSAGE;
    }
    int st = forest_init(&f, opt->threads, opt->diag, &opt->stats);
    f.sink = program_sink(p);
    if (f.sink) f.env.sink = *f.sink; /* Embree's errors too */
    forest_limits(&f, opt);
    f.shoot_derive = syl_derive_begin; /* shoots' query modules: the stand-alone environment */
    const float base[3] = {0, 0, 0};
    if (!st) st = forest_add_tree(&f, &P, base, P.years);
    if (!st) st = forest_setup(&f, base[1], P.sun, false);
    if (!st) st = forest_run(&f, opt->progress, opt->user);
    double t1 = forest_now();
    SylSkeleton *sk = NULL;
    if (!st) {
        sk = syl_skeleton_new(syl_program_name(p));
        st = sk ? tree_to_skeleton(&f.trees[0], f.years, sk, 0, &opt->stats.organs) : SYL_ELIMIT;
        if (!st) st = lang_textures_apply(p, sk, P.seed, opt->diag);
    }
    st = forest_said(&f, st, 0);
    forest_free(&f);
    if (st) {
        syl_skeleton_free(sk);
        return st;
    }
    double t2 = forest_now();
    opt->stats.other_s += t2 - t1;
    opt->stats.total_s = t2 - t0;
    *out = sk;
    return SYL_OK;
}
