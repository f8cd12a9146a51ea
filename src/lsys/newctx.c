/* The pass of a table with new contexts (`<<`, `>>`): modules are rewritten one after
 * another, each rule's new context matched in the string written so far, whose context
 * links grow with it exactly as match_link_left / match_link_right would build them. */
#include <stdlib.h>
#include <string.h>

#include "lang/builtins.h"
#include "lsys/newctx.h"
#include "sylva/sylva.h"
#include "util/pages.h"

/* Forward: the output modules some `<<` pattern names, in the order written, each with the
 * entry of the module before it on its path (-1: none, or one no pattern names, where every
 * match fails). A match walks these few entries, not the output. */
typedef struct Entry {
    int32_t link;
    uint16_t code;
    uint32_t poff; /* its parameters in the output */
} Entry;

/* What a pass keeps of the string it writes. Backward, in the positions of the buffer it
 * fills from the end: position `at`, just before the output, is where the next successor
 * goes, and its link is the module a new right context starts from. */
typedef struct Links {
    Entry *ent;      /* forward */
    size_t nent, entcap;
    int32_t *link;   /* backward: the next module along the axis (-1: none) */
    uint16_t *code;  /* that module's code (CODE_NONE: none) */
    int32_t *pair;   /* for a '[' the index of its ']' */
    uint32_t *poff;  /* parameter offset of each module */
    size_t cap;
    /* the bracket stack: forward, the path entry at each open '['; backward, the next
     * module at each ']' entered from its end, and where that ']' is */
    int32_t *sidx, *sclose;
    uint16_t *scode;
    size_t sp, scap;
} Links;

/* Room is made for this many modules' successors at once. */
enum { BATCH = 64 };

/* What a successor does to the links the pass keeps, made once a pass for each rule used, so
 * that the entries of a successor are not found module by module. A successor whose brackets
 * balance changes the links only through its modules outside its branches (nothing after it
 * looks into a branch it closed), and of those a match reads at most the longest new context's
 * length, up to a module no pattern names. Forward these are its last such modules, backward
 * its first ones. */
enum { PLAN_MAX = 8 };
typedef struct Plan {
    uint32_t stamp;          /* the pass it was made in (0: none) */
    bool walk;               /* brackets that do not balance, or longer contexts: module by module */
    bool cut;                /* a module no pattern names (or one beyond the longest context)
                                stands between these entries and the links before the successor */
    uint8_t n;               /* entries it adds, in string order */
    uint16_t code[PLAN_MAX];
    uint32_t poff[PLAN_MAX]; /* parameter offset in the successor */
} Plan;

static void links_free(Links *l) {
    pages_free(l->ent, l->entcap * sizeof *l->ent);
    free(l->link);
    free(l->code);
    free(l->pair);
    free(l->poff);
    free(l->sidx);
    free(l->sclose);
    free(l->scode);
    memset(l, 0, sizeof *l);
}

/* The plan of rule r for a pass in direction `backward`: K is the longest new context. */
static void plan_make(Plan *pl, const Rule *r, bool backward, const bool *skip, const bool *want, int K) {
    *pl = (Plan){.walk = K > PLAN_MAX};
    int depth = 0, n = 0;
    uint32_t off = 0;
    for (int j = 0; j < r->nsucc && !pl->walk; off += CODE_ARITY(r->succ[j]), j++) {
        uint16_t c = r->succ[j];
        int s = CODE_SYM(c);
        if (s == SYM_OPEN) depth++;
        else if (s == SYM_CLOSE) pl->walk = depth-- == 0;
        else if (depth || skip[s] || (backward && (pl->cut || n == K))) continue;
        else if (!want[c]) { /* forward, what came before is cut off; backward, what follows */
            pl->cut = true;
            n = backward ? n : 0;
        } else {
            if (n == K) { /* forward: the oldest can no longer be reached */
                memmove(pl->code, pl->code + 1, (size_t)(K - 1) * sizeof *pl->code);
                memmove(pl->poff, pl->poff + 1, (size_t)(K - 1) * sizeof *pl->poff);
                n--;
                pl->cut = true;
            }
            pl->code[n] = c;
            pl->poff[n++] = off;
            if (backward && n == K) pl->cut = true; /* backward: nothing after is read */
        }
    }
    pl->walk |= depth != 0;
    pl->n = (uint8_t)n;
}

