/* Rewriting one chunk of a string: each module's rule chosen (contexts, conditions, weights)
 * and its successor emitted, every random draw from the module's own stream. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lang/builtins.h"
#include "lsys/classes.h"
#include "lsys/rewrite.h"
#include "sylva/sylva.h"

static int fail(Work *w, size_t pos, const Rule *r, int status) {
    w->fault.status = SYL_EMODEL;
    w->fault.pos = pos;
    w->fault.rule = r;
    if (status != EVAL_OK && !w->fault.vm.status) w->fault.vm.status = status;
    return SYL_EMODEL;
}

/* Copy a successor's codes: short ones with one fixed-size move (both sides are padded). */
static inline void put_codes(uint16_t *dst, const Rule *r) {
    if (r->nsucc <= SUCC_PAD) memcpy(dst, r->succ, SUCC_PAD * sizeof *dst);
    else memcpy(dst, r->succ, (size_t)r->nsucc * sizeof *dst);
}

/* Successor parameters of a rule whose slots are all k, x, x + k, x - k, x * k or x / k:
 * no VM, no random stream. False if a value is not finite (emit then reports it). */
typedef uint64_t Bits2 __attribute__((vector_size(16))); /* two slots' bits */

static inline __attribute__((always_inline)) bool put_slots(double *restrict dst, const Rule *restrict r, const double *restrict x) {
    bool ok = true;
    if (r->blend) { /* no loop per kind of slot: every slot is written from the same three values */
        double y = x[r->blend_local], v = y;
        if (r->narith) {
            double k = r->arith_k[0];
            switch (r->arith_kind[0]) {
            case SLOT_ADDK: v = y + k; break;
            case SLOT_SUBK: v = y - k; break;
            case SLOT_MULK: v = y * k; break;
            default: v = y / k; break; /* SLOT_DIVK */
            }
            ok = isfinite(v) != 0;
        }
        uint64_t yb, vb;
        memcpy(&yb, &y, sizeof yb);
        memcpy(&vb, &v, sizeof vb);
        const Bits2 Y = {yb, yb}, V = {vb, vb};
#define PAIR(p)                                                                                                   \
    do {                                                                                                          \
        Bits2 t, mx, mv;                                                                                          \
        memcpy(&t, &r->tmpl[2 * (p)], sizeof t);                                                                  \
        memcpy(&mx, &r->blend_x[2 * (p)], sizeof mx);                                                             \
        memcpy(&mv, &r->blend_v[2 * (p)], sizeof mv);                                                             \
        Bits2 d = t | (Y & mx) | (V & mv);                                                                        \
        memcpy(&dst[2 * (p)], &d, sizeof d);                                                                      \
    } while (0)
        switch (r->blend_pairs) { /* unrolled: no loop counter for one to four pairs */
        case 4: PAIR(3); /* fall through */
        case 3: PAIR(2); /* fall through */
        case 2: PAIR(1); /* fall through */
        default: PAIR(0);
        }
#undef PAIR
        return ok;
    }
    if (r->planned) { /* the room of a successor's parameters holds MAX_ARITY more */
        memcpy(dst, r->tmpl, sizeof r->tmpl);
        const int ncopy = r->ncopy, narith = r->narith, ndup = r->ndup;
        for (int a = 0; a < narith; a++) {
            double v, y = x[r->arith_local[a]], k = r->arith_k[a];
            switch (r->arith_kind[a]) {
            case SLOT_ADDK: v = y + k; break;
            case SLOT_SUBK: v = y - k; break;
            case SLOT_MULK: v = y * k; break;
            default: v = y / k; break; /* SLOT_DIVK */
            }
            ok &= isfinite(v) != 0;
            dst[r->arith[a]] = v;
        }
        for (int c = 0; c < ncopy; c++) dst[r->copy_dst[c]] = x[r->copy_src[c]];
        for (int d = 0; d < ndup; d++) dst[r->dup_dst[d]] = dst[r->dup_src[d]];
        return ok;
    }
    for (int k = 0; k < r->nslots; k++) {
        const Slot *s = &r->slots[k];
        double v;
        switch (s->kind) {
        case SLOT_CONST: dst[k] = s->k; continue;
        case SLOT_LOCAL: dst[k] = x[s->local]; continue;
        case SLOT_ADDK: v = x[s->local] + s->k; break;
        case SLOT_SUBK: v = x[s->local] - s->k; break;
        case SLOT_MULK: v = x[s->local] * s->k; break;
        default: v = x[s->local] / s->k; break; /* SLOT_DIVK: vm_free rules have no other */
        }
        ok &= isfinite(v) != 0;
        dst[k] = v;
    }
    return ok;
}

