/* Module strings: storage, the public accessors, canonical printing and counting. */
#include "lsys/modstr.h"

#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sylva/sylva.h"
#include "util/pages.h"

/* Strings are written once per step into fresh memory, and page faults dominated filling
 * them (on a virtual machine a 4 KB fault costs microseconds): their arrays live in whole
 * 2 MB pages (util/pages.c). */
bool ms_scratch_grow(void *arrp, size_t *cap, size_t need, size_t used, size_t elem) {
    void **arr = arrp;
    if (need <= *cap) return true;
    if (!elem || need > PTRDIFF_MAX / elem / 2) return false;
    size_t c = *cap ? *cap : 1024;
    while (c < need) c *= 2;
    void *p = pages_grow(*arr, *cap * elem, used * elem, c * elem);
    if (!p) return false;
    *arr = p;
    *cap = c;
    return true;
}

bool ms_scratch_reserve(void *arrp, size_t *cap, size_t need, size_t elem) {
    return ms_scratch_grow(arrp, cap, need, 0, elem);
}

void ms_scratch_free(void *arr, size_t cap, size_t elem) { pages_free(arr, cap * elem); }

static int charge(SylString *s, int64_t delta) {
    if (!s->mem) return SYL_OK;
    if (delta >= 0 ? !budget_charge(s->mem, (uint64_t)delta) : (budget_release(s->mem, (uint64_t)-delta), false))
        return SYL_ELIMIT;
    s->charged += (uint64_t)delta;
    return SYL_OK;
}

int ms_reserve(SylString *s, size_t n, size_t np) {
    if (s->np + np >= UINT32_MAX) return SYL_ELIMIT; /* offsets are 32-bit */
    if (s->n + n > s->cap) {
        size_t cap = s->cap + s->cap / 2 + 1024;
        if (cap < s->n + n) cap = s->n + n;
        if (charge(s, (int64_t)((cap - s->cap) * sizeof *s->code))) return SYL_ELIMIT;
        uint16_t *c = pages_grow(s->code, s->cap * sizeof *c, s->n * sizeof *c, cap * sizeof *c);
        if (!c) return SYL_ELIMIT;
        s->code = c;
        s->cap = cap;
    }
    if (s->np + np > s->pcap) {
        size_t cap = s->pcap + s->pcap / 2 + 256;
        if (cap < s->np + np) cap = s->np + np;
        if (charge(s, (int64_t)((cap - s->pcap) * sizeof *s->par))) return SYL_ELIMIT;
        double *p = pages_grow(s->par, s->pcap * sizeof *p, s->np * sizeof *p, cap * sizeof *p);
        if (!p) return SYL_ELIMIT;
        s->par = p;
        s->pcap = cap;
    }
    return SYL_OK;
}

/* One array of a string moved: its first `used` elements to `shift`, its capacity to `cap`;
 * the donor's array of the same kind (*darr of dcap elements) given to it (pages_grow_front). */
static int move_array(SylString *s, void **arr, size_t *cap, size_t elem, size_t used, size_t shift, size_t newcap,
                      void **darr, size_t *dcap) {
    if (newcap < *cap) newcap = *cap;
    if (charge(s, (int64_t)((newcap - *cap) * elem))) return SYL_ELIMIT;
    void *p = pages_grow_front(*arr, *cap * elem, used * elem, shift * elem, newcap * elem, *darr, *dcap * elem);
    if (!p) {
        charge(s, -(int64_t)((newcap - *cap) * elem));
        return SYL_ELIMIT;
    }
    *arr = p;
    *cap = newcap;
    *darr = NULL, *dcap = 0;
    return SYL_OK;
}

/* The shift, at least `room` elements, that moves whole pages of an array of `bytes`. */
static size_t page_shift(size_t room, size_t elem, size_t bytes) {
    size_t unit = pages_shift_unit(bytes);
    size_t b = (room * elem + unit - 1) / unit * unit;
    return (b + elem - 1) / elem;
}

