/* syl_strands_build: a tree of Holton's strands from a `strands` block, as Zamuda's modeller builds
 * it (docs/strands.md); syl_strands_validate: the block's check for `sylva check`. */
#include <stdio.h>

#include "lang/textures.h"
#include "skeleton/store.h"
#include "strands/strands.h"
#include "sylva/trees.h"
#include "util/array.h"
#include "util/budget.h"
#include "lang/program.h"

int syl_strands_validate(const SylProgram *p, FILE *diag) {
    return syl_program_kind(p) == SYL_MODEL_STRANDS ? strands_params_check(p, diag) : 0;
}

int syl_strands_build(const SylProgram *p, const SylTreeOptions *opt, SylSkeleton **out) {
    static const SylTreeOptions none = {0};
    if (!opt) opt = &none;
    *out = NULL;
    if (syl_program_kind(p) != SYL_MODEL_STRANDS) {
        program_say(p, opt->diag, DIAG_ERROR, NULL, "'%s' is a %s, not a strands block", syl_program_name(p),
                    syl_model_kind_name(syl_program_kind(p)));
        return SYL_EUSAGE;
    }
    StrandsParams P;
    if (strands_params_read(p, &P, opt->diag)) return SYL_EMODEL;
    if (opt->use_seed) P.seed = opt->seed;
    P.seed += opt->seed_offset; /* a scene's n-th plant of a row: turned its own way */
    StrandsCounts c = strands_counts(&P, opt->age);
    /* counted before anything is allocated; the caller's budget keeps them until freed */
    uint64_t bytes = c.nodes * sizeof(SylNode) + c.organs * sizeof(SylOrgan);
    Budget own, *mem = budget_use(&own, opt->max_memory, opt->budget);
    if (!budget_charge(mem, bytes)) {
        program_say(p, opt->diag, DIAG_ERROR, NULL, "'%s' would need %llu nodes and %llu leaves (%llu MB), more than --max-memory "
                    "allows (%llu MB%s)",
                    syl_program_name(p), (unsigned long long)c.nodes, (unsigned long long)c.organs,
                    (unsigned long long)(bytes >> 20), (unsigned long long)budget_limit_mb(mem),
                    mem == &own ? "" : " in all");
        return SYL_ELIMIT;
    }
    SylSkeleton *sk = syl_skeleton_new(syl_program_name(p));
    if (!sk) {
        program_say(p, opt->diag, DIAG_ERROR, NULL, "'%s': out of memory for the skeleton", syl_program_name(p));
        budget_release(mem, bytes);
        return SYL_ELIMIT;
    }
    if (mem != &own) skeleton_charge(sk, mem, bytes);
    else budget_release(mem, bytes);
    sk->nmaterials = c.organs ? 2 : 1;
    /* the counts are known (3.1): one allocation each, not a doubling series */
    if (!skeleton_reserve_nodes(sk, c.nodes) || (c.organs && !skeleton_reserve_organs(sk, c.organs))) {
        if (opt->diag) /* within the budget, but the system said no (ulimit -v, a cgroup) */
            program_say(p, opt->diag, DIAG_ERROR, NULL, "'%s': out of memory for the skeleton's %llu nodes and %llu leaves (%llu MB)",
                    syl_program_name(p), (unsigned long long)c.nodes, (unsigned long long)c.organs,
                    (unsigned long long)(bytes >> 20));
        syl_skeleton_free(sk);
        return SYL_ELIMIT;
    }
    int st = strands_build(&P, opt->age, sk, NULL, opt->cancel);
    if (st == SYL_ECANCELED) { /* asked to stop: nothing said */
        syl_skeleton_free(sk);
        return st;
    }
    if (!st && (st = lang_textures_apply(p, sk, P.seed, opt->diag)) != SYL_OK) {
        syl_skeleton_free(sk);
        return st;
    }
    if (st) {
        program_say(p, opt->diag, DIAG_ERROR, NULL, "'%s': out of memory for the skeleton", syl_program_name(p));
        syl_skeleton_free(sk);
        return st;
    }
    *out = sk;
    return SYL_OK;
}
