/* Module strings in struct-of-arrays form: one 16-bit code per module (symbol and
 * parameter count), and the parameters of all modules, in order, in one array. */
#ifndef SYL_MODSTR_H
#define SYL_MODSTR_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lang/program.h"
#include "sylva/sylva.h"

#include "util/budget.h"

struct SylString {
    uint16_t *code;
    double *par;
    size_t n, cap;   /* modules */
    size_t np, pcap; /* parameters */
    uint32_t *poff;  /* parameter offset per module (n + 1), built on demand */
    /* POFF_*: readers of a const string may build poff from several threads at once, so one
     * builds it while the others wait (syl_string_module takes a const string) */
    _Atomic int poff_state;
    size_t poff_n, poff_cap; /* the n it was built for; its room */
    uint64_t charged; /* bytes counted against mem */
    Budget *mem;      /* the memory budget (--max-memory) its arrays count against; NULL: none */
    uint64_t max_modules; /* of the derivation writing it (0: none) */
};

/* Make room for n more modules and np more parameters. Returns SYL_OK or SYL_ELIMIT. */
int ms_reserve(SylString *s, size_t n, size_t np);
/* Rewriting in place (derive.c): move the string's modules back by at least `room` slots and
 * its parameters by at least `proom`, growing the arrays; *at and *pat say where they start
 * now (whole pages are moved rather than copied when the arrays are big). The caller then
 * writes the next string from slot 0 while it reads this one. donor (or NULL), a string no
 * longer needed, is emptied: its pages go where the next string will be written, when they
 * fit (pages_grow_front), so that they are not first touched again. */
int ms_move_back(SylString *s, size_t n, size_t np, size_t room, size_t proom, size_t *at, size_t *pat,
                 SylString *donor);
/* Move the code slots [from, from + len) and the parameter slots [pfrom, pfrom + plen) up by
 * extra and pextra, growing the arrays: more room between a writer in place and its reader. */
int ms_move_tail(SylString *s, size_t from, size_t len, size_t extra, size_t pfrom, size_t plen, size_t pextra);
enum { POFF_STALE, POFF_BUILDING, POFF_READY };
/* Offsets of every module's parameters, built once per string contents (NULL if out of
 * memory). Safe to call from several threads on one string nobody changes. */
const uint32_t *ms_offsets(const SylString *s);
/* Whoever changes modules or parameters says so (the offsets are then rebuilt). */
static inline void ms_changed(SylString *s) { atomic_store_explicit(&s->poff_state, POFF_STALE, memory_order_relaxed); }
void ms_release(SylString *s); /* free the arrays, keep the struct */
/* The engine's scratch arrays (context links), kept between steps in the same storage as
 * strings: array_reserve's contract, except that the contents are not kept when they grow. */
bool ms_scratch_reserve(void *arrp, size_t *cap, size_t need, size_t elem);
bool ms_scratch_grow(void *arrp, size_t *cap, size_t need, size_t used, size_t elem); /* keeps `used` */
void ms_scratch_free(void *arr, size_t cap, size_t elem);

#endif