int ms_move_back(SylString *s, size_t n, size_t np, size_t room, size_t proom, size_t *at, size_t *pat,
                 SylString *donor) {
    SylString none = {0};
    if (!donor) donor = &none;
    int st = np + proom >= UINT32_MAX ? SYL_ELIMIT : SYL_OK; /* offsets are 32-bit */
    size_t sh = page_shift(room, sizeof *s->code, (room + n) * sizeof *s->code);
    size_t psh = page_shift(proom, sizeof *s->par, (proom + np) * sizeof *s->par);
    if (!st) st = move_array(s, (void **)&s->code, &s->cap, sizeof *s->code, n, sh, sh + n, (void **)&donor->code, &donor->cap);
    if (!st) st = move_array(s, (void **)&s->par, &s->pcap, sizeof *s->par, np, psh, psh + np, (void **)&donor->par, &donor->pcap);
    if (donor != &none) ms_release(donor); /* what it has left, and its charge */
    if (st) return st;
    *at = sh;
    *pat = psh;
    ms_changed(s);
    return SYL_OK;
}

int ms_move_tail(SylString *s, size_t from, size_t len, size_t extra, size_t pfrom, size_t plen, size_t pextra) {
    if (pfrom + plen + pextra >= UINT32_MAX) return SYL_ELIMIT;
    if (from + len + extra > s->cap) {
        size_t cap = from + len + extra;
        if (charge(s, (int64_t)((cap - s->cap) * sizeof *s->code))) return SYL_ELIMIT;
        uint16_t *c = pages_grow(s->code, s->cap * sizeof *c, (from + len) * sizeof *c, cap * sizeof *c);
        if (!c) return charge(s, -(int64_t)((cap - s->cap) * sizeof *s->code)), SYL_ELIMIT;
        s->code = c;
        s->cap = cap;
    }
    if (pfrom + plen + pextra > s->pcap) {
        size_t cap = pfrom + plen + pextra;
        if (charge(s, (int64_t)((cap - s->pcap) * sizeof *s->par))) return SYL_ELIMIT;
        double *p = pages_grow(s->par, s->pcap * sizeof *p, (pfrom + plen) * sizeof *p, cap * sizeof *p);
        if (!p) return charge(s, -(int64_t)((cap - s->pcap) * sizeof *s->par)), SYL_ELIMIT;
        s->par = p;
        s->pcap = cap;
    }
    memmove(s->code + from + extra, s->code + from, len * sizeof *s->code);
    if (plen) memmove(s->par + pfrom + pextra, s->par + pfrom, plen * sizeof *s->par);
    return SYL_OK;
}

const uint32_t *ms_offsets(const SylString *cs) {
    /* The cache is not part of the string's value: building it is a const operation made
     * safe between threads by poff_state (stale -> building -> ready). */
    SylString *s = (SylString *)cs;
    for (;;) {
        int st = atomic_load_explicit(&s->poff_state, memory_order_acquire);
        if (st == POFF_READY && s->poff_n == s->n) return s->poff;
        if (st == POFF_BUILDING) { /* another reader is building it: short, wait */
            sched_yield();
            continue;
        }
        if (atomic_compare_exchange_weak_explicit(&s->poff_state, &st, POFF_BUILDING, memory_order_acquire,
                                                  memory_order_relaxed))
            break;
    }
    if (s->n + 1 > s->poff_cap) {
        uint32_t *o = NULL;
        if (!charge(s, (int64_t)((s->n + 1 - s->poff_cap) * sizeof *s->poff))) {
            o = pages_grow(s->poff, s->poff_cap * sizeof *o, 0, (s->n + 1) * sizeof *o); /* rebuilt below */
            if (!o) charge(s, -(int64_t)((s->n + 1 - s->poff_cap) * sizeof *s->poff));
        }
        if (!o) {
            atomic_store_explicit(&s->poff_state, POFF_STALE, memory_order_release);
            return NULL;
        }
        s->poff = o;
        s->poff_cap = s->n + 1;
    }
    uint32_t *o = s->poff;
    uint32_t at = 0;
    for (size_t i = 0; i < s->n; i++) {
        o[i] = at;
        at += CODE_ARITY(s->code[i]);
    }
    o[s->n] = at;
    s->poff_n = s->n;
    atomic_store_explicit(&s->poff_state, POFF_READY, memory_order_release);
    return o;
}

void ms_release(SylString *s) {
    budget_release(s->mem, s->charged);
    s->charged = 0;
    pages_free(s->code, s->cap * sizeof *s->code);
    pages_free(s->par, s->pcap * sizeof *s->par);
    pages_free(s->poff, s->poff_cap * sizeof *s->poff);
    s->code = NULL;
    s->par = NULL;
    s->poff = NULL;
    s->n = s->cap = s->np = s->pcap = s->poff_cap = 0;
    ms_changed(s);
}