static inline int emit(Work *w, const Rule *r, const double *locals, size_t pos, Rng *rng, bool *rng_ready) {
    SylString *o = w->out;
    put_codes(o->code + o->n, r);
    o->n += (size_t)r->nsucc;
    double *dst = o->par + o->np;
    if (r->planned && put_slots(dst, r, locals)) { /* else the loop below finds the value to report */
        o->np += (size_t)r->nslots;
        w->applied = true;
        return SYL_OK;
    }
    for (int k = 0; k < r->nslots; k++) {
        const Slot *s = &r->slots[k];
        double v;
        switch (s->kind) {
        case SLOT_CONST: dst[k] = s->k; continue;
        case SLOT_LOCAL: dst[k] = locals[s->local]; continue;
        case SLOT_ADDK: v = locals[s->local] + s->k; break;
        case SLOT_SUBK: v = locals[s->local] - s->k; break;
        case SLOT_MULK: v = locals[s->local] * s->k; break;
        case SLOT_DIVK: v = locals[s->local] / s->k; break;
        default:
            if (!*rng_ready) {
                *rng = rng_stream(w->seed, w->key, (uint64_t)w->table, pos);
                *rng_ready = true;
            }
            if (vm_run(w->p, s->pc, locals, rng, &dst[k], &w->fault.vm)) return fail(w, pos, r, EVAL_OK);
            continue;
        }
        if (!isfinite(v)) {
            w->fault.vm.pc = s->pc;
            return fail(w, pos, r, EVAL_NONFINITE);
        }
        dst[k] = v;
    }
    o->np += (size_t)r->nslots;
    w->applied = true;
    return SYL_OK;
}

/* Rule r, whose contexts match at module i: its condition, then its weight. The verdict is
 * WEIGH_SKIP (the condition is false), WEIGH_TAKE (unweighted: it decides), WEIGH_ADDED (a
 * candidate of the weighted choice, in w->cand) or WEIGH_FAULT (w->fault set, *status). */
static inline int weigh(Work *w, const Rule *r, size_t i, double *locals, Rng *rng, bool *rng_ready, int *nc,
                        double *total, int *status) {
    if ((r->cond >= 0 || r->weight >= 0) && !*rng_ready) {
        *rng = rng_stream(w->seed, w->key, (uint64_t)w->table, i);
        *rng_ready = true;
    }
    if (r->cond >= 0) {
        double v;
        if (vm_run(w->p, (uint32_t)r->cond, locals, rng, &v, &w->fault.vm)) {
            *status = fail(w, i, r, EVAL_OK);
            return WEIGH_FAULT;
        }
        if (v == 0) return WEIGH_SKIP;
    }
    if (!r->weighted) return WEIGH_TAKE;
    double wt = r->const_weight;
    if (r->weight >= 0 && vm_run(w->p, (uint32_t)r->weight, locals, rng, &wt, &w->fault.vm)) {
        *status = fail(w, i, r, EVAL_OK);
        return WEIGH_FAULT;
    }
    if (wt < 0) {
        w->fault.vm.pc = (uint32_t)r->weight;
        *status = fail(w, i, r, EVAL_NEG_WEIGHT);
        return WEIGH_FAULT;
    }
    if (*nc == w->ncap) { /* grows once per chunk at most a few times */
        int cap = w->ncap ? 2 * w->ncap : 16;
        const Rule **c = realloc(w->cand, sizeof *c * (size_t)cap);
        double *wt2 = c ? realloc(w->weight, sizeof *wt2 * (size_t)cap) : NULL;
        if (c) w->cand = c;
        if (!c || !wt2) {
            w->fault.status = SYL_ELIMIT;
            w->fault.limit = LIMIT_MEMORY;
            w->fault.pos = i;
            *status = SYL_ELIMIT;
            return WEIGH_FAULT;
        }
        w->weight = wt2;
        w->ncap = cap;
    }
    w->cand[*nc] = r;
    w->weight[(*nc)++] = wt;
    *total += wt;
    return WEIGH_ADDED;
}

