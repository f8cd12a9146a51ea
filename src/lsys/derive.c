/* The derivation engine: steps, passes of one table and the deriver API.
 *
 * A step reads one string and writes the next. The input is cut into chunks that threads
 * rewrite independently (rewrite.c); every random draw comes from a stream keyed by (seed,
 * step, table, module position), so the result is the same for any number of threads. */
#include <math.h>
#include <time.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lang/builtins.h"
#include "lang/groups.h"
#include "util/budget.h"
#include "util/parallel.h"
#include "util/pages.h"
#include "util/pool.h"
#include "lsys/derive.h"
#include "lsys/classes.h"
#include "lsys/rewrite.h"
#include "lsys/match.h"
#include "lsys/modstr.h"
#include "lsys/newctx.h"
#include "sylva/sylva.h"
#include "lang/vm.h"

enum { PARALLEL_MIN = 1 << 16, MAX_THREADS = 256, TABLE_CACHE = 8 };
/* The processor time a pass must cost per module read, times its growth, before it is split
 * (SylDeriveOptions.split_ns): a split pass writes fresh memory and joins its chunks, 5-14 ns
 * per module written more than one thread in place (bench/models/threads.syl on this machine,
 * derive --stats), so from 70 ns a split gains on two free cores (docs/architecture.md,
 * "Threads"). A machine without free cores is seen at the first split pass (no_free_cores). */
enum { SPLIT_NS = 70 };

/* The chunks of a pass (pool_run): chunk k of works; a pass with new contexts is one chunk,
 * on the calling thread. */
typedef struct Chunks {
    Work *works;
    bool newctx, back;
    struct NewctxScratch **scratch;
    uint64_t *ns;       /* each chunk's processor time (its thread's), when split */
} Chunks;

/* The processor time of the calling thread, in ns: each chunk's own cost, whatever else the
 * machine runs (the schedule model of docs/architecture.md, "Threads"). */