static bool entries_room(Links *l, size_t need) {
    if (need <= l->entcap) return true;
    size_t cap = l->entcap ? 2 * l->entcap : 1024;
    while (cap < need) cap *= 2;
    /* in whole 2 MB pages: a step of a big string writes millions of entries */
    Entry *e = pages_grow(l->ent, l->entcap * sizeof *e, l->nent * sizeof *e, cap * sizeof *e);
    if (!e) return false;
    l->ent = e;
    l->entcap = cap;
    return true;
}

/* Room for cap positions (contents kept). */
static bool links_room(Links *l, size_t cap) {
    if (cap <= l->cap) return true;
    int32_t *a = realloc(l->link, cap * sizeof *a);
    if (a) l->link = a;
    uint16_t *b = a ? realloc(l->code, cap * sizeof *b) : NULL;
    if (b) l->code = b;
    int32_t *c = b ? realloc(l->pair, cap * sizeof *c) : NULL;
    if (c) l->pair = c;
    uint32_t *d = c ? realloc(l->poff, cap * sizeof *d) : NULL;
    if (d) l->poff = d;
    if (!d) return false;
    l->cap = cap;
    return true;
}

static bool stack_grow(Links *l) {
    {
        size_t cap = l->scap ? 2 * l->scap : 256;
        int32_t *a = realloc(l->sidx, cap * sizeof *a);
        if (a) l->sidx = a;
        int32_t *b = a ? realloc(l->sclose, cap * sizeof *b) : NULL;
        if (b) l->sclose = b;
        uint16_t *c = b ? realloc(l->scode, cap * sizeof *c) : NULL;
        if (c) l->scode = c;
        if (!c) return false;
        l->scap = cap;
    }
    return true;
}

static inline bool push(Links *l, int32_t idx, uint16_t code, int32_t close) {
    if (l->sp == l->scap && !stack_grow(l)) return false;
    l->sidx[l->sp] = idx;
    l->scode[l->sp] = code;
    l->sclose[l->sp++] = close;
    return true;
}

/* match_link_left one module on: output module c (parameters at poff) after the path whose
 * last entry is *last. False when the bracket stack cannot grow. */
static inline bool link_left(Links *l, uint16_t c, uint32_t poff, const bool *skip, const bool *want,
                             int32_t *last) {
    int s = CODE_SYM(c);
    if (s == SYM_OPEN) return push(l, *last, 0, 0);
    if (s == SYM_CLOSE) *last = l->sp ? l->sidx[--l->sp] : -1;
    else if (!skip[s] && want[c]) { /* a module no pattern names: every match fails there */
        l->ent[l->nent] = (Entry){.link = *last, .code = c, .poff = poff};
        *last = (int32_t)l->nent++;
    } else if (!skip[s]) *last = -1;
    return true;
}

/* The same backward (match_link_right): module c put in front of the axis whose first entry
 * is *next; poff counts back from the end of the parameters. */
static inline bool link_right(Links *l, uint16_t c, uint32_t poff, const bool *skip, const bool *want,
                              int32_t *next) {
    int s = CODE_SYM(c);
    if (s == SYM_CLOSE) {
        if (!push(l, *next, 0, 0)) return false;
        *next = -1;
    } else if (s == SYM_OPEN) *next = l->sp ? l->sidx[--l->sp] : -1;
    else if (!skip[s] && want[c]) {
        l->ent[l->nent] = (Entry){.link = *next, .code = c, .poff = poff};
        *next = (int32_t)l->nent++;
    } else if (!skip[s]) *next = -1;
    return true;
}

static int fault(Work *w, size_t pos, const Rule *r, int status, int limit) {
    w->fault.status = status;
    w->fault.limit = limit;
    w->fault.pos = pos;
    w->fault.rule = r;
    return status;
}

