/* `extern` functions: the model declares them, the program's caller binds them (sylva.h). */
#include <string.h>

#include "lang/program.h"

/* The function of the i-th extern, in declaration order; NULL past the end. */
static Function *extern_at(const SylProgram *p, int i) {
    for (int k = 0; k < p->nfns; k++)
        if (p->fns[k].external && i-- == 0) return &p->fns[k];
    return NULL;
}

int syl_program_extern_count(const SylProgram *p) {
    int n = 0;
    for (int k = 0; k < p->nfns; k++) n += p->fns[k].external;
    return n;
}

const char *syl_program_extern(const SylProgram *p, int i, int *nparams, int *has_default) {
    const Function *f = i >= 0 ? extern_at(p, i) : NULL;
    if (!f) return NULL;
    if (nparams) *nparams = f->nparams;
    if (has_default) *has_default = f->has_default;
    return f->name;
}

int syl_program_bind_extern(SylProgram *p, const char *name, SylExternFn fn, void *user) {
    for (int k = 0; k < p->nfns; k++) {
        Function *f = &p->fns[k];
        if (f->external && !strcmp(f->name, name)) {
            f->bound = fn;
            f->bound_user = fn ? user : NULL;
            return SYL_OK;
        }
    }
    return SYL_EUSAGE;
}
