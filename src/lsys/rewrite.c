/* Rewriting one chunk of a string: each module's rule chosen (contexts, conditions, weights)
 * and its successor emitted, every random draw from the module's own stream. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lang/builtins.h"
#include "lsys/rewrite.h"
#include "sylva/sylva.h"

static inline void copy_module(Work *w, uint16_t c, const double *args) {
    SylString *o = w->out;
    int ar = CODE_ARITY(c);
    o->code[o->n++] = c;
    double *dst = o->par + o->np;
    for (int k = 0; k < ar; k++) dst[k] = args[k]; /* mostly 0 or 1: no call to memcpy */
    o->np += (size_t)ar;
}

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

static inline int emit(Work *w, const Rule *r, const double *locals, size_t pos, Rng *rng, bool *rng_ready) {
    SylString *o = w->out;
    put_codes(o->code + o->n, r);
    o->n += (size_t)r->nsucc;
    double *dst = o->par + o->np;
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
        if (r->cond >= 0 || r->weight >= 0) {
            if (!*rng_ready) {
                *rng = rng_stream(w->seed, w->key, (uint64_t)w->table, i);
                *rng_ready = true;
            }
        }
        if (r->cond >= 0) {
            double v;
            if (vm_run(w->p, (uint32_t)r->cond, locals, rng, &v, &w->fault.vm)) {
                *status = fail(w, i, r, EVAL_OK);
                return NULL;
            }
            if (v == 0) continue;
        }
        if (!r->weighted) return r;
        double wt = r->const_weight;
        if (r->weight >= 0 && vm_run(w->p, (uint32_t)r->weight, locals, rng, &wt, &w->fault.vm)) {
            *status = fail(w, i, r, EVAL_OK);
            return NULL;
        }
        if (wt < 0) {
            w->fault.vm.pc = (uint32_t)r->weight;
            *status = fail(w, i, r, EVAL_NEG_WEIGHT);
            return NULL;
        }
        if (nc == w->ncap) { /* grows once per chunk at most a few times */
            int cap = w->ncap ? 2 * w->ncap : 16;
            const Rule **c = realloc(w->cand, sizeof *c * (size_t)cap);
            double *wt2 = c ? realloc(w->weight, sizeof *wt2 * (size_t)cap) : NULL;
            if (c) w->cand = c;
            if (!c || !wt2) {
                w->fault.status = SYL_ELIMIT;
                w->fault.limit = LIMIT_MEMORY;
                w->fault.pos = i;
                *status = SYL_ELIMIT;
                return NULL;
            }
            w->weight = wt2;
            w->ncap = cap;
        }
        w->cand[nc] = r;
        w->weight[nc++] = wt;
        total += wt;
    }
    if (!nc || total <= 0) return NULL;
    if (!*rng_ready) {
        *rng = rng_stream(w->seed, w->key, (uint64_t)w->table, i);
        *rng_ready = true;
    }
    double u = rng_unit(rng) * total;
    int pick = 0;
    while (pick < nc - 1 && (u -= w->weight[pick]) >= 0) pick++;
    while (w->weight[pick] == 0) pick--; /* u landed exactly on a boundary before a zero */
    const Rule *r = w->cand[pick];
    /* the contexts bound last may be another candidate's: bind the chosen rule's again */
    if (r->nleft) match_left(in, i, r, locals);
    if (r->nright) match_right(in, i, r, locals);
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

/* Strings without parameters under rules that make none: codes only, no checks per slot. */
static void run_chunk_codes(Work *w) {
    const RuleTable *t = w->t;
    const uint16_t *code = w->in->code;
    SylString *o = w->out;
    const size_t need = (size_t)t->max_succ + SUCC_PAD;
    size_t n = o->n;
    for (size_t i = w->lo; i < w->hi; i++) {
        if (n + need > o->cap) {
            o->n = n;
            if (over_limit(w, i, ms_reserve(o, need + (w->hi - i), 0))) return;
        }
        uint16_t c = code[i];
        const Rule *r = t->dispatch[c].plain;
        if (r) {
            put_codes(o->code + n, r);
            n += (size_t)r->nsucc;
            w->applied = true;
        } else {
            o->code[n++] = c;
        }
    }
    o->n = n;
}

static void run_chunk(Work *w) {
    const RuleTable *t = w->t;
    const View *in = w->in;
    SylString *o = w->out;
    const uint16_t *code = in->code;
    size_t pi = w->plo; /* an index, not a pointer: a string without parameters has none */
    const size_t need = (size_t)t->max_succ + SUCC_PAD;
    const size_t pneed = (size_t)t->max_succ_params + MAX_ARITY;
    double locals[MAX_LOCALS + MAX_ARITY];
    w->fault.status = SYL_OK;
    for (size_t i = w->lo; i < w->hi; i++) {
        uint16_t c = code[i];
        const double *args = in->par ? in->par + pi : NULL;
        pi += CODE_ARITY(c);
        if (o->n + need > o->cap || o->np + pneed > o->pcap) {
            if (over_limit(w, i, ms_reserve(o, need + (w->hi - i), pneed))) return;
        }
        const Dispatch *d = &t->dispatch[c];
        Rng rng;
        bool rng_ready = false;
        if (d->plain) {
            if (emit(w, d->plain, args, i, &rng, &rng_ready)) return;
            continue;
        }
        if (!d->count) {
            copy_module(w, c, args);
            continue;
        }
        if (d->fast) { /* neighbours' codes against each rule's, in order */
            uint16_t lc = in->lcode ? in->lcode[i] : CODE_NONE, rc = in->rcode ? in->rcode[i] : CODE_NONE;
            const FastRule *f = d->fast, *end = f + d->count;
            while (f < end && !((f->left == CODE_ANY || f->left == lc) && (f->right == CODE_ANY || f->right == rc)))
                f++;
            if (f == end) copy_module(w, c, args);
            else if (emit(w, f->rule, args, i, &rng, &rng_ready)) return;
            continue;
        }
        memcpy(locals, args, sizeof(double) * CODE_ARITY(c));
        int status;
        const Rule *r = choose(w, d, i, locals, &rng, &rng_ready, &status);
        if (status) return;
        if (!r) copy_module(w, c, args);
        else if (emit(w, r, locals, i, &rng, &rng_ready)) return;
    }
}

void rewrite_chunk(Work *w) { w->codes_only ? run_chunk_codes(w) : run_chunk(w); }

int rewrite_emit(Work *w, const Rule *r, const double *locals, size_t pos, Rng *rng, bool *rng_ready) {
    return emit(w, r, locals, pos, rng, rng_ready);
}