/* The weighted choice among the nc candidates, from module i's stream; NULL when none weighs. */
static inline const Rule *pick(Work *w, int nc, double total, size_t i, Rng *rng, bool *rng_ready) {
    if (!nc || total <= 0) return NULL;
    if (!*rng_ready) {
        *rng = rng_stream(w->seed, w->key, (uint64_t)w->table, i);
        *rng_ready = true;
    }
    double u = rng_unit(rng) * total;
    int k = 0;
    while (k < nc - 1 && (u -= w->weight[k]) >= 0) k++;
    while (w->weight[k] == 0) k--; /* u landed exactly on a boundary before a zero */
    return w->cand[k];
}

int rewrite_weigh(Work *w, const Rule *r, size_t i, double *locals, Rng *rng, bool *rng_ready, int *nc,
                  double *total, int *status) {
    return weigh(w, r, i, locals, rng, rng_ready, nc, total, status);
}

const Rule *rewrite_pick(Work *w, int nc, double total, size_t i, Rng *rng, bool *rng_ready) {
    return pick(w, nc, total, i, rng, rng_ready);
}

/* Try the rules for module i in order: the first applicable one decides. If it is weighted,
 * the choice is among every applicable weighted rule, in proportion to its weight. */
static const Rule *choose(Work *w, const Dispatch *d, size_t i, double *locals, Rng *rng, bool *rng_ready,
                          int *status) {
    const RuleTable *t = w->t;
    const View *in = w->in;
    double total = 0;
    int nc = 0;
    *status = SYL_OK;
    for (uint32_t k = 0; k < d->count; k++) {
        const Rule *r = &t->rules[t->order[d->first + k]];
        if (nc && !r->weighted) continue;
        if (r->nleft && !match_left(in, i, r, locals)) continue;
        if (r->nright && !match_right(in, i, r, locals)) continue;
        int v = weigh(w, r, i, locals, rng, rng_ready, &nc, &total, status);
        if (v == WEIGH_TAKE) return r;
        if (v == WEIGH_FAULT) return NULL;
    }
    const Rule *r = pick(w, nc, total, i, rng, rng_ready);
    /* the contexts bound last may be another candidate's: bind the chosen rule's again */
    if (r && r->nleft) match_left(in, i, r, locals);
    if (r && r->nright) match_right(in, i, r, locals);
    return r;
}

/* Checked whenever an output buffer grows: the exact module count is checked after the pass. */
static bool over_limit(Work *w, size_t pos, int reserve_status) {
    if (w->out->n <= w->out->max_modules && !reserve_status) return false;
    w->fault.status = SYL_ELIMIT;
    w->fault.limit = reserve_status ? LIMIT_MEMORY : LIMIT_MODULES;
    w->fault.pos = pos;
    return true;
}

static const double no_params[1]; /* without parameters every arity is 0 */

/* Where the input's codes and parameters are now: in place they move when room is made. */
static inline const uint16_t *in_code(const Work *w) { return w->inplace ? w->out->code + w->at : w->in->code; }
static inline const double *in_par(const Work *w) {
    const double *p = w->inplace ? w->out->par : w->in->par;
    return p ? p + (w->inplace ? w->pat : 0) : no_params;
}

/* Room for `room` more codes and `proom` more parameters before module lo (parameter pi) is
 * read. In place, the writer must stay behind the reader: when it would catch up, the unread
 * rest moves further back, by what the growth seen so far says the rest will need. True when
 * a limit is hit (w->fault set). */
static bool make_room_slow(Work *w, size_t lo, size_t pi, size_t room, size_t proom) {
    SylString *o = w->out;
    if (!w->inplace) return over_limit(w, lo, ms_reserve(o, room + (w->hi - lo), proom));
    size_t gap = w->at + lo - o->n, pgap = w->pat + pi - o->np;
    size_t rest = w->n_in - lo, prest = w->np_in - pi;
    double g = lo ? (double)o->n / (double)lo : 2, pg = pi ? (double)o->np / (double)pi : 2;
    size_t want = (size_t)((g > 1 ? g - 1 : 0) * (double)rest * 1.1) + 2 * room + 1024;
    size_t pwant = (size_t)((pg > 1 ? pg - 1 : 0) * (double)prest * 1.1) + 2 * proom + 256;
    size_t extra = want > gap ? want - gap : 0, pextra = pwant > pgap ? pwant - pgap : 0;
    int st = ms_move_tail(o, w->at + lo, rest, extra, w->pat + pi, prest, pextra);
    if (!st) {
        w->at += extra;
        w->pat += pextra;
    }
    return over_limit(w, lo, st);
}