static void copy_module(SylString *o, uint16_t c, const double *args) {
    int ar = CODE_ARITY(c);
    o->code[o->n++] = c;
    for (int k = 0; k < ar; k++) o->par[o->np + (size_t)k] = args[k];
    o->np += (size_t)ar;
}

/* Where the successor of the module being rewritten goes. Forward: the entry of the output's
 * last path module (cursor) and the output's parameters; backward: the view of the new string
 * to the right and the free position just before it. */
typedef struct Here {
    const Entry *ent;
    int32_t cursor;
    const double *par;
    size_t pend;     /* backward entries: poff counts back from here (the buffer moves) */
    const View *nv;  /* backward, when a `>>` context names a branch: the links of every module */
    size_t at;
} Here;

/* Inlined, like applies and choose below, into each pass, whose direction is then a constant. */
#define HOT static inline __attribute__((always_inline))

HOT bool match_new_left(const Here *h, const PatElem *pat, int n, double *locals) {
    int32_t pos = h->cursor;
    for (int j = n - 1; j >= 0; j--) {
        if (pos < 0 || h->ent[pos].code != pat[j].code) return false;
        int ar = CODE_ARITY(pat[j].code);
        for (int k = 0; k < ar; k++) locals[pat[j].local + k] = h->par[h->ent[pos].poff + (uint32_t)k];
        pos = h->ent[pos].link;
    }
    return true;
}

/* Backward without branches in `>>` contexts: the entries of the axis that follows. */
HOT bool match_new_right(const Here *h, const PatElem *pat, int n, double *locals) {
    int32_t pos = h->cursor;
    for (int j = 0; j < n; j++) {
        if (pos < 0 || h->ent[pos].code != pat[j].code) return false;
        int ar = CODE_ARITY(pat[j].code);
        for (int k = 0; k < ar; k++) locals[pat[j].local + k] = h->par[h->pend - h->ent[pos].poff + (uint32_t)k];
        pos = h->ent[pos].link;
    }
    return true;
}

/* Whether rule r applies to input module i, its contexts' parameters bound in locals. A rule
 * with `<<` takes part only in forward passes, one with `>>` only in backward ones. */
HOT bool applies(const Work *w, const Rule *r, size_t i, const Here *h, bool backward, double *locals) {
    if (r->nnewleft && (backward || !match_new_left(h, r->newleft, r->nnewleft, locals))) return false;
    if (r->nnewright && (!backward || !(h->nv ? match_right_pat(h->nv, h->at, r->newright, r->nnewright,
                                                                  r->newright_branches, locals)
                                              : match_new_right(h, r->newright, r->nnewright, locals))))
        return false;
    if (r->nleft && !match_left(w->in, i, r, locals)) return false;
    if (r->nright && !match_right(w->in, i, r, locals)) return false;
    return true;
}

/* As rewrite.c's choice (rewrite_weigh, rewrite_pick), with the new contexts matched too. */
HOT const Rule *choose(Work *w, uint16_t c, size_t i, const Here *h, bool backward, double *locals, Rng *rng,
                       bool *rng_ready, int *status) {
    const RuleTable *t = w->t;
    const Dispatch *d = &t->dispatch[c];
    double total = 0;
    int nc = 0;
    *status = SYL_OK;
    if (d->count == 1) { /* one rule without condition or weight: its contexts decide */
        const Rule *r = &t->rules[t->order[d->first]];
        if (r->cond < 0 && !r->weighted) return applies(w, r, i, h, backward, locals) ? r : NULL;
    }
    for (uint32_t k = 0; k < d->count; k++) {
        const Rule *r = &t->rules[t->order[d->first + k]];
        if (nc && !r->weighted) continue;
        if (!applies(w, r, i, h, backward, locals)) continue;
        int v = rewrite_weigh(w, r, i, locals, rng, rng_ready, &nc, &total, status);
        if (v == WEIGH_TAKE) return r;
        if (v == WEIGH_FAULT) return NULL;
    }
    const Rule *r = rewrite_pick(w, nc, total, i, rng, rng_ready);
    if (r) applies(w, r, i, h, backward, locals); /* bind the chosen rule's contexts again */
    return r;
}