static uint64_t thread_ns(void) {
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static void run_chunk(void *arg, int k) {
    Chunks *c = arg;
    uint64_t t0 = c->ns ? thread_ns() : 0;
    if (c->newctx) newctx_chunk(&c->works[k], c->back, c->scratch);
    else rewrite_chunk(&c->works[k]);
    if (c->ns) c->ns[k] = thread_ns() - t0;
}

/* The chunks of a split pass and where they go in the one output: at[k], pat[k] are chunk
 * k's offsets (codes, parameters), parts[k] its own buffer, ns[k] its thread's time. */
typedef struct Parts {
    Work *works; /* NULL for a join */
    SylString *out, *parts;
    size_t *at, *pat;
    uint64_t *ns;
} Parts;

/* A split pass of a plain table writes one output sized in advance (no join): first each
 * chunk's size (rewrite_size), then, at the offsets their sums give, each chunk writes its
 * part itself, so that its pages are first touched by its own thread. A chunk's tail goes to
 * its own buffer and is copied after, so that no write spills into the next chunk's part. */

static void size_chunk(void *arg, int k) {
    Parts *x = arg;
    uint64_t t0 = thread_ns();
    rewrite_size(&x->works[k]);
    x->ns[k] = thread_ns() - t0;
}

static void write_chunk(void *arg, int k) {
    Parts *x = arg;
    Work *w = &x->works[k];
    uint64_t t0 = thread_ns();
    size_t hi = w->hi;
    SylString part = {.code = x->out->code + x->at[k], .par = x->out->par ? x->out->par + x->pat[k] : NULL,
                      .cap = w->n_out + REWRITE_SPILL_CODES, .pcap = w->np_out + REWRITE_SPILL_PARAMS};
    SylString *tail = &x->parts[k];
    Work t = *w; /* the tail's, into tail */
    w->out = &part;
    w->exact = true;
    w->hi = w->cut;
    rewrite_chunk(w);
    if (!w->fault.status && w->cut < hi) {
        t.lo = w->cut, t.plo = (uint32_t)w->pcut, t.out = tail, t.cand = NULL, t.weight = NULL, t.ncap = 0;
        rewrite_chunk(&t);
        w->applied |= t.applied;
        if (t.fault.status) w->fault = t.fault;
        else {
            if (tail->n) memcpy(part.code + part.n, tail->code, tail->n * sizeof *tail->code);
            if (tail->np) memcpy(part.par + part.np, tail->par, tail->np * sizeof *tail->par);
        }
        free(t.cand);
        free(t.weight);
    }
    w->hi = hi;
    w->out = x->out;
    x->ns[k] = thread_ns() - t0;
}

/* The second half of a pass of several chunks: chunk k (> 0), written to a buffer of its
 * own, is copied into the output at the offsets the chunks before it sum to, by its own
 * thread, so that the copies run side by side and each thread first-touches its part. */
static void join_chunk(void *arg, int k) {
    Parts *j = arg;
    const SylString *part = &j->parts[k];
    j->ns[k] = 0;
    if (!k) return;
    uint64_t t0 = thread_ns();
    if (part->n) memcpy(j->out->code + j->at[k], part->code, part->n * sizeof *part->code);
    if (part->np) memcpy(j->out->par + j->pat[k], part->par, part->np * sizeof *part->par);
    j->ns[k] = thread_ns() - t0;
}

/* The sum and the largest of n costs, added to *sum and *max. */
static void add_costs(const uint64_t *ns, int n, uint64_t *sum, uint64_t *max) {
    uint64_t m = 0;
    for (int k = 0; k < n; k++) {
        *sum += ns[k];
        if (ns[k] > m) m = ns[k];
    }
    *max += m;
}

/* ---- one pass over a string ---- */

typedef struct Engine {
    const SylProgram *p;
    Budget own;         /* the memory budget when the caller shares none */
    Budget *mem;        /* own or the caller's */
    uint64_t max_modules, max_work;
    int threads;
    uint64_t seed;
    FILE *diag;
    /* context links of the string being read, each grown as needed and kept for the next step */
    int32_t *left, *right, *pair, *stack;
    uint16_t *lcode, *rcode;
    uint8_t *rclass, *cstack; /* run_chunk_classes: right neighbours' classes, left classes' stack */
    uint8_t *rnext;             /* and those of the string it writes (both from [1]), */
    uint32_t *pend;             /* with the modules waiting for theirs */
    ClassPlan plan;             /* of the table plan_for */
    const RuleTable *plan_for;
    /* rclass holds the right classes of rclass_of (rclass_n modules) under plan_for's plan,
     * written by the pass that wrote it; NULL when any other pass or the cut came since */
    const SylString *rclass_of;
    size_t rclass_n;
    struct NewctxScratch *newctx; /* the arrays of passes with new contexts */
    Pool *pool;         /* the threads of passes of several chunks, made on the first */
    SylString *parts;   /* their buffers (chunks 1..threads-1), kept from pass to pass */
    size_t cap_left, cap_right, cap_pair, cap_stack, cap_lcode, cap_rcode, cap_rclass, cap_cstack, cap_rnext, cap_pend;
    double growth[TABLE_COUNT], density[TABLE_COUNT]; /* last pass: out/in modules, params/module */
    double cost[TABLE_COUNT];   /* last pass: its chunks' processor time per module read (ns) */
    double split_ns;            /* the cost from which a pass is split */
    bool no_free_cores;         /* a split pass's chunks did not run at once: no more splits, */
    bool measure;               /* unless split_ns was given (to measure the splits) */
    uint64_t rewritten;
    uint64_t split_passes, chunk_ns, chunk_max_ns, join_ns, join_max_ns; /* SylDeriveOptions' */
    uint64_t work;      /* modules read by all passes, each at least 100 (max_work) */
    bool warned_depth;
    bool reported;      /* an error was reported: one message per failure */
    LsysQueries queries; /* what fills query modules */
    /* models with groups: the rule table of each set of active groups met, built when first
     * needed (a handful per derivation), so that the hot loop never tests a rule's group */
    struct {
        int table;
        uint64_t active;
        RuleTable t;
        Arena arena;
    } cache[TABLE_CACHE];
    int ncache, evict;
    int active_step;    /* the step whose groups `active` holds, -1 none */
    uint64_t active;
    int cut_sym;        /* the symbol of `%`, -1 when the program has none */
} Engine;

static void report(Engine *e, const Work *w, int step, const char *what) {
    e->reported = true;
    if (!program_heard(e->p, e->diag)) return;
    const SylProgram *p = e->p;
    Diag d = {.out = e->diag, .sink = program_sink(p), .src = &p->src};
    if (w->fault.status == SYL_ELIMIT) {
        if (w->fault.limit == LIMIT_MODULES)
            program_say(e->p, e->diag, DIAG_ERROR, NULL, "%s %d would exceed the limit of %llu modules; raise it with --max-modules",
                    what, step, (unsigned long long)e->max_modules);
        else if (w->fault.limit == LIMIT_WORK)
            program_say(e->p, e->diag, DIAG_ERROR, NULL, "%s %d would take the derivation past %llu modules rewritten by all its steps "
                    "together; raise the limit with --max-work",
                    what, step, (unsigned long long)e->max_work);
        else if (atomic_load(&e->mem->refused))
            program_say(e->p, e->diag, DIAG_ERROR, NULL, "%s %d would need more than %llu MB of memory; raise the limit with "
                    "--max-memory",
                    what, step, (unsigned long long)budget_limit_mb(e->mem));
        else program_say(e->p, e->diag, DIAG_ERROR, NULL, "%s %d: out of memory", what, step);
        return;
    }
    SylLoc loc = w->fault.rule ? w->fault.rule->loc : (SylLoc){0};
    if (w->fault.vm.status && w->fault.vm.pc < (uint32_t)p->ncode) loc = p->code_loc[w->fault.vm.pc];
    const char *name = w->fault.rule && w->fault.rule != &p->axiom ? p->syms[CODE_SYM(w->fault.rule->pred)].name : NULL;
    if (name)
        diag_error(&d, loc, "%s (%s %d, module %zu '%s')", syl_eval_error_text(w->fault.vm.status), what, step,
                   w->fault.pos + 1, name);
    else
        diag_error(&d, loc, "%s (%s %d, module %zu)", syl_eval_error_text(w->fault.vm.status), what, step,
                   w->fault.pos + 1);
}

static void engine_free(Engine *e) {
    if (e->queries.release) e->queries.release(e->queries.user);
    for (int k = 0; k < e->ncache; k++) arena_free(&e->cache[k].arena);
    ms_scratch_free(e->left, e->cap_left, sizeof *e->left);
    ms_scratch_free(e->right, e->cap_right, sizeof *e->right);
    ms_scratch_free(e->pair, e->cap_pair, sizeof *e->pair);
    ms_scratch_free(e->stack, e->cap_stack, sizeof *e->stack);
    ms_scratch_free(e->lcode, e->cap_lcode, sizeof *e->lcode);
    ms_scratch_free(e->rcode, e->cap_rcode, sizeof *e->rcode);
    ms_scratch_free(e->rclass, e->cap_rclass, 1);
    free(e->cstack);
    ms_scratch_free(e->rnext, e->cap_rnext, 1);
    free(e->pend);
    class_plan_free(&e->plan);
    newctx_release(&e->newctx);
    pool_free(e->pool);
    for (int k = 0; e->parts && k < e->threads; k++) ms_release(&e->parts[k]);
    free(e->parts);
}

/* Whether step is derived backward (`direction`): asked only by tables with new contexts. */
static int direction_backward(Engine *e, int step, const char *what, bool *back) {
    const SylProgram *p = e->p;
    *back = p->backward;
    if (p->direction_when < 0) return SYL_OK;
    double locals[1] = {(double)step}, v;
    Rng rng = rng_stream(e->seed, (uint64_t)step << 16, TABLE_COUNT + 1, 0);
    VmFault f = {0};
    if (vm_run(p, (uint32_t)p->direction_when, locals, &rng, &v, &f)) {
        e->reported = true;
        if (program_heard(p, e->diag)) {
            Diag d = {.out = e->diag, .sink = program_sink(p), .src = &p->src};
            SylLoc loc = f.pc < (uint32_t)p->ncode ? p->code_loc[f.pc] : p->code_loc[p->direction_when];
            diag_error(&d, loc, "%s (the direction of %s %d)", syl_eval_error_text(f.status), what, step);
        }
        return SYL_EMODEL;
    }
    if (v == 0) *back = !p->backward;
    return SYL_OK;
}

/* The rules of table `table` that take part at `step`: all of them when the model has no
 * groups in that table; else the table of the groups its `use` lines select, from the cache. */
static int select_table(Engine *e, int table, int step, const RuleTable **out) {
    const SylProgram *p = e->p;
    *out = &p->tables[table];
    if (!p->grouped[table]) return SYL_OK;
    if (e->active_step != step) {
        VmFault f = {0};
        int g = 0;
        if (lang_groups_active(p, step, e->seed, &e->active, &f, &g)) {
            e->reported = true;
            if (program_heard(p, e->diag)) {
                Diag d = {.out = e->diag, .sink = program_sink(p), .src = &p->src};
                SylLoc loc = f.pc < (uint32_t)p->ncode ? p->code_loc[f.pc] : p->groups[g].loc;
                diag_error(&d, loc, "%s (use of group '%s' at step %d)", syl_eval_error_text(f.status),
                           p->groups[g].name, step);
            }
            return SYL_EMODEL;
        }
        e->active_step = step;
    }
    uint64_t active = e->active & p->grouped[table];
    for (int k = 0; k < e->ncache; k++)
        if (e->cache[k].table == table && e->cache[k].active == active) {
            *out = &e->cache[k].t;
            return SYL_OK;
        }
    int k = e->ncache < TABLE_CACHE ? e->ncache++ : e->evict++ % TABLE_CACHE;
    arena_free(&e->cache[k].arena);
    if (e->plan_for == &e->cache[k].t) e->plan_for = NULL; /* the same address, other rules */
    e->cache[k].table = table;
    e->cache[k].active = active;
    if (!lang_table_select(p, table, active, &e->cache[k].t, &e->cache[k].arena)) {
        arena_free(&e->cache[k].arena);
        e->cache[k].table = -1;
        return SYL_ELIMIT;
    }
    *out = &e->cache[k].t;
    return SYL_OK;
}

/* Whether a pass may write its string over the one it reads (rewrite.c's make_room): one
 * thread; a string that grew by an eighth or more last time (a stable or shrinking one gains
 * nothing: the spare buffer is already big enough) and whose arrays are in whole pages, so
 * that moving it back moves pages instead of copying bytes; rules that read their contexts
 * from the neighbour arrays alone, never from modules already passed. In place, a step
 * touches fresh memory only for its growth, where two buffers fill the spare one as well. */
static bool in_place(const Engine *e, const RuleTable *t, int table, const SylString *in, int nt) {
    if (nt != 1 || e->growth[table] < 1.125 || t->has_newctx) return false;
    if (in->cap * sizeof *in->code < PAGES_BIG || (in->np && in->pcap * sizeof *in->par < PAGES_BIG)) return false;
    return !t->has_context || (!t->ctx_index && !t->ctx_branches && !in->np);
}

/* Move the string read to the back of its arrays, by the room the output should need; the
 * string before it (spare, not needed while strings grow) gives its pages to the front. */
static int move_back(Engine *e, int table, SylString *s, Work *w, SylString *spare) {
    size_t n = s->n, np = s->np;
    double g = e->growth[table] * 1.02, slack = (double)n / 64 + 4096;
    size_t room = (size_t)((g - 1) * (double)n + slack);
    size_t proom = (size_t)((double)n * g * e->density[table] * 1.02 - (double)np + slack);
    if (e->density[table] * g * (double)n < (double)np) proom = (size_t)slack;
    int st = ms_move_back(s, n, np, room, proom, &w->at, &w->pat, spare);
    if (st) return st;
    w->inplace = true;
    w->n_in = n;
    w->np_in = np;
    s->n = s->np = 0;
    return SYL_OK;
}

/* A stack as deep as n modules may nest, in small pages (malloc): only the depth of the
 * branches is used, and a 2 MB page would be zeroed for its first bytes. Not kept. */
/* A split pass done (begun at w0): its chunks' times counted; when they took as long side by
 * side as one after the other would, the machine has no core to spare (as this one, shared),
 * and the next passes are not split. */
static void split_done(Engine *e, const uint64_t *ns, int nt, const struct timespec *w0, uint64_t *sum,
                       uint64_t *longest) {
    struct timespec w1;
    clock_gettime(CLOCK_MONOTONIC, &w1);
    e->split_passes++;
    add_costs(ns, nt, &e->chunk_ns, &e->chunk_max_ns);
    add_costs(ns, nt, sum, longest);
    double wall = (double)(w1.tv_sec - w0->tv_sec) * 1e9 + (double)(w1.tv_nsec - w0->tv_nsec);
    if (wall * 1.25 > (double)*sum) e->no_free_cores = true;
}

static bool stack_reserve(void **arr, size_t *cap, size_t n, size_t elem) {
    if (n <= *cap) return true;
    free(*arr);
    *cap = (*arr = malloc(n * elem)) ? n : 0;
    return *arr != NULL;
}

/* Rewrite *cur with table t (of kind `table`) into *spare (emptied first), or over itself,
 * then make the result *cur. Returns a SYL_* status. */
static int rewrite_pass(Engine *e, const RuleTable *t, int table, uint64_t key, SylString **cur,
                        SylString **spare, bool *applied, int step, const char *what) {
    const SylProgram *p = e->p;
    SylString *in = *cur, *out = *spare;
    const SylString *rclass_of = e->rclass_of;
    e->rclass_of = NULL; /* whatever this pass writes, the classes kept describe another string */
    e->rewritten += in->n;
    /* a pass costs at least as much as rewriting 100 modules: a million steps of one module
     * is work too */
    e->work += in->n + 100;
    if (e->work > e->max_work) {
        Work w = {.fault = {.status = SYL_ELIMIT, .limit = LIMIT_WORK}};
        report(e, &w, step, what);
        return SYL_ELIMIT;
    }
    /* Chunks of PARALLEL_MIN modules at least. A pass of a light table (no VM, no matching
     * beyond one neighbour) stays on one thread: split, it cost 1.4-3.3x the processor time
     * on the bench models (docs/bench.md, "Threads"): it is bound by memory, and one thread
     * rewrites in place or by classes, which chunks cannot. A plain table's split pass writes
     * one output sized in advance (write_chunk), no join: it may leave in place for chunks. */
    int nt = e->threads;
    if ((size_t)nt > in->n / PARALLEL_MIN) nt = (int)(in->n / PARALLEL_MIN);
    if (nt < 1) nt = 1;
    bool codes_only = !in->np && !t->emits_params && (t->all_plain || t->all_fast);
    bool by_classes = codes_only && t->all_fast && t->nclass > 0 && t->ctx_right && !t->ctx_index &&
                      !t->ctx_branches && !t->has_newctx;
    if (nt > 1 && (t->light || by_classes || (!t->all_plain && in_place(e, t, table, in, 1)))) nt = 1;
    /* a pass that costs too little per module stays whole (an unmeasured one too: the first
     * passes of a table are short) */
    double g = e->growth[table] > 1 ? e->growth[table] : 1;
    if (nt > 1 && (e->cost[table] < e->split_ns * g || (e->no_free_cores && !e->measure))) nt = 1;
    Work place = {0};
    size_t n_in = in->n, np_in = in->np;
    if (in_place(e, t, table, in, nt)) {
        int st = move_back(e, table, in, &place, *spare); /* which empties *spare */
        if (st) return st;
        out = in;
    }
    out->n = out->np = 0;
    ms_changed(out); /* the offset cache describes the old contents */
    View v = {.code = in->code, .par = in->par, .n = n_in, .skip = p->skip};
    if (place.inplace) {
        v.code = in->code + place.at;
        v.par = in->par ? in->par + place.pat : NULL;
    }
    /* one thread, contexts of one module without parameters on both sides, pick tables:
     * run_chunk_classes follows the left neighbours itself and reads the right ones' classes */
    bool classes = nt == 1 && by_classes;
    if (classes) {
        bool known = e->plan_for == t && rclass_of == in && e->rclass_n == n_in; /* cap_rclass >= n_in */
        if (!ms_scratch_reserve(&e->rclass, &e->cap_rclass, n_in + 1, 1) ||
            !stack_reserve((void **)&e->cstack, &e->cap_cstack, n_in + 1, 1) ||
            !stack_reserve((void **)&e->pend, &e->cap_pend, n_in + 1, sizeof *e->pend))
            return SYL_ELIMIT;
        if (e->plan_for != t) { /* once per table: 64 K codes */
            e->plan_for = NULL;
            if (!class_plan_build(&e->plan, t, p->skip)) return SYL_ELIMIT;
            e->plan_for = t;
        }
        if (!known) match_class_right(v.code, n_in, e->plan.act, e->plan.none, e->rclass + 1, e->cstack);
        v.rclass = e->rclass + 1;
        v.plan = &e->plan;
    } else if (t->has_context) {
        if (np_in) {
            v.poff = ms_offsets(in);
            if (!v.poff) return SYL_ELIMIT;
        }
        size_t n = n_in;
        /* indices are needed to bind context parameters or follow longer contexts;
         * rules of the fast kind compare neighbour codes only */
        bool idx = t->ctx_index;
        if (t->ctx_branches) {
            if (!ms_scratch_reserve(&e->pair, &e->cap_pair, n, sizeof *e->pair)) return SYL_ELIMIT;
            match_pairs(v.code, n, e->pair);
            v.pair = e->pair;
        }
        if ((t->ctx_left || t->ctx_right) &&
            !ms_scratch_reserve(&e->stack, &e->cap_stack, 2 * n + 2, sizeof *e->stack))
            return SYL_ELIMIT;
        if (t->ctx_left) {
            if (!ms_scratch_reserve(&e->lcode, &e->cap_lcode, n, sizeof *e->lcode) ||
                (idx && !ms_scratch_reserve(&e->left, &e->cap_left, n, sizeof *e->left)))
                return SYL_ELIMIT;
            match_link_left(v.code, n, p->skip, idx ? e->left : NULL, e->lcode, e->stack);
            v.left = idx ? e->left : NULL;
            v.lcode = e->lcode;
        }
        if (t->ctx_right) {
            if (!ms_scratch_reserve(&e->rcode, &e->cap_rcode, n, sizeof *e->rcode) ||
                (idx && !ms_scratch_reserve(&e->right, &e->cap_right, n, sizeof *e->right)))
                return SYL_ELIMIT;
            match_link_right(v.code, n, p->skip, idx ? e->right : NULL, e->rcode, e->stack);
            v.right = idx ? e->right : NULL;
            v.rcode = e->rcode;
        }
    }
    bool back = false;
    if (t->has_newctx) { /* each module reads what the one before it wrote: one thread */
        nt = 1;
        int st = direction_backward(e, step, what, &back);
        if (st) return st;
    }
    /* size the output from the last pass's growth, so that it is rarely moved */
    if (nt == 1 && e->growth[table] > 0 && !place.inplace) {
        size_t want = (size_t)((double)n_in * e->growth[table] * 1.02) + 64;
        size_t pwant = (size_t)((double)want * e->density[table] * 1.02) + 64;
        if (want > e->max_modules) want = (size_t)e->max_modules;
        ms_reserve(out, want, pwant); /* a refusal here is met again, and reported, below */
    }
    if (nt > 1 && ((!e->pool && !(e->pool = pool_new(e->threads))) ||
                   (!e->parts && !(e->parts = calloc((size_t)e->threads, sizeof *e->parts)))))
        nt = 1; /* no pool: one thread does it all */
    Work works[MAX_THREADS];
    SylString *parts = e->parts;
    /* where each chunk's parameters start */
    uint32_t plo = 0;
    size_t lo = 0;
    for (int k = 0; k < nt; k++) {
        size_t hi = k == nt - 1 ? n_in : n_in / (size_t)nt * (size_t)(k + 1);
        works[k] = (Work){.p = p, .t = t, .in = &v, .lo = lo, .hi = hi, .plo = plo, .key = key,
                          .table = table, .seed = e->seed, .out = k ? &parts[k] : out,
                          .codes_only = codes_only, .stack = classes ? e->cstack : NULL,
                          .rnext = &e->rnext, .cap_rnext = &e->cap_rnext, .pend = e->pend,
                          .inplace = place.inplace, .at = place.at, .pat = place.pat, .n_in = place.n_in,
                          .np_in = place.np_in, .np_all = nt == 1 ? np_in : 0};
        if (k) { /* the buffer of the last pass, emptied */
            parts[k].n = parts[k].np = 0;
            ms_changed(&parts[k]);
            parts[k].mem = e->mem;
            parts[k].max_modules = e->max_modules;
        }
        for (size_t i = lo; i < hi && k < nt - 1; i++) plo += CODE_ARITY(v.code[i]);
        lo = hi;
    }
    uint64_t ns[MAX_THREADS], sum = 0, longest = 0;
    Chunks chunks = {works, t->has_newctx, back, &e->newctx, ns}; /* has_newctx: nt is 1 */
    /* plain tables: each code's output has one size, so the chunks write one output */
    bool exact = nt > 1 && t->all_plain && !t->has_newctx && !place.inplace;
    int status = SYL_OK;
    bool reported = false;
    if (exact) {
        size_t at[MAX_THREADS], pat[MAX_THREADS], n = 0, np = 0;
        uint64_t sns[MAX_THREADS];
        Parts x = {works, out, parts, at, pat, sns};
        struct timespec w0;
        clock_gettime(CLOCK_MONOTONIC, &w0);
        pool_run(e->pool, nt, size_chunk, &x);
        for (int k = 0; k < nt; k++) {
            at[k] = n, pat[k] = np;
            n += works[k].n_out, np += works[k].np_out;
            works[k].out = &parts[k]; /* its tail's buffer, emptied (chunk 0's too) */
            parts[k].n = parts[k].np = 0;
            ms_changed(&parts[k]);
            parts[k].mem = e->mem;
            parts[k].max_modules = e->max_modules;
        }
        works[nt - 1].cut = works[nt - 1].hi; /* the last spills past the end: room is made */
        add_costs(sns, nt, &e->join_ns, &e->join_max_ns);
        add_costs(sns, nt, &sum, &longest);
        if (n > e->max_modules) {
            Work w = {.fault = {.status = SYL_ELIMIT, .limit = LIMIT_MODULES}};
            report(e, &w, step, what);
            status = SYL_ELIMIT;
            reported = true;
        } else if (!(status = ms_reserve(out, n + REWRITE_SPILL_CODES, np + REWRITE_SPILL_PARAMS))) {
            x.ns = ns;
            pool_run(e->pool, nt, write_chunk, &x);
            out->n = n;
            out->np = np;
            split_done(e, ns, nt, &w0, &sum, &longest);
        }
    } else if (nt > 1) {
        struct timespec w0;
        clock_gettime(CLOCK_MONOTONIC, &w0);
        pool_run(e->pool, nt, run_chunk, &chunks);
        split_done(e, ns, nt, &w0, &sum, &longest);
    } else {
        run_chunk(&chunks, 0);
        add_costs(ns, nt, &sum, &longest);
    }
    if (n_in >= 4096) e->cost[table] = (double)sum / (double)n_in; /* small passes: too noisy */
    for (int k = 0; k < nt; k++) {
        free(works[k].cand);
        free(works[k].weight);
    }
    for (int k = 0; k < nt && !status; k++) {
        *applied |= works[k].applied;
        if (works[k].fault.status) {
            report(e, &works[k], step, what);
            status = works[k].fault.status;
            reported = true;
        }
    }
    if (nt > 1 && !exact && !status) { /* the other chunks after chunk 0, in order, copied side by side */
        size_t at[MAX_THREADS], pat[MAX_THREADS], n = out->n, np = out->np;
        for (int k = 1; k < nt; k++) {
            at[k] = n, pat[k] = np;
            n += parts[k].n, np += parts[k].np;
        }
        if (!(status = ms_reserve(out, n - out->n, np - out->np))) {
            Parts joins = {NULL, out, parts, at, pat, ns};
            pool_run(e->pool, nt, join_chunk, &joins);
            add_costs(ns, nt, &e->join_ns, &e->join_max_ns);
            out->n = n;
            out->np = np;
        }
    }
    if (!status && out->n > e->max_modules) {
        Work w = {.fault = {.status = SYL_ELIMIT, .limit = LIMIT_MODULES}};
        report(e, &w, step, what);
        status = SYL_ELIMIT;
        reported = true;
    }
    if (!status && n_in) {
        e->growth[table] = (double)out->n / (double)n_in;
        e->density[table] = out->n ? (double)out->np / (double)out->n : 0;
    }
    if (status == SYL_ELIMIT && !reported) {
        Work w = {.fault = {.status = SYL_ELIMIT, .limit = LIMIT_MEMORY}};
        report(e, &w, step, what);
    }
    if (status && place.inplace) out->n = out->np = 0; /* half rewritten: nothing to read */
    if (!status && !place.inplace) {
        *spare = in;
        *cur = out;
    }
    if (!status && classes && e->plan.writes_right) { /* the next pass of t reads them */
        uint8_t *r = e->rclass;
        size_t cap = e->cap_rclass;
        e->rclass = e->rnext, e->cap_rclass = e->cap_rnext;
        e->rnext = r, e->cap_rnext = cap;
        e->rclass_of = *cur;
        e->rclass_n = (*cur)->n;
    }
    return status;
}

/* Whether some module of s is a predecessor of the table's rules: only then could another
 * pass change the string, so only then does stopping at maxdepth deserve a warning. */
static bool any_predecessor(const RuleTable *t, const SylString *s) {
    for (size_t i = 0; i < s->n; i++)
        if (t->dispatch[s->code[i]].count) return true;
    return false;
}

/* Apply a table repeatedly until no rule applies or its maxdepth is reached. */
static int rewrite_until_stable(Engine *e, int table, int step, SylString **cur, SylString **spare) {
    const RuleTable *t = &e->p->tables[table];
    if (!t->nrules) return SYL_OK;
    int st = select_table(e, table, step, &t);
    if (st || !t->nrules) return st;
    for (int d = 0; d < t->maxdepth; d++) {
        bool applied = false;
        st = rewrite_pass(e, t, table, (uint64_t)step << 16 | (uint64_t)d, cur, spare, &applied, step,
                          table == TABLE_DECOMPOSE ? "decomposition after step" : "interpretation of step");
        if (st) return st;
        if (!applied) break;
        if (d == t->maxdepth - 1 && !e->warned_depth && program_heard(e->p, e->diag) && any_predecessor(t, *cur)) {
            e->warned_depth = true;
            program_say(e->p, e->diag, DIAG_WARNING, NULL, "%s rules may still apply after maxdepth %d passes (step %d); "
                             "raise `maxdepth` in the block if more are meant",
                    table == TABLE_DECOMPOSE ? "decomposition" : "interpretation", t->maxdepth, step);
        }
    }
    return SYL_OK;
}

static void engine_init(Engine *e, const SylProgram *p, const SylDeriveOptions *opt) {
    memset(e, 0, sizeof *e);
    e->p = p;
    e->diag = opt->diag;
    e->seed = opt->use_seed ? opt->seed : p->seed;
    e->threads = opt->threads;
    e->split_ns = opt->split_ns ? (double)opt->split_ns : SPLIT_NS;
    e->measure = opt->split_ns != 0;
    if (e->threads <= 0) e->threads = par_threads(0);
    if (e->threads > MAX_THREADS) e->threads = MAX_THREADS;
    e->max_modules = opt->max_modules ? opt->max_modules : 200000000ull;
    if (e->max_modules > INT32_MAX) e->max_modules = INT32_MAX;
    e->max_work = opt->max_work ? opt->max_work : 100000000000ull;
    e->mem = budget_use(&e->own, opt->max_memory, opt->budget);
    e->active_step = -1;
    e->cut_sym = -1;
    for (int s = 0; s < p->nsyms; s++)
        if (p->syms[s].turtle == TC_CUT) e->cut_sym = s;
}

/* The cut (cpfg, L-Py): each `%` and the rest of its branch leave the string, up to the `]`
 * that closes the branch, which stays; a `%` outside any branch ends the string. In place. */
static void cut_branches(SylString *s, int cut) {
    size_t i = 0, n = s->n, pi = 0;
    while (i < n && CODE_SYM(s->code[i]) != cut) pi += CODE_ARITY(s->code[i++]);
    if (i == n) return;
    size_t j = i, pj = pi;
    while (i < n) {
        uint16_t c = s->code[i];
        if (CODE_SYM(c) == cut) {
            for (int depth = 0; i < n; pi += CODE_ARITY(s->code[i]), i++) {
                int sym = CODE_SYM(s->code[i]);
                if (sym == SYM_OPEN) depth++;
                else if (sym == SYM_CLOSE && depth-- == 0) break;
            }
            continue;
        }
        s->code[j++] = c;
        for (int k = CODE_ARITY(c); k > 0; k--) s->par[pj++] = s->par[pi++];
        i++;
    }
    s->n = j;
    s->np = pj;
    ms_changed(s);
}

static SylString *new_string(Engine *e) {
    SylString *s = calloc(1, sizeof *s);
    if (s) s->mem = e->mem, s->max_modules = e->max_modules;
    return s;
}

/* Strings handed to the caller count against the caller's budget until freed, and no
 * longer against a derivation's own (it goes with the deriver). */
static SylString *detach(Engine *e, SylString *s) {
    s->max_modules = 0;
    if (s->mem == &e->own) {
        budget_release(&e->own, s->charged);
        s->mem = NULL;
        s->charged = 0;
    }
    return s;
}

/* The axiom: a successor with no predecessor, evaluated in a stream of step 0. */
static int axiom(Engine *e, SylString *out) {
    const SylProgram *p = e->p;
    const Rule *r = &p->axiom;
    if (ms_reserve(out, (size_t)r->nsucc + 1, (size_t)r->nslots + 1)) return SYL_ELIMIT;
    Work w = {.p = p, .out = out, .seed = e->seed, .table = TABLE_COUNT};
    Rng rng;
    bool ready = false;
    double none[1] = {0};
    if (rewrite_emit(&w, r, none, 0, &rng, &ready)) {
        report(e, &w, 0, "axiom, step");
        return SYL_EMODEL;
    }
    return SYL_OK;
}

/* Query modules (?P ?H ?L ?U ?E) take the turtle's state after every step, as the turtle
 * sees the string: through the `interpret` rules when there are any. Those rules keep query
 * modules as they are, so the k-th query module read is the k-th of the string. The
 * environment the caller plugged in fills them (docs/language.md, "Open L-systems"). */
static bool is_query(const SylProgram *p, uint16_t code) { return lang_symbol_is_query(p, CODE_SYM(code)); }

static int query_fill(Engine *e, SylString *s, int step) {
    return e->queries.ops ? e->queries.ops->fill(e->queries.user, e->p, s, step) : SYL_OK;
}

static int fill_queries(Engine *e, SylString *s, int step) {
    const SylProgram *p = e->p;
    if (!p->uses_queries) return SYL_OK;
    /* no module with an interpret rule's symbol: s is read as it is (the passes would copy it) */
    const RuleTable *it = &p->tables[TABLE_INTERPRET];
    bool pred[MAX_SYMBOLS] = {false}, interpreted = false;
    for (int k = 0; k < it->nrules; k++) pred[CODE_SYM(it->rules[k].pred)] = true;
    for (size_t i = 0; it->nrules && !interpreted && i < s->n; i++) interpreted = pred[CODE_SYM(s->code[i])];
    if (!interpreted) return query_fill(e, s, step);
    SylString *cur = new_string(e), *spare = new_string(e);
    int st = cur && spare ? ms_reserve(cur, s->n, s->np) : SYL_ELIMIT;
    if (!st) {
        memcpy(cur->code, s->code, s->n * sizeof *s->code);
        if (s->np) memcpy(cur->par, s->par, s->np * sizeof *s->par);
        cur->n = s->n;
        cur->np = s->np;
        st = rewrite_until_stable(e, TABLE_INTERPRET, step, &cur, &spare);
    }
    if (!st) st = query_fill(e, cur, step);
    /* copy the filled values back, query module by query module */
    bool query[MAX_SYMBOLS] = {false};
    for (int k = 0; k < p->nsyms && k < MAX_SYMBOLS; k++) query[k] = is_query(p, (uint16_t)k);
    for (size_t i = 0, j = 0, pi = 0, pj = 0; !st && i < s->n; pi += CODE_ARITY(s->code[i]), i++) {
        if (!query[CODE_SYM(s->code[i])]) continue;
        while (j < cur->n && cur->code[j] != s->code[i]) pj += CODE_ARITY(cur->code[j++]);
        if (j == cur->n) break; /* an interpret rule removed it: it keeps its values */
        if (CODE_ARITY(s->code[i])) /* a ?P without parameters: the string may have none */
            memcpy(s->par + pi, cur->par + pj, sizeof(double) * CODE_ARITY(s->code[i]));
        pj += CODE_ARITY(cur->code[j++]);
    }
    syl_string_free(cur);
    syl_string_free(spare);
    e->rclass_of = NULL; /* a string of the same address may come */
    return st;
}

/* The counters the caller reads from its options. */
static void costs_out(const Engine *e, SylDeriveOptions *o) {
    o->rewritten = e->rewritten;
    o->split_passes = e->split_passes;
    o->chunk_ns = e->chunk_ns, o->chunk_max_ns = e->chunk_max_ns;
    o->join_ns = e->join_ns, o->join_max_ns = e->join_max_ns;
}

struct SylDeriver {
    Engine e;
    SylDeriveOptions *opt;
    SylDeriveOptions own_opt; /* opt when the caller passes NULL (defaults) */
    SylString *cur, *spare;
    bool may_cut; /* the program, or the start string given, holds `%` */
    int step;
    int status; /* the first error; every later call returns it */
};

/* The start string, given or the axiom: copied, then decomposed and queried (step 0). */
static int begin(SylDeriver *d, const SylString *start) {
    Engine *e = &d->e;
    int st = SYL_OK;
    if (start) {
        st = ms_reserve(d->cur, start->n, start->np);
        if (!st) {
            if (start->n) memcpy(d->cur->code, start->code, start->n * sizeof *start->code);
            if (start->np) memcpy(d->cur->par, start->par, start->np * sizeof *start->par);
            d->cur->n = start->n;
            d->cur->np = start->np;
            for (size_t i = 0; i < start->n && d->e.cut_sym >= 0; i++)
                if (CODE_SYM(start->code[i]) == d->e.cut_sym) d->may_cut = true;
        }
    } else st = axiom(e, d->cur);
    if (!st) st = rewrite_until_stable(e, TABLE_DECOMPOSE, 0, &d->cur, &d->spare);
    if (!st) st = fill_queries(e, d->cur, 0);
    if (!st && d->opt->on_step) d->opt->on_step(d->opt->user, 0, d->cur);
    return st;
}

/* Every SYL_ELIMIT says why: those not reported where they arose came from an allocation. */
static int said(Engine *e, int st, int step, const char *what) {
    if (st == SYL_ELIMIT && !e->reported) {
        Work w = {.fault = {.status = SYL_ELIMIT, .limit = LIMIT_MEMORY}};
        report(e, &w, step, what);
    }
    return st;
}

int lsys_derive_begin(const SylProgram *p, SylDeriveOptions *opt, const SylString *start, const LsysQueries *q,
                      SylDeriver **out) {
    *out = NULL;
    if (!lang_kind_is(p->kind, KF_RULES)) {
        if (opt) lang_kind_refuse(p, opt->diag, p->name, p->kind, false);
        if (q && q->release) q->release(q->user);
        return SYL_EUSAGE;
    }
    SylDeriver *d = calloc(1, sizeof *d);
    if (!d) {
        if (opt) program_say(p, opt->diag, DIAG_ERROR, NULL, "out of memory");
        if (q && q->release) q->release(q->user);
        return SYL_ELIMIT;
    }
    d->own_opt = (SylDeriveOptions){.steps = -1};
    d->opt = opt ? opt : &d->own_opt;
    engine_init(&d->e, p, d->opt);
    if (q) d->e.queries = *q;
    d->cur = new_string(&d->e);
    d->spare = new_string(&d->e);
    d->may_cut = p->may_cut;
    d->status = said(&d->e, d->cur && d->spare ? begin(d, start) : SYL_ELIMIT, 0, "step");
    *out = d;
    return d->status;
}

int syl_derive_step(SylDeriver *d) {
    if (d->status) return d->status;
    if (syl_cancelled(d->opt->cancel)) return d->status = SYL_ECANCELED; /* its caller moved on */
    Engine *e = &d->e;
    const SylProgram *p = e->p;
    int step = ++d->step, st = SYL_OK;
    const RuleTable *t = &p->tables[TABLE_PRODUCE];
    if (t->nrules) st = select_table(e, TABLE_PRODUCE, step, &t);
    if (!st && t->nrules) {
        bool applied = false;
        st = rewrite_pass(e, t, TABLE_PRODUCE, (uint64_t)step << 16, &d->cur, &d->spare, &applied, step, "step");
    }
    if (!st) st = rewrite_until_stable(e, TABLE_DECOMPOSE, step, &d->cur, &d->spare);
    if (!st && d->may_cut) {
        cut_branches(d->cur, e->cut_sym);
        e->rclass_of = NULL;
    }
    if (!st) st = fill_queries(e, d->cur, step);
    if (!st && d->opt->on_step) d->opt->on_step(d->opt->user, step, d->cur);
    costs_out(e, d->opt);
    return d->status = said(e, st, step, "step");
}

void lsys_deriver_keep_cuts(SylDeriver *d) { d->may_cut = false; }

const SylString *syl_deriver_string(const SylDeriver *d) { return d->cur; }
int syl_deriver_steps(const SylDeriver *d) { return d->step; }

int syl_derive_end(SylDeriver *d, SylString **out) {
    if (out) *out = NULL;
    if (!d) return SYL_ELIMIT;
    int st = d->status;
    costs_out(&d->e, d->opt);
    if (!st && out) *out = detach(&d->e, d->cur);
    else syl_string_free(d->cur);
    syl_string_free(d->spare);
    engine_free(&d->e);
    free(d);
    return st;
}

int syl_interpret(const SylProgram *p, const SylString *in, const SylDeriveOptions *opt, SylString **out) {
    static const SylDeriveOptions defaults = {.steps = -1};
    if (!opt) opt = &defaults;
    Engine e;
    engine_init(&e, p, opt);
    SylString *cur = new_string(&e), *spare = new_string(&e);
    int st = cur && spare ? ms_reserve(cur, in->n, in->np) : SYL_ELIMIT;
    if (!st) {
        if (in->n) memcpy(cur->code, in->code, in->n * sizeof *in->code);
        if (in->np) memcpy(cur->par, in->par, in->np * sizeof *in->par);
        cur->n = in->n;
        cur->np = in->np;
        st = rewrite_until_stable(&e, TABLE_INTERPRET, opt->steps >= 0 ? opt->steps : p->derive, &cur, &spare);
    }
    said(&e, st, opt->steps >= 0 ? opt->steps : p->derive, "interpretation of step");
    syl_string_free(spare);
    engine_free(&e);
    if (st) {
        syl_string_free(cur);
        *out = NULL;
        return st;
    }
    *out = detach(&e, cur);
    return SYL_OK;
}
