/* The derivation engine's own entry: a deriver whose query modules a given environment fills. */
#ifndef SYL_LSYS_DERIVE_H
#define SYL_LSYS_DERIVE_H
#include "sylva/sylva.h"

/* The environment that fills a derivation's query modules. ops NULL: none (the modules keep
 * their values). release, when set, is called with user as the deriver ends (or when begin
 * fails): the deriver then owns user. */
typedef struct LsysQueries {
    const SylQueryOps *ops;
    void *user;
    void (*release)(void *user);
} LsysQueries;

/* syl_derive_begin with the environment q (copied). The public syl_derive_begin
 * (scene/derive.c) is this with the caller's environment or a stand-alone one. */
int lsys_derive_begin(const SylProgram *p, SylDeriveOptions *opt, const SylString *start, const LsysQueries *q,
                      SylDeriver **out);

/* Keep every `%` in the strings of d's steps: no cut when a step ends (docs/language.md §12).
 * For a reader to whom a `%` means something, as a shoot rule's "the axis ends". */
void lsys_deriver_keep_cuts(SylDeriver *d);

#endif