/* Input module i (parameters args), which has rules with contexts, conditions or weights:
 * the rule chosen emitted into o (w->out), in *used, or the module copied (*used NULL). SYL_OK
 * or the fault's status. */
HOT int rewrite_one(Work *w, size_t i, const double *args, const Here *h, bool backward, SylString *o,
                    const Rule **used) {
    uint16_t c = w->in->code[i];
    double locals[MAX_LOCALS + MAX_ARITY];
    Rng rng;
    bool ready = false;
    int status;
    if (CODE_ARITY(c)) memcpy(locals, args, sizeof(double) * CODE_ARITY(c));
    const Rule *r = choose(w, c, i, h, backward, locals, &rng, &ready, &status);
    if (status) return status;
    if (!(*used = r)) {
        copy_module(o, c, args);
        return SYL_OK;
    }
    return rewrite_emit(w, r, locals, i, &rng, &ready);
}

/* The plans of one pass: for each rule of the table, made when the pass first uses it. */
typedef struct Plans {
    Plan *plan;
    const Rule *rules;
    uint32_t stamp;
    const bool *skip, *want;
    int K;
    bool backward;
} Plans;

static inline const Plan *plan_of(const Plans *ps, const Rule *r) {
    Plan *pl = &ps->plan[r - ps->rules];
    if (pl->stamp != ps->stamp) {
        plan_make(pl, r, ps->backward, ps->skip, ps->want, ps->K);
        pl->stamp = ps->stamp;
    }
    return pl;
}

/* First module first: the output is w->out; the entries of its path grow as successors are
 * appended (match_link_left, one module at a time, kept only for the modules `<<` names). */
static void forward(Work *w, Links *lp, const Plans *ps) {
    const RuleTable *t = w->t;
    const View *in = w->in;
    const bool *skip = in->skip;
    SylString *o = w->out;
    Links l = *lp; /* a copy in registers, put back at the end */
    l.sp = l.nent = 0;
    static const bool none[CODE_COUNT]; /* a table with `>>` only: nothing to keep */
    const bool *want = t->newleft_code ? t->newleft_code : none;
    int32_t last = -1; /* the entry of the output's last path module */
    const size_t per = t->max_succ > 1 ? (size_t)t->max_succ : 1; /* codes a module may add: one stays */
    size_t pi = w->plo;
    w->fault.status = SYL_OK;
    for (size_t lo = w->lo; lo < w->hi; lo += BATCH) {
        /* room for a batch of successors (and as many entries) at once, not module by module */
        size_t hi = w->hi - lo < BATCH ? w->hi : lo + BATCH;
        size_t room = (hi - lo) * per + SUCC_PAD;
        size_t proom = (hi - lo) * ((size_t)t->max_succ_params + MAX_ARITY);
        if (o->n + room > o->cap || o->np + proom > o->pcap) {
            int st = ms_reserve(o, room + (w->hi - lo), proom);
            if (st || o->n > o->max_modules) {
                fault(w, lo, NULL, SYL_ELIMIT, st ? LIMIT_MEMORY : LIMIT_MODULES);
                break;
            }
        }
        if (l.nent + room > l.entcap && !entries_room(&l, l.nent + room)) {
            fault(w, lo, NULL, SYL_ELIMIT, LIMIT_MEMORY);
            break;
        }
        for (size_t i = lo; i < hi; i++) {
            uint16_t c = in->code[i];
            const double *args = in->par ? in->par + pi : NULL;
            pi += CODE_ARITY(c);
            size_t at = o->n;
            uint32_t pat = (uint32_t)o->np;
            const Dispatch *d = &t->dispatch[c];
            const Rule *r = d->plain;
            if (r) { /* no context, no choice */
                Rng rng;
                bool ready = false;
                if (rewrite_emit(w, r, args, i, &rng, &ready)) goto done;
            } else if (d->count) {
                Here h = {.ent = l.ent, .cursor = last, .par = o->par};
                if (rewrite_one(w, i, args, &h, false, o, &r)) goto done;
            }
            if (!r) { /* it stays */
                if (!d->count) copy_module(o, c, args);
                if (!link_left(&l, c, pat, skip, want, &last)) {
                    fault(w, i, NULL, SYL_ELIMIT, LIMIT_MEMORY);
                    goto done;
                }
                continue;
            }
            const Plan *pl = plan_of(ps, r);
            if (!pl->walk) {
                if (pl->cut) last = -1;
                for (int k = 0; k < pl->n; k++) {
                    l.ent[l.nent] = (Entry){.link = last, .code = pl->code[k], .poff = pat + pl->poff[k]};
                    last = (int32_t)l.nent++;
                }
                continue;
            }
            for (size_t j = at; j < o->n; pat += CODE_ARITY(o->code[j]), j++) /* one module at a time */
                if (!link_left(&l, o->code[j], pat, skip, want, &last)) {
                    fault(w, i, NULL, SYL_ELIMIT, LIMIT_MEMORY);
                    goto done;
                }
        }
    }
done:
    *lp = l;
}