static inline bool make_room(Work *w, size_t lo, size_t pi, size_t room, size_t proom) {
    const SylString *o = w->out;
    if (w->exact) return false; /* sized by rewrite_size */
    bool fits = w->inplace ? w->at + lo - o->n >= room && w->pat + pi - o->np >= proom
                           : o->n + room <= o->cap && o->np + proom <= o->pcap;
    return !fits && make_room_slow(w, lo, pi, room, proom);
}

/* Output room is made for BATCH modules' successors at once: one capacity check per batch
 * instead of per module, and the write cursors stay in registers in between. */
enum { BATCH = 64 };
/* Modules that stay are copied one by one up to this many in a row, else moved in one go. */
enum { RUN_MIN = 4 };

/* The first of d's fast rules whose neighbour codes match, or NULL: looked up by the
 * neighbours' classes, else (too many classes) a mask of all the rules, which costs no
 * mispredicted branch per rule (which rule matches depends on the data). */
static inline const Rule *fast_pick(const RuleTable *t, const Dispatch *d, uint16_t lc, uint16_t rc) {
    if (d->pick) return d->pick[t->ctx_class[lc] * t->nclass + t->ctx_class[rc]];
    const FastRule *f = d->fast;
    for (uint32_t at = 0; at < d->count; at += 32) {
        uint32_t n = d->count - at < 32 ? d->count - at : 32, hit = 0;
        for (uint32_t k = 0; k < n; k++) {
            const FastRule *e = &f[at + k];
            hit |= (uint32_t)(((e->left == CODE_ANY) | (e->left == lc)) & ((e->right == CODE_ANY) | (e->right == rc)))
                   << k;
        }
        if (hit) return f[at + (uint32_t)__builtin_ctz(hit)].rule;
    }
    return NULL;
}

/* The neighbour codes of module i for fast rules (a side without links has no such rules). */
static inline uint16_t lcode_at(const View *in, size_t i) { return in->lcode ? in->lcode[i] : CODE_NONE; }
static inline uint16_t rcode_at(const View *in, size_t i) { return in->rcode ? in->rcode[i] : CODE_NONE; }

/* Strings without parameters under plain or fast rules that make none: codes only. */
static void run_chunk_codes(Work *w) {
    const RuleTable *t = w->t;
    const View *in = w->in;
    SylString *o = w->out;
    bool applied = false;
    for (size_t lo = w->lo; lo < w->hi; lo += BATCH) {
        size_t hi = w->hi - lo < BATCH ? w->hi : lo + BATCH;
        size_t room = (hi - lo) * (size_t)t->max_succ + SUCC_PAD;
        if (make_room(w, lo, 0, room, 0)) return;
        const uint16_t *code = in_code(w);
        uint16_t *oc = o->code + o->n;
        for (size_t i = lo; i < hi; i++) {
            uint16_t c = code[i];
            const Dispatch *d = &t->dispatch[c];
            const Rule *r = d->plain;
            if (!r && d->fast) r = fast_pick(t, d, lcode_at(in, i), rcode_at(in, i));
            if (r) {
                put_codes(oc, r);
                oc += r->nsucc;
                applied = true;
            } else {
                *oc++ = c;
            }
        }
        o->n = (size_t)(oc - o->code);
    }
    w->applied |= applied;
}

/* run_chunk_codes for a whole string in one thread when every context is one module without
 * parameters and pick tables exist: the left neighbour's class is followed while scanning
 * (a stack of the branch parents'), the right one's read from in->rclass, a byte a module.
 * No link pass and no link arrays for the left side, a quarter of the memory for the right.
 * The rule of each module is read from the plan (classes.h), and the right classes of the
 * output are written to w->rnext as it is written: the module whose right class is not
 * known yet on the current axis (*pend) gets the class of the next one written there, or
 * none at the ']' that ends the axis. */
