/* syl_weber: a Weber–Penn tree from a `weber` block. (The generator lands in this folder.) */
#include "sylva/trees.h"

#include "weber/params.h"

int syl_weber_validate(const SylProgram *p, FILE *diag) {
    WeberParams w;
    return weber_params_read(p, &w, diag);
}

int syl_weber(const SylProgram *p, const SylTreeOptions *opt, SylSkeleton **out) {
    *out = NULL;
    if (opt && opt->diag)
        fprintf(opt->diag, "sylva: error: '%s': weber blocks are not generated yet\n", syl_program_name(p));
    return SYL_EMODEL;
}