/* The backward output, written into the output string's own arrays from their end: modules
 * in [h, cap) of code, parameters in [ph, pcap) of par, moved to the front once at the end
 * (a copy within memory already touched, where a separate buffer faulted in fresh pages). */
typedef struct Back {
    uint16_t *code;
    double *par;
    size_t cap, pcap, h, ph;
} Back;

/* Room for `need` more modules and `pneed` more parameters before the front (and the slot at
 * h - 1): out's arrays grow, the contents move to their new end and every index into them
 * with them. */
static bool back_room(Back *b, SylString *out, Links *l, bool walk, size_t need, size_t pneed, int32_t *next) {
    if (b->h < need + 1) {
        size_t used = b->cap - b->h, old = b->cap;
        out->n = old; /* all of it is kept while the arrays grow */
        int st = ms_reserve(out, old + need + 1, 0);
        out->n = 0;
        if (st) return false;
        size_t delta = out->cap - old, h = b->h + delta;
        memmove(out->code + h, out->code + b->h, used * sizeof *out->code);
        b->code = out->code;
        b->cap = out->cap;
        b->h = h;
        if (walk) {
            Links nl = *l;
            nl.link = nl.pair = NULL;
            nl.code = NULL;
            nl.poff = NULL;
            nl.cap = 0;
            if (!links_room(&nl, b->cap)) {
                free(nl.link), free(nl.code), free(nl.pair), free(nl.poff);
                return false;
            }
            memcpy(nl.code + h, l->code + (h - delta), used * sizeof *nl.code);
            memcpy(nl.poff + h, l->poff + (h - delta), used * sizeof *nl.poff);
            for (size_t j = 0; j < used; j++) {
                int32_t a = l->link[h - delta + j], p = l->pair[h - delta + j];
                nl.link[h + j] = a < 0 ? a : a + (int32_t)delta;
                nl.pair[h + j] = p < 0 ? p : p + (int32_t)delta;
            }
            for (size_t k = 0; k < l->sp; k++) {
                if (l->sidx[k] >= 0) l->sidx[k] += (int32_t)delta;
                l->sclose[k] += (int32_t)delta;
            }
            if (*next >= 0) *next += (int32_t)delta;
            free(l->link), free(l->code), free(l->pair), free(l->poff);
            l->link = nl.link, l->code = nl.code, l->pair = nl.pair, l->poff = nl.poff, l->cap = nl.cap;
        }
    }
    if (b->ph < pneed) {
        size_t used = b->pcap - b->ph, old = b->pcap;
        out->np = old;
        int st = ms_reserve(out, 0, old + pneed);
        out->np = 0;
        if (st) return false;
        size_t delta = out->pcap - old, ph = b->ph + delta;
        if (used) memmove(out->par + ph, out->par + b->ph, used * sizeof *out->par);
        if (walk)
            for (size_t j = b->h; j < b->cap; j++) l->poff[j] += (uint32_t)delta;
        b->par = out->par;
        b->pcap = out->pcap;
        b->ph = ph;
    }
    return true;
}

/* Last module first: each successor is written to a scratch string, then put in front of
 * the output (Back), whose right links (and bracket pairs) grow towards the front. */