static void run_chunk_classes(Work *w) {
    const RuleTable *t = w->t;
    const View *in = w->in;
    const ClassCode *plan = in->plan->code;
    const ClassSucc *succ = in->plan->succ;
    const uint8_t *rclass = in->rclass;
    const uint32_t none = in->plan->none, none_row = none * (uint32_t)t->nclass;
    uint8_t *stack = w->stack, *rn = NULL;
    uint32_t *pstack = w->pend, pend = 0; /* where the right class waited for goes (0: nowhere) */
    uint32_t left = none_row; /* the left neighbour's class, as its row in the pick tables */
    size_t sp = 0, psp = 0;
    SylString *o = w->out;
    uint32_t applied = 0;
    for (size_t lo = w->lo; lo < w->hi; lo += BATCH) {
        size_t hi = w->hi - lo < BATCH ? w->hi : lo + BATCH;
        size_t room = (hi - lo) * (size_t)t->max_succ + SUCC_PAD;
        if (make_room(w, lo, 0, room, 0)) return;
        const uint16_t *code = in_code(w);
        uint16_t *oc = o->code + o->n;
        if (1 + o->n + room > *w->cap_rnext && !ms_scratch_grow(w->rnext, w->cap_rnext, 1 + o->n + room, 1 + o->n, 1)) {
            over_limit(w, lo, SYL_ELIMIT);
            return;
        }
        uint8_t *ro = (rn = *w->rnext) + 1 + o->n;
        for (size_t i = lo; i < hi; i++) {
            uint16_t c = code[i];
            ClassCode k = plan[c];
            uint32_t a = k.act; /* the left link of match_link_left, one module on */
            const ClassSucc *e = succ; /* a module no rule rewrites (base 0) is not looked up */
            const Rule *r = NULL;
            if (k.base) r = (e = &succ[k.base + (k.mask & (left + rclass[i]))])->rule;
            if (r) {
                memcpy(oc, e->code, sizeof e->code);
                if (e->n > SUCC_PAD) put_codes(oc, r);
                memcpy(ro, e->rt, sizeof e->rt);
                if (e->has_base) {
                    rn[pend] = e->first;
                    pend = (uint32_t)(ro - rn) + e->last;
                }
                oc += e->n;
                ro += e->n;
                applied = 1;
                if (a < ACT_SKIP) left = k.row;
                else if (a == ACT_OPEN) stack[sp++] = (uint8_t)left;
                else if (a == ACT_CLOSE) left = sp ? stack[--sp] : none_row;
                continue;
            }
            *oc++ = c; /* it stays: its own link and the output's are the same */
            if (a == ACT_SKIP) { /* ignored (most often, as F in model c): nothing to follow */
            } else if (a < ACT_SKIP) {
                left = k.row;
                rn[pend] = (uint8_t)a;
                pend = (uint32_t)(ro - rn);
            } else if (a == ACT_OPEN) {
                stack[sp++] = (uint8_t)left;
                pstack[psp++] = pend;
                pend = 0;
            } else if (a == ACT_CLOSE) {
                left = sp ? stack[--sp] : none_row;
                rn[pend] = (uint8_t)none;
                pend = psp ? pstack[--psp] : 0;
            }
            ro++;
        }
        o->n = (size_t)(oc - o->code);
    }
    if (rn) /* the axes the string ends */
        for (rn[pend] = (uint8_t)none; psp;) rn[pstack[--psp]] = (uint8_t)none;
    w->applied |= applied != 0;
}

