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
    /* The files `sylva convert` writes the block as (KC_* of lang/kinds.h; 0: none), and the
     * function that writes it as one of them: format is one bit of converts, note (may be
     * NULL) the comment a .syl block opens with. It reads the block (its parameters, its
     * texture lines' images) before it writes, so that a bad block writes nothing; SYL_OK,
     * SYL_EMODEL (reported to diag), SYL_EUSAGE, SYL_ELIMIT or SYL_EIO. */
    unsigned converts;
    int (*convert)(const SylProgram *p, unsigned format, const char *note, FILE *out, FILE *diag);
} KindOps;

/* Every kind has a row (tests/unit/test_kinds.c); a kind the enum does not know gets the
 * empty one. */
const KindOps *kinds_ops(SylModelKind k);

#endif