static void backward(Work *w, Links *lp, SylString *tmpp, const Plans *ps) {
    const RuleTable *t = w->t;
    const View *in = w->in;
    SylString *out = w->out;
    const size_t need = (size_t)t->max_succ + SUCC_PAD, pneed = (size_t)t->max_succ_params + MAX_ARITY;
    Links l = *lp;
    SylString tmp = *tmpp;
    l.sp = 0;
    int32_t next = -1;
    uint16_t nextcode = CODE_NONE;
    w->fault.status = SYL_OK;
    size_t pi = w->plo + w->np_all; /* the end of the chunk's parameters (one chunk: all) */
    /* room for the output as rewrite_pass sized it from the last pass's growth (out->cap), so
     * that it is rarely moved, and at least for the input's size */
    size_t n_in = w->hi - w->lo, p_in = pi - w->plo;
    size_t cap = n_in + need + 1024, pcap = p_in + pneed + 1024;
    Back b = {0};
    if (!ms_reserve(out, cap, pcap))
        b = (Back){.code = out->code, .par = out->par, .cap = out->cap, .pcap = out->pcap};
    b.h = b.cap;
    b.ph = b.pcap;
    const bool walk = t->newright_branches; /* else entries, as forward */
    const size_t per = t->max_succ > 1 ? (size_t)t->max_succ : 1; /* codes a module may add: one stays */
    const bool *skip = in->skip;
    static const bool none[CODE_COUNT];
    const bool *want = t->newright_code ? t->newright_code : none;
    l.nent = 0;
    /* successors go to tmp after TMP_AT codes and TMP_PAT parameters, so that a short one is
     * put in front of the output by one copy of a fixed size ending where it ends (what it
     * copies before it lands in the free room) */
    enum { TMP_AT = SUCC_PAD, TMP_PAT = SLOT_PLAN };
    tmp.n = tmp.np = 0;
    if (!b.code || !b.par || (walk && !links_room(&l, b.cap)) || ms_reserve(&tmp, need + TMP_AT, pneed + TMP_PAT)) {
        fault(w, w->hi, NULL, SYL_ELIMIT, LIMIT_MEMORY);
        goto done;
    }
    memset(tmp.code, 0, TMP_AT * sizeof *tmp.code);
    memset(tmp.par, 0, TMP_PAT * sizeof *tmp.par);
    w->out = &tmp;
    Here here = {0};
    for (size_t hi = w->hi; hi > w->lo;) {
        /* room for a batch of successors (and as many entries) at once, not module by module */
        size_t lo = hi - w->lo > BATCH ? hi - BATCH : w->lo;
        size_t room = (hi - lo) * per + SUCC_PAD;
        size_t proom = (hi - lo) * ((size_t)t->max_succ_params + MAX_ARITY);
        if (((b.h < room + 1 || b.ph < proom) && !back_room(&b, out, &l, walk, room, proom, &next)) ||
            (!walk && l.nent + room > l.entcap && !entries_room(&l, l.nent + room))) {
            fault(w, hi - 1, NULL, SYL_ELIMIT, LIMIT_MEMORY);
            break;
        }
        for (size_t i = hi; i-- > lo;) {
            uint16_t c0 = in->code[i];
            pi -= CODE_ARITY(c0);
            const double *args = in->par ? in->par + pi : NULL;
            const Dispatch *d = &t->dispatch[c0];
            if (!walk && !d->plain && !d->count) { /* no rule for it: it stays, linked as below */
                size_t pn = CODE_ARITY(c0);
                b.code[--b.h] = c0;
                b.ph -= pn;
                for (size_t k = 0; k < pn; k++) b.par[b.ph + k] = args[k];
                if (!link_right(&l, c0, (uint32_t)(b.pcap - b.ph), skip, want, &next)) {
                    fault(w, i, NULL, SYL_ELIMIT, LIMIT_MEMORY);
                    goto done;
                }
                continue;
            }
            size_t at = b.h - 1;
            View nv; /* filled only when walking */
            here.ent = l.ent; /* fields, not a new struct: this loop runs once a module */
            here.cursor = next;
            here.par = b.par;
            here.pend = b.pcap;
            here.at = at;
            if (walk) {
                nv = (View){.code = b.code, .par = b.par, .poff = l.poff, .right = l.link, .rcode = l.code,
                            .pair = l.pair, .n = b.cap, .skip = in->skip};
                here.nv = &nv;
                l.link[at] = next;
                l.code[at] = nextcode;
            }
            size_t nn, pn; /* modules and parameters put in front of the output */
            const Rule *r = NULL;
            if (!d->plain && !d->count) { /* no rule for it: it stays, straight to the front */
                nn = 1;
                pn = CODE_ARITY(c0);
                b.code[--b.h] = c0;
                b.ph -= pn;
                for (size_t k = 0; k < pn; k++) b.par[b.ph + k] = args[k];
            } else {
                tmp.n = TMP_AT;
                tmp.np = TMP_PAT;
                if ((r = d->plain)) {
                    Rng rng;
                    bool ready = false;
                    if (rewrite_emit(w, r, args, i, &rng, &ready)) goto done;
                } else if (rewrite_one(w, i, args, &here, true, &tmp, &r)) goto done;
                nn = tmp.n - TMP_AT;
                pn = tmp.np - TMP_PAT;
                if (b.cap - b.h + nn > out->max_modules) {
                    fault(w, i, NULL, SYL_ELIMIT, LIMIT_MODULES);
                    goto done;
                }
                b.h -= nn;
                b.ph -= pn;
                if (nn <= TMP_AT) memcpy(b.code + b.h + nn - TMP_AT, tmp.code + nn, TMP_AT * sizeof *b.code);
                else memcpy(b.code + b.h, tmp.code + TMP_AT, nn * sizeof *b.code);
                if (pn <= TMP_PAT) memcpy(b.par + b.ph + pn - TMP_PAT, tmp.par + pn, TMP_PAT * sizeof *b.par);
                else memcpy(b.par + b.ph, tmp.par + TMP_PAT, pn * sizeof *b.par);
            }
            const Plan *pl = !walk && r ? plan_of(ps, r) : NULL;
            if (pl && !pl->walk) { /* its first modules on the axis, last first */
                if (pl->cut) next = -1;
                for (int k = pl->n; k-- > 0;) {
                    uint32_t poff = (uint32_t)(b.pcap - b.ph - pl->poff[k]);
                    l.ent[l.nent] = (Entry){.link = next, .code = pl->code[k], .poff = poff};
                    next = (int32_t)l.nent++;
                }
                continue;
            }
            if (!walk) { /* match_link_right over the new modules, kept for those `>>` names */
                size_t off = b.ph + pn;
                for (size_t j = b.h + nn; j-- > b.h;) {
                    off -= CODE_ARITY(b.code[j]);
                    if (!link_right(&l, b.code[j], (uint32_t)(b.pcap - off), skip, want, &next)) {
                        fault(w, i, NULL, SYL_ELIMIT, LIMIT_MEMORY);
                        goto done;
                    }
                }
                continue;
            }
            uint32_t off = (uint32_t)b.ph;
            for (size_t j = b.h; j < b.h + nn; j++) {
                l.poff[j] = off;
                off += CODE_ARITY(b.code[j]);
            }
            for (size_t j = b.h + nn; j-- > b.h;) { /* match_link_right, one module at a time */
                uint16_t c = b.code[j];
                int s = CODE_SYM(c);
                l.link[j] = next;
                l.code[j] = nextcode;
                l.pair[j] = -1;
                if (s == SYM_CLOSE) { /* entering a branch from its end */
                    if (!push(&l, next, nextcode, (int32_t)j)) {
                        fault(w, i, NULL, SYL_ELIMIT, LIMIT_MEMORY);
                        goto done;
                    }
                    next = -1;
                    nextcode = CODE_NONE;
                } else if (s == SYM_OPEN) {
                    if (l.sp) {
                        l.sp--;
                        next = l.sidx[l.sp];
                        nextcode = l.scode[l.sp];
                        l.pair[j] = l.sclose[l.sp];
                    } else { /* never in a balanced string: a walk past it ends the string */
                        next = -1;
                        nextcode = CODE_NONE;
                        l.pair[j] = (int32_t)b.cap - 1;
                    }
                } else if (!in->skip[s]) {
                    next = (int32_t)j;
                    nextcode = c;
                }
            }
        }
        hi = lo;
    }
    if (!w->fault.status) {
        out->n = b.cap - b.h;
        out->np = b.pcap - b.ph;
        memmove(out->code, out->code + b.h, out->n * sizeof *out->code);
        if (out->np) memmove(out->par, out->par + b.ph, out->np * sizeof *out->par);
    }
done:
    w->out = out;
    *lp = l;
    *tmpp = tmp;
}