static void run_chunk(Work *w) {
    const RuleTable *t = w->t;
    const View *in = w->in;
    SylString *o = w->out;
    size_t pi = w->plo;
    double locals[MAX_LOCALS + MAX_ARITY];
    const uint64_t pass = rng_pass(w->seed, w->key); /* the modules' streams: rng_at(pass, ...) */
    w->fault.status = SYL_OK;
    for (size_t lo = w->lo; lo < w->hi; lo += BATCH) {
        size_t hi = w->hi - lo < BATCH ? w->hi : lo + BATCH;
        size_t room = (hi - lo) * (size_t)t->max_succ + SUCC_PAD;
        size_t proom = (hi - lo) * ((size_t)t->max_succ_params + MAX_ARITY);
        if (make_room(w, lo, pi, room, proom)) return;
        const uint16_t *code = in_code(w);
        const double *par = in_par(w);
        /* write cursors; o->n and o->np are brought up to date before anything reads them */
        uint16_t *oc = o->code + o->n;
        double *op = o->par + o->np;
#define SYNC() (o->n = (size_t)(oc - o->code), o->np = (size_t)(op - o->par))
#define RELOAD() (oc = o->code + o->n, op = o->par + o->np)
        for (size_t i = lo; i < hi; i++) {
            uint16_t c = code[i];
            const double *args = par + pi;
            int ar = CODE_ARITY(c);
            pi += (size_t)ar;
            const Dispatch *d = &t->dispatch[c];
            const Rule *r = d->plain;
            const double *x = args;
            if (!r) {
                if (d->fast) r = fast_pick(t, d, lcode_at(in, i), rcode_at(in, i));
                else if (d->choice) { /* constant weights: pick's draw without the weighing */
                    const Choice *ch = d->choice;
                    Rng rng = rng_at(pass, (uint64_t)w->table, i);
                    if (ch->total > 0) {
                        /* pick's loop without its branches: u only falls (weights >= 0), so
                         * the rules it steps over are the partial differences still >= 0 */
                        double u = rng_unit(&rng) * ch->total;
                        int k = 0;
                        for (int j = 0; j < ch->n - 1; j++) {
                            u -= ch->weight[j];
                            k += u >= 0;
                        }
                        if (ch->zero)
                            while (ch->weight[k] == 0) k--; /* u landed exactly on a boundary before a zero */
                        r = ch->rule[k];
                    }
                    if (r && !(r->vm_free && put_slots(op, r, args))) {
                        SYNC(); /* the VM goes on with the module's stream, as after pick */
                        bool rng_ready = true;
                        if (emit(w, r, args, i, &rng, &rng_ready)) return;
                        RELOAD();
                        continue;
                    }
                    if (r) {
                        put_codes(oc, r);
                        oc += r->nsucc;
                        op += r->nslots;
                        w->applied = true;
                        continue;
                    }
                } else if (d->count) { /* conditions, weights or longer contexts */
                    memcpy(locals, args, sizeof(double) * (size_t)ar);
                    int status;
                    SYNC();
                    Rng rng;
                    bool rng_ready = false;
                    r = choose(w, d, i, locals, &rng, &rng_ready, &status);
                    if (status) return;
                    if (r && emit(w, r, locals, i, &rng, &rng_ready)) return;
                    RELOAD();
                    if (r) continue;
                }
                if (!r) { /* no rule applies: the module stays */
                    *oc++ = c;
                    for (int k = 0; k < ar; k++) *op++ = args[k]; /* mostly 0 or 1: no call to memcpy */
                    continue;
                }
            }
            if (r->vm_free && put_slots(op, r, x)) {
                put_codes(oc, r);
                oc += r->nsucc;
                op += r->nslots;
                w->applied = true;
                continue;
            }
            SYNC(); /* the VM, or a value to report */
            Rng rng;
            bool rng_ready = false;
            if (emit(w, r, x, i, &rng, &rng_ready)) return;
            RELOAD();
        }
        SYNC();
#undef SYNC
#undef RELOAD
    }
}

/* Tables of plain rules only (the common parametric case): the loop of run_chunk without
 * contexts or choices, small enough for every cursor to stay in a register. */
