/* syl_weber: a Weber–Penn tree from a `weber` block. (The generator lands in this folder.) */
#include "sylva/trees.h"

int syl_weber_validate(const SylProgram *p, FILE *diag) {
    (void)p;
    (void)diag;
    return 0;
}

int syl_weber(const SylProgram *p, const SylTreeOptions *opt, SylSkeleton **out) {
    *out = NULL;
    if (opt && opt->diag)
        fprintf(opt->diag, "sylva: error: '%s': weber blocks are not generated yet\n", syl_program_name(p));
    return SYL_EMODEL;
}