/* What passes keep for the next: allocated once, not page-faulted in again every step. */
struct NewctxScratch {
    Links links;
    SylString tmp;
    Plan *plans;      /* one per rule of the pass's table */
    size_t nplans;
    uint32_t stamp;   /* the pass: plans made in an earlier one are made again */
    Budget *mem;      /* --max-memory: what the arrays hold is charged after each pass */
    uint64_t charged;
};

static uint64_t scratch_bytes(const struct NewctxScratch *s) {
    const Links *l = &s->links;
    return l->entcap * sizeof *l->ent +
           l->cap * (sizeof *l->link + sizeof *l->code + sizeof *l->pair + sizeof *l->poff) +
           l->scap * (sizeof *l->sidx + sizeof *l->sclose + sizeof *l->scode) + s->nplans * sizeof *s->plans;
}

void newctx_chunk(Work *w, bool backward_step, struct NewctxScratch **scratch) {
    if (!*scratch && !(*scratch = calloc(1, sizeof **scratch))) {
        fault(w, w->lo, NULL, SYL_ELIMIT, LIMIT_MEMORY);
        return;
    }
    struct NewctxScratch *s = *scratch;
    s->mem = w->out->mem;
    /* a table of the active groups keeps the rules' indices in the model's table (all): the
     * plans are indexed by those, and the longest context is the longest of all */
    const RuleTable *t = w->t, *all = &w->p->tables[w->table];
    if ((size_t)all->nrules > s->nplans) {
        Plan *p = realloc(s->plans, (size_t)all->nrules * sizeof *p);
        if (!p) {
            fault(w, w->lo, NULL, SYL_ELIMIT, LIMIT_MEMORY);
            return;
        }
        memset(p + s->nplans, 0, ((size_t)all->nrules - s->nplans) * sizeof *p);
        s->plans = p;
        s->nplans = (size_t)all->nrules;
    }
    if (++s->stamp == 0) { /* after 2^32 passes: every plan made again */
        memset(s->plans, 0, s->nplans * sizeof *s->plans);
        s->stamp = 1;
    }
    static const bool none[CODE_COUNT];
    const bool *want = backward_step ? t->newright_code : t->newleft_code;
    Plans ps = {.plan = s->plans, .rules = t->rules, .stamp = s->stamp, .skip = w->in->skip,
                .want = want ? want : none, .backward = backward_step};
    for (int k = 0; k < all->nrules; k++) {
        int n = backward_step ? all->rules[k].nnewright : all->rules[k].nnewleft;
        if (n > ps.K) ps.K = n;
    }
    if (ps.K < 1) ps.K = 1; /* no such context: nothing is wanted, every plan cuts or keeps */
    if (backward_step) backward(w, &s->links, &s->tmp, &ps);
    else forward(w, &s->links, &ps);
    uint64_t now = scratch_bytes(s);
    if (!budget_resize(s->mem, s->charged, now)) {
        if (!w->fault.status) fault(w, w->hi, NULL, SYL_ELIMIT, LIMIT_MEMORY);
        return; /* the next pass or newctx_release releases what is charged */
    }
    s->charged = now;
}

void newctx_release(struct NewctxScratch **scratch) {
    struct NewctxScratch *s = *scratch;
    if (!s) return;
    budget_release(s->mem, s->charged);
    links_free(&s->links);
    ms_release(&s->tmp);
    free(s->plans);
    free(s);
    *scratch = NULL;
}
