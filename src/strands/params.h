/* The parameters of a `strands` block (Holton 1994 as in Zamuda 2006, docs/strands.md): the
 * global ones, and the per-order ones as the product of a function of the Gravelius order g
 * and one of the Weibull order w (Zamuda eqs. 3.17-3.22), each a number or a `curve`. */
#ifndef STRANDS_PARAMS_H
#define STRANDS_PARAMS_H
#include <stdint.h>
#include <stdio.h>

#include "lang/program.h"

/* One factor: a curve sampled at the (integer) order, or a constant. */
typedef struct StrandsFactor {
    const Curve *curve; /* NULL: k */
    double k;
} StrandsFactor;

/* A per-order parameter: clamp(f_g(g) * f_w(w), lo, hi). */
typedef struct StrandsOrderParam {
    StrandsFactor g, w;
    double lo, hi;
} StrandsOrderParam;

enum {
    SP_SPLIT,          /* k_s   (3.17) */
    SP_ANGLE,          /* alpha (3.18), degrees */
    SP_GRAVIMORPHISM,  /* alpha_m (3.19), degrees */
    SP_LENGTH_MAX,     /* M     (3.20) */
    SP_LENGTH_MIN,     /* m     (3.21) */
    SP_LENGTH_SCALE,   /* k_l   (3.22) */
    SP_LAT_LENGTH_MAX, /* Holton's M_minor: the lateral's own bounds and scale (default: the above) */
    SP_LAT_LENGTH_MIN,
    SP_LAT_LENGTH_SCALE,
    SP_ORDER_COUNT
};

typedef enum { LEAVES_NONE, LEAVES_STACKED, LEAVES_STAGGERED, LEAVES_SPIRAL, LEAVES_BUNCHED, LEAVES_CONIFEROUS } LeafType;

typedef struct StrandsParams {
    int64_t strands;      /* S */
    double trunk_length;  /* l_0^{0,0} */
    double thickness;     /* k_d: d = k_d sqrt(S_0) */
    double gravicentral;  /* k_c: scales alpha_1 at Gravelius order 0 */
    double phyllotaxis;   /* alpha_p, degrees */
    StrandsOrderParam order[SP_ORDER_COUNT];
    LeafType leaf_type;
    double leaf_density;  /* rho_l: leaves per terminal branch */
    double leaf_size;     /* l_l */
    uint64_t seed;        /* turns the whole tree about its trunk */
} StrandsParams;

/* Read and check a strands block's directives; returns the number of errors (each reported
 * on diag with file:line:col and a caret). P holds the defaults where a directive is absent. */
int strands_params_read(const SylProgram *p, StrandsParams *P, FILE *diag);

/* The same for `sylva check`: the error count, negative when every error was of --set. */
int strands_params_check(const SylProgram *p, FILE *diag);
/* Every directive name and its thesis symbol (for tests of the docs); returns the count. */
int strands_param_names(const char **names, const char **symbols, int max);

/* The value of a per-order parameter at Gravelius order g and Weibull order w. */
static inline double strands_factor(const StrandsFactor *f, int order) {
    return f->curve ? curve_eval(f->curve, (double)order) : f->k;
}
static inline double strands_order_value(const StrandsOrderParam *o, int g, int w) {
    double v = strands_factor(&o->g, g) * strands_factor(&o->w, w);
    return v < o->lo ? o->lo : v > o->hi ? o->hi : v;
}

#endif
