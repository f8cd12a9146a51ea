/* The plan of the class pass (rewrite.c, run_chunk_classes): tables whose contexts are one
 * module without parameters on each side, read by their neighbours' classes.
 *
 * Per module code, where its rule is: one entry for a plain rule or for a module no rule
 * rewrites, a block of nclass * nclass entries, indexed by the neighbours' classes, for a
 * module of fast rules (one load a module where the dispatch took three).
 *
 * The pass also writes the right classes of the string it writes, for the next pass of the
 * same table, so that no pass over the whole string looks for them (match_class_right): a
 * module's right class is known once the next module along its axis is written, and a
 * successor's own modules find theirs inside it, from a template made here. */
#ifndef SYL_LSYS_CLASSES_H
#define SYL_LSYS_CLASSES_H
#include <stdbool.h>
#include <stdint.h>

#include "lang/program.h"

typedef struct ClassSucc {
    const Rule *rule;      /* NULL: the module stays */
    uint32_t n;            /* its successor's length */
    uint16_t code[SUCC_PAD]; /* its first SUCC_PAD codes (the rule's own, one load nearer) */
    uint8_t rt[SUCC_PAD];  /* the right classes its successor's modules find inside it */
    uint8_t has_base;      /* its successor has a module, outside its branches, that is not ignored */
    uint8_t first;         /* the class of the first such: the right class of the module before */
    uint8_t last;          /* the offset of the last such: its right class comes later */
} ClassSucc;

typedef struct ClassCode {
    uint32_t base; /* the code's first entry */
    uint8_t mask;  /* 0xff: the entry is base + left class * nclass + right class; 0: base */
    uint8_t act;   /* match_class_actions */
    uint8_t row;   /* with act a class: act * nclass, the row of pick tables it is the left of */
} ClassCode;

typedef struct ClassPlan {
    ClassCode *code; /* CODE_COUNT entries */
    uint8_t *act;    /* the same acts, a byte a code, for match_class_right */
    ClassSucc *succ; /* entry 0: the module stays */
    uint8_t none;    /* the class of no neighbour */
    /* the right classes the pass writes are those of its output: every successor is short
     * (SUCC_PAD) with balanced brackets, and every module that reads a right class is one
     * that a context names (not ignored, not a bracket) */
    bool writes_right;
} ClassPlan;

/* Build the plan of t (t->nclass > 0, t->all_fast); false when out of memory. */
bool class_plan_build(ClassPlan *cp, const RuleTable *t, const bool *skip);
void class_plan_free(ClassPlan *cp);

#endif
