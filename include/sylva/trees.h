/* Procedural trees: a `weber` block (Weber & Penn 1995, also read from Arbaro's XML species
 * files) and a `strands` block (Holton 1994, as in Zamuda's modeller) build a skeleton straight
 * from their parameters, the same skeleton an L-system or a grown tree gives, so the mesher,
 * the renderer, metrics and every file format take it unchanged. docs/weberpenn.md and
 * docs/strands.md list the parameters. */
#ifndef SYLVA_TREES_H
#define SYLVA_TREES_H
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "sylva.h"
#include "skeleton.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct SylTreeOptions {
    bool use_seed;       /* seed below instead of the block's own */
    uint64_t seed;
    uint64_t seed_offset; /* added to the block's own seed (a scene's n-th plant: n) */
    int threads;         /* 0: all cores; the tree is the same for any count */
    double age;          /* strands: age t in (0, 1] (S' = t^2 S, l0' = t^2 l0); 0: full grown */
    int levels;          /* weber: stop at this many stem levels (0: the block's Levels) */
    uint64_t max_memory; /* bytes, when budget is NULL; 0: the default */
    SylBudget *budget;
    FILE *diag;
    /* asked (sylva.h) by weber before each trunk, each first-level branch, the nodes and the
     * leaves, by strands before every 4,096 segments, by pafco before its trunk and each whorl
     * of its crown, by curvetree before its trunk's nodes and each first-level branch's; the
     * other kinds never ask. NULL: never */
    const SylCancel *cancel;
} SylTreeOptions;

/* The tree of a compiled `weber` or `strands` program. SYL_OK, SYL_EUSAGE for another kind
 * of model, SYL_ELIMIT beyond the memory budget. */
int syl_weber_build(const SylProgram *p, const SylTreeOptions *opt, SylSkeleton **out);
int syl_strands_build(const SylProgram *p, const SylTreeOptions *opt, SylSkeleton **out);
/* A `curvetree` block: the Blender plug-in's tree grown from a trunk curve inside a crown
 * envelope (docs/curvetree.md). */
int syl_curvetree_build(const SylProgram *p, const SylTreeOptions *opt, SylSkeleton **out);
/* Pafčo's generator (docs/pafco.md): opt->age in (0, 1] scales the tree's height. */
int syl_pafco_build(const SylProgram *p, const SylTreeOptions *opt, SylSkeleton **out);

/* Check a block's parameters as `sylva check` does (syl_validate calls these): returns
 * the number of errors reported to diag, each with file:line:col, the line and a caret
 * (negative when every error was of --set, a bad command line). */
int syl_weber_validate(const SylProgram *p, FILE *diag);
int syl_strands_validate(const SylProgram *p, FILE *diag);
int syl_curvetree_validate(const SylProgram *p, FILE *diag);
int syl_pafco_validate(const SylProgram *p, FILE *diag);

#ifdef __cplusplus
}
#endif

#endif