/* ---- public access ---- */

size_t syl_string_length(const SylString *s) { return s->n; }

double *syl_string_params(SylString *s, size_t *n) {
    if (n) *n = s->np;
    return s->np ? s->par : NULL;
}

int syl_string_module(const SylString *s, size_t i, int *nparams, const double **params) {
    if (i >= s->n) {
        if (nparams) *nparams = 0;
        if (params) *params = NULL;
        return -1;
    }
    if (nparams) *nparams = CODE_ARITY(s->code[i]);
    if (params) {
        const uint32_t *o = ms_offsets(s);
        *params = o ? s->par + o[i] : NULL;
    }
    return CODE_SYM(s->code[i]);
}

void syl_string_symbols(const SylString *s, int32_t *out) {
    for (size_t i = 0; i < s->n; i++) out[i] = CODE_SYM(s->code[i]);
}

_Static_assert((int)SYL_MAX_PARAMS == (int)MAX_ARITY, "the public bound on parameters is the code's");

void syl_string_arities(const SylString *s, int sym, uint64_t counts[SYL_MAX_PARAMS + 1]) {
    memset(counts, 0, sizeof *counts * (SYL_MAX_PARAMS + 1));
    for (size_t i = 0; i < s->n; i++)
        if (CODE_SYM(s->code[i]) == sym) counts[CODE_ARITY(s->code[i])]++;
}

/* Walks the parameters alongside the codes, so it needs no offsets table. */
size_t syl_string_gather(const SylString *s, int sym, int nparams, double *out) {
    size_t rows = 0;
    const double *par = s->par;
    for (size_t i = 0; i < s->n; i++) {
        uint16_t c = s->code[i];
        int arity = CODE_ARITY(c);
        if (CODE_SYM(c) == sym && arity == nparams) {
            if (out) memcpy(out + rows * (size_t)nparams, par, sizeof *par * (size_t)nparams);
            rows++;
        }
        par += arity;
    }
    return rows;
}

void syl_string_count(const SylString *s, uint64_t *counts) {
    for (size_t i = 0; i < s->n; i++) counts[CODE_SYM(s->code[i])]++;
}

SylString *syl_string_new(void) { return calloc(1, sizeof(SylString)); }

int syl_string_push(SylString *s, int sym, int nparams, const double *params) {
    if (sym < 0 || sym >= MAX_SYMBOLS || nparams < 0 || nparams > MAX_ARITY) return SYL_EUSAGE;
    if (ms_reserve(s, 1, (size_t)nparams)) return SYL_ELIMIT;
    s->code[s->n++] = CODE(sym, nparams);
    for (int k = 0; k < nparams; k++) s->par[s->np++] = params[k];
    ms_changed(s);
    return SYL_OK;
}

void syl_string_free(SylString *s) {
    if (!s) return;
    ms_release(s);
    free(s);
}

int syl_string_write(const SylProgram *p, const SylString *s, FILE *out) {
    const double *par = s->par;
    size_t nl[MAX_SYMBOLS];
    for (int i = 0; i < p->nsyms; i++) nl[i] = strlen(p->syms[i].name);
    char buf[1 << 16];
    size_t at = 0;
    for (size_t i = 0; i < s->n; i++) {
        uint16_t c = s->code[i];
        int sym = CODE_SYM(c), ar = CODE_ARITY(c);
        if (at > sizeof buf - 1024) {
            if (fwrite(buf, 1, at, out) != at) return SYL_EIO;
            at = 0;
        }
        if (nl[sym] < 256) {
            memcpy(buf + at, p->syms[sym].name, nl[sym]);
            at += nl[sym];
        }
        if (!ar) continue;
        buf[at++] = '(';
        for (int k = 0; k < ar; k++) {
            if (k) buf[at++] = ',';
            at += (size_t)snprintf(buf + at, 32, "%g", *par++);
            if (at > sizeof buf - 64) {
                if (fwrite(buf, 1, at, out) != at) return SYL_EIO;
                at = 0;
            }
        }
        buf[at++] = ')';
    }
    if (at && fwrite(buf, 1, at, out) != at) return SYL_EIO;
    return ferror(out) ? SYL_EIO : SYL_OK;
}
