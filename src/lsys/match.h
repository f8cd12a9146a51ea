/* Branch-aware context matching (ABOP §1.8): a left context looks back along the path to
 * the root, a right context looks forward along the axis and into branches it names.
 *
 * Two linear passes per step give every module its neighbours: left[i], the previous
 * module on the path to the root, and right[i], the next one along its axis (skipping
 * side branches and ignored symbols). Contexts then follow these links instead of walking
 * the string; only right contexts that name branches walk, using the bracket pairs. Which
 * way a rule is matched is the rule's own (Rule.right_branches): a table may need both. */
#ifndef SYL_MATCH_H
#define SYL_MATCH_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lang/program.h"

/* What the matcher reads: the string, its links and parameter offsets. */
typedef struct View {
    const uint16_t *code;
    const double *par;
    const uint32_t *poff;  /* NULL when no module has parameters */
    const int32_t *left;   /* -1: none */
    const int32_t *right;  /* -1: none */
    const uint16_t *lcode, *rcode; /* the codes of those neighbours (CODE_NONE: none) */
    const int32_t *pair;   /* for '[' the index of its ']' and the other way round */
    const uint8_t *rclass; /* or, for run_chunk_classes, the class of the right neighbour's code */
    const struct ClassPlan *plan; /* with rclass: the class pass's table (classes.h) */
    size_t n;
    const bool *skip;      /* symbols ignored in contexts */
} View;

static inline void match_bind(const View *v, size_t pos, const PatElem *pe, double *locals) {
    int ar = CODE_ARITY(pe->code);
    for (int k = 0; k < ar; k++) locals[pe->local + k] = v->par[v->poff[pos] + (uint32_t)k];
}

/* Match rule r's contexts around module i, binding their parameters into locals. */
/* A code no module has (symbol 0 is '[', which never has parameters). */
#define CODE_NONE CODE(SYM_OPEN, MAX_ARITY)

static inline bool match_left(const View *v, size_t i, const Rule *r, double *locals) {
    /* the neighbour's code sits beside module i: most rules are rejected without a jump */
    if (v->lcode[i] != r->left[r->nleft - 1].code) return false;
    if (!v->left) return true; /* no links: every left context is one module without parameters */
    int32_t pos = (int32_t)i;
    for (int j = r->nleft - 1; j >= 0; j--) {
        pos = v->left[pos];
        if (pos < 0 || v->code[pos] != r->left[j].code) return false;
        match_bind(v, (size_t)pos, &r->left[j], locals);
    }
    return true;
}

bool match_branches(const View *v, size_t i, const Rule *r, double *locals); /* walks, with pair[] */

static inline bool match_right(const View *v, size_t i, const Rule *r, double *locals) {
    if (r->right_branches) return match_branches(v, i, r, locals);
    if (v->rcode[i] != r->right[0].code) return false;
    if (!v->right) return true; /* likewise */
    int32_t pos = (int32_t)i;
    for (int j = 0; j < r->nright; j++) {
        pos = v->right[pos];
        if (pos < 0 || v->code[pos] != r->right[j].code) return false;
        match_bind(v, (size_t)pos, &r->right[j], locals);
    }
    return true;
}

/* New right contexts (newctx.c): a pattern that is not the rule's old context, matched after
 * position i of a view of the new string (i is where the successor goes). */
bool match_right_pat(const View *v, size_t i, const PatElem *pat, int n, bool branches, double *locals);

/* Fill the links and neighbour codes; stack must hold n entries. Strings always have
 * balanced brackets. */
void match_link_left(const uint16_t *code, size_t n, const bool *skip, int32_t *left, uint16_t *lcode,
                     int32_t *stack);
void match_link_right(const uint16_t *code, size_t n, const bool *skip, int32_t *right, uint16_t *rcode,
                      int32_t *stack);
void match_pairs(const uint16_t *code, size_t n, int32_t *pair);
/* What a module is to the class scans, a byte per code: its class (RuleTable.ctx_class) or
 * one of ACT_*, so that a scan reads one table instead of the symbol, skip and class. */
enum { ACT_SKIP = 0xfd, ACT_CLOSE = 0xfe, ACT_OPEN = 0xff };
void match_class_actions(const uint8_t *cls, const bool *skip, uint8_t *act);
/* rclass[i] = the class of module i's right neighbour (cls[CODE_NONE], in act: none); the
 * right links of match_link_right in one byte a module; stack must hold n entries. (The
 * class pass writes them as it writes a string, run_chunk_classes: this is for the first.) */
void match_class_right(const uint16_t *code, size_t n, const uint8_t *act, uint8_t none, uint8_t *rclass,
                       uint8_t *stack);

#endif
