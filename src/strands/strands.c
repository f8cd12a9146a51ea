/* syl_strands: a tree of Holton's strands from a `strands` block. (The model lands in this folder.) */
#include "sylva/trees.h"

int syl_strands_validate(const SylProgram *p, FILE *diag) {
    (void)p;
    (void)diag;
    return 0;
}

int syl_strands(const SylProgram *p, const SylTreeOptions *opt, SylSkeleton **out) {
    *out = NULL;
    if (opt && opt->diag)
        fprintf(opt->diag, "sylva: error: '%s': strands blocks are not generated yet\n", syl_program_name(p));
    return SYL_EMODEL;
}
