/* Rewriting one chunk of a string with one table: what a thread of a pass does (rewrite.c). */
#ifndef SYL_LSYS_REWRITE_H
#define SYL_LSYS_REWRITE_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsys/match.h"
#include "lsys/modstr.h"
#include "lang/vm.h"
#include "util/rng.h"

enum { LIMIT_MODULES = 1, LIMIT_MEMORY, LIMIT_WORK };

typedef struct Fault {
    int status;      /* SYL_OK, SYL_EMODEL or SYL_ELIMIT */
    int limit;       /* with SYL_ELIMIT: LIMIT_* */
    VmFault vm;
    size_t pos;      /* the module being rewritten */
    const Rule *rule;
} Fault;

/* One chunk of one pass. */
typedef struct Work {
    const SylProgram *p;
    const RuleTable *t;
    const View *in;
    size_t lo, hi;
    uint32_t plo;     /* offset of module lo's parameters */
    SylString *out;
    uint64_t key;     /* step and pass, for the random streams */
    int table;
    uint64_t seed;
    bool applied;     /* a rule other than identity was used */
    bool codes_only;  /* no parameters in or out, plain or fast rules: run_chunk_codes */
    uint8_t *stack;   /* set for run_chunk_classes (in->rclass): room for n left classes */
    /* with stack: the output's right classes, module j's at (*rnext)[1 + j] ([0] is written
     * for no module), grown with the output; room for n positions in it waiting for theirs */
    uint8_t **rnext;
    size_t *cap_rnext;
    uint32_t *pend;
    /* in place (derive.c): out is also the string read, whose module i sits at out->code[at +
     * i] and parameter j at out->par[pat + j]; n_in and np_in are its sizes */
    bool inplace;
    size_t at, pat, n_in, np_in;
    size_t np_all;    /* parameters of modules lo..hi (set for a pass of one chunk) */
    /* a split pass of a plain table (rewrite_size): the output has room for all the chunk
     * writes (exact: no capacity check); n_out and np_out are its sizes, and the modules from
     * cut (parameters from pcut) are its tail */
    bool exact;
    size_t n_out, np_out, cut, pcut;
    const struct Rule **cand; /* applicable weighted rules of one module, and their weights */
    double *weight;
    int ncap;
    Fault fault;
} Work;

/* Plain tables (all_plain): what chunk lo..hi writes, n_out codes and np_out parameters (each
 * code's successor has one size), and its tail, the last modules whose output holds at least
 * what a write before them may spill past its end (SUCC_PAD codes, SLOT_PLAN parameters;
 * REWRITE_SPILL): written anywhere else and copied, they keep the chunk's writes out of the
 * next chunk's part of one shared output. */
enum { REWRITE_SPILL_CODES = 16, REWRITE_SPILL_PARAMS = 8 };
void rewrite_size(Work *w);
/* Rewrite modules lo..hi of w->in into w->out; a fault is left in w->fault. */
void rewrite_chunk(Work *w);
/* Write rule r's successor for module pos (its parameters bound in locals) to w->out; the
 * random stream is made when first needed. SYL_OK, or SYL_EMODEL with w->fault set. */
int rewrite_emit(Work *w, const Rule *r, const double *locals, size_t pos, Rng *rng, bool *rng_ready);

/* The choice among a module's rules, for passes that match contexts their own way (newctx.c):
 * rewrite_weigh takes rule r, whose contexts match at module i, in file order (its condition,
 * then its weight; *nc and *total count the weighted candidates), and rewrite_pick draws among
 * the candidates once the rules are tried (NULL: none weighs). */
enum { WEIGH_SKIP, WEIGH_TAKE, WEIGH_ADDED, WEIGH_FAULT };
int rewrite_weigh(Work *w, const Rule *r, size_t i, double *locals, Rng *rng, bool *rng_ready, int *nc,
                  double *total, int *status);
const Rule *rewrite_pick(Work *w, int nc, double total, size_t i, Rng *rng, bool *rng_ready);

#endif