static void run_chunk_plain(Work *w) {
    const RuleTable *t = w->t;
    const uint8_t *stay = t->stay;
    /* how far the input may be read: short runs are copied in fixed sizes, which may read
     * and write past them (the output has room, the writer stays SUCC_PAD codes and
     * MAX_ARITY parameters behind the reader) */
    const size_t n_end = w->inplace ? w->n_in : w->in->n;
    const size_t np_end = w->inplace ? w->np_in : w->np_all;
    SylString *o = w->out;
    size_t pi = w->plo;
    bool applied = false;
    w->fault.status = SYL_OK;
    for (size_t lo = w->lo; lo < w->hi; lo += BATCH) {
        size_t hi = w->hi - lo < BATCH ? w->hi : lo + BATCH;
        size_t room = (hi - lo) * (size_t)t->max_succ + SUCC_PAD;
        size_t proom = (hi - lo) * ((size_t)t->max_succ_params + MAX_ARITY);
        if (make_room(w, lo, pi, room, proom)) break;
        const uint16_t *code = in_code(w);
        const double *par = in_par(w), *args = par + pi;
        uint16_t *oc = o->code + o->n;
        double *op = o->par + o->np;
        for (size_t i = lo; i < hi; i++) {
            uint16_t c = code[i];
            int ar = CODE_ARITY(c);
            const Rule *r = t->dispatch[c].plain;
            if (!r && (i + 1 == hi || !stay[code[i + 1]])) { /* it stays alone */
                *oc++ = c;
                for (int k = 0; k < ar; k++) *op++ = args[k]; /* mostly 0 or 1: no call to memcpy */
            } else if (!r) {
                size_t j = i + 2, np = (size_t)ar + stay[code[i + 1]] - 1;
                for (unsigned st; j < hi && (st = stay[code[j]]); j++) np += st - 1;
                /* a run of modules that stay: its codes and its parameters copied in one go,
                 * short ones in fixed sizes, long ones moved (in place the writer may be
                 * closer behind the reader than the run is long) */
                if (j - i <= 8 && i + 8 <= n_end) memcpy(oc, code + i, 8 * sizeof *oc);
                else memmove(oc, code + i, (j - i) * sizeof *oc);
                if (np <= 4 && (size_t)(args - par) + 4 <= np_end) memcpy(op, args, 4 * sizeof *op);
                else memmove(op, args, np * sizeof *op);
                oc += j - i;
                op += np;
                args += np;
                i = j - 1;
                continue;
            } else if (r->vm_free && put_slots(op, r, args)) {
                put_codes(oc, r);
                oc += r->nsucc;
                op += r->nslots;
                applied = true;
            } else { /* the VM, or a value to report */
                o->n = (size_t)(oc - o->code);
                o->np = (size_t)(op - o->par);
                Rng rng;
                bool rng_ready = false;
                if (emit(w, r, args, i, &rng, &rng_ready)) return;
                oc = o->code + o->n;
                op = o->par + o->np;
            }
            args += ar;
        }
        o->n = (size_t)(oc - o->code);
        o->np = (size_t)(op - o->par);
        pi = (size_t)(args - par);
    }
    w->applied |= applied;
}

_Static_assert((int)REWRITE_SPILL_CODES >= (int)SUCC_PAD && REWRITE_SPILL_CODES >= 8, "put_codes and runs of 8");
_Static_assert((int)REWRITE_SPILL_PARAMS >= (int)SLOT_PLAN && REWRITE_SPILL_PARAMS >= 4, "put_slots and runs of 4");

void rewrite_size(Work *w) {
    const RuleTable *t = w->t;
    const uint16_t *code = w->in->code;
    const Dispatch *dispatch = t->dispatch;
    size_t n = 0, np = 0, pin = 0;
    for (size_t i = w->lo; i < w->hi; i++) {
        uint16_t c = code[i];
        const Rule *r = dispatch[c].plain;
        n += r ? (size_t)r->nsucc : 1;
        np += r ? (size_t)r->nslots : (size_t)CODE_ARITY(c);
        pin += (size_t)CODE_ARITY(c);
    }
    w->n_out = n, w->np_out = np;
    /* the tail: back from hi until its output covers the spill (codes only: no parameters) */
    size_t tn = 0, tp = 0, i = w->hi, pneed = w->codes_only ? 0 : REWRITE_SPILL_PARAMS;
    while (i > w->lo && (tn < REWRITE_SPILL_CODES || tp < pneed)) {
        uint16_t c = code[--i];
        const Rule *r = dispatch[c].plain;
        tn += r ? (size_t)r->nsucc : 1;
        tp += r ? (size_t)r->nslots : (size_t)CODE_ARITY(c);
        pin -= (size_t)CODE_ARITY(c);
    }
    w->cut = i;
    w->pcut = w->plo + pin;
}

void rewrite_chunk(Work *w) {
    if (w->codes_only) w->stack ? run_chunk_classes(w) : run_chunk_codes(w);
    else if (w->t->all_plain) run_chunk_plain(w);
    else run_chunk(w);
}

int rewrite_emit(Work *w, const Rule *r, const double *locals, size_t pos, Rng *rng, bool *rng_ready) {
    return emit(w, r, locals, pos, rng, rng_ready);
}
