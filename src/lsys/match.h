/* Branch-aware context matching (ABOP §1.8): a left context looks back along the path to
 * the root, a right context looks forward along the axis and into branches it names. */
#ifndef SYL_MATCH_H
#define SYL_MATCH_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "../lang/program.h"

/* What the matcher reads: the string, its bracket pairs and parameter offsets. */
typedef struct View {
    const uint16_t *code;
    const double *par;
    const uint32_t *poff; /* NULL when no module has parameters */
    const int32_t *pair;  /* for '[' the index of its ']' and the other way round */
    size_t n;
    const bool *skip;     /* symbols ignored in contexts */
} View;

/* Match rule r's contexts around module i, binding their parameters into locals. */
bool match_left(const View *v, size_t i, const Rule *r, double *locals);
bool match_right(const View *v, size_t i, const Rule *r, double *locals);

/* Fill pair[] for a string whose brackets balance; returns false if they do not. */
bool match_pairs(const uint16_t *code, size_t n, int32_t *pair);

#endif
