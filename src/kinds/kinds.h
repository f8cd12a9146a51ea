/* The registry of model kinds: for each kind, the functions of the engine that owns it, as its
 * row of lang/kinds.def names them, so that code above the generators asks here instead of
 * naming kinds. What a kind can do (derived, grows, has ages, stands in a scene, ...) is its
 * flags (lang/kinds.h). */
#ifndef SYL_KINDS_H
#define SYL_KINDS_H
#include <stdio.h>

#include "sylva/sylva.h"
#include "sylva/trees.h"

typedef struct KindOps {
    /* Check a block as `sylva check` does (syl_validate calls it): the number of errors
     * reported to diag with file:line:col and a caret, negative when all were of --set.
     * NULL: the language's own checks are the whole check. */
    int (*validate)(const SylProgram *p, FILE *diag);
    /* Build the tree straight from the block's parameters, at opt->age for a kind with
     * KF_AGES (its frames), with opt->levels where it has levels. NULL: an engine above makes
     * it (lsys derives an lsystem; sot grows a grow block among the others of its scene). */
    int (*build)(const SylProgram *p, const SylTreeOptions *opt, SylSkeleton **out);
    /* What describes the block's parameters: its directive table, with names, types, ranges,
     * defaults, units and meanings (lang/schema.h; syl_describe_json reads it through
     * lang_kind_schema, the same column). NULL: none (a scene). */
    const struct SchTable *describe;
} KindOps;

/* Every kind has a row (tests/unit/test_kinds.c); a kind the enum does not know gets the
 * empty one. */
const KindOps *kinds_ops(SylModelKind k);

#endif
