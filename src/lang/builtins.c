/* Built-in functions of the expression language (lang/builtins.h), and the opcodes' names. */
#include "lang/builtins.h"

#include <math.h>
#include <string.h>

#include "lang/opcodes.h"

const char *const syl_op_names[OP__COUNT] = {
#define SYL_OP_NAME(name, kind, effect) #name,
    SYL_OPCODES(SYL_OP_NAME)
#undef SYL_OP_NAME
};
const char syl_op_kinds[OP__COUNT] = {
#define SYL_OP_KIND(name, kind, effect) #kind[0],
    SYL_OPCODES(SYL_OP_KIND)
#undef SYL_OP_KIND
};

#define BUILTINS(X)                                                                 \
    X(sin, 1, 0) X(cos, 1, 0) X(tan, 1, 0) X(asin, 1, 0) X(acos, 1, 0) X(atan, 1, 0) \
    X(atan2, 2, 0) X(rad, 1, 0) X(deg, 1, 0) X(sqrt, 1, 0) X(exp, 1, 0) X(log, 1, 0) \
    X(log10, 1, 0) X(pow, 2, 0) X(abs, 1, 0) X(fabs, 1, 0) X(floor, 1, 0)            \
    X(ceil, 1, 0) X(round, 1, 0) X(trunc, 1, 0) X(sign, 1, 0) X(min, 2, 0)          \
    X(max, 2, 0) X(clamp, 3, 0) X(uniform, 2, 1) X(normal, 2, 1) X(ran, 1, 1)       \
    X(nran, 2, 1)

enum {
#define B_ENUM(n, a, r) B_##n,
    BUILTINS(B_ENUM)
#undef B_ENUM
};

const signed char syl_op_effects[OP__COUNT] = {
#define SYL_OP_EFFECT(name, kind, effect) effect,
    SYL_OPCODES(SYL_OP_EFFECT)
#undef SYL_OP_EFFECT
};

const Builtin syl_builtins[] = {
#define B_ROW(n, a, r) {#n, a, r},
    BUILTINS(B_ROW)
#undef B_ROW
};
const int syl_builtin_count = sizeof syl_builtins / sizeof *syl_builtins;

int syl_builtin_find(const char *name) {
    for (int i = 0; i < syl_builtin_count; i++)
        if (!strcmp(syl_builtins[i].name, name)) return i;
    return -1;
}

const char *syl_eval_error_text(int status) {
    switch (status) {
    case EVAL_DIV_ZERO: return "division by zero";
    case EVAL_DOMAIN: return "argument out of the function's domain";
    case EVAL_NONFINITE: return "the result is not a finite number";
    case EVAL_DEPTH: return "functions call each other too deeply";
    case EVAL_NEG_WEIGHT: return "a rule's weight is negative";
    case EVAL_EXTERN: return "the function bound to this extern failed";
    case EVAL_UNBOUND: return "this extern function has no default and nothing is bound to it (bind one from "
                              "Python, derive(functions=...), or give it one: extern f(x) = ...)";
    default: return "ok";
    }
}

static const double DEG = 57.29577951308232, RAD = 0.017453292519943295;

int syl_builtin_apply(int id, const double *a, Rng *rng, double *out) {
    double r;
    switch (id) {
    case B_sin: r = sin(a[0] * RAD); break;
    case B_cos: r = cos(a[0] * RAD); break;
    case B_tan: r = tan(a[0] * RAD); break;
    case B_asin:
        if (a[0] < -1 || a[0] > 1) return EVAL_DOMAIN;
        r = asin(a[0]) * DEG;
        break;
    case B_acos:
        if (a[0] < -1 || a[0] > 1) return EVAL_DOMAIN;
        r = acos(a[0]) * DEG;
        break;
    case B_atan: r = atan(a[0]) * DEG; break;
    case B_atan2: r = atan2(a[0], a[1]) * DEG; break;
    case B_rad: r = a[0] * RAD; break;
    case B_deg: r = a[0] * DEG; break;
    case B_sqrt:
        if (a[0] < 0) return EVAL_DOMAIN;
        r = sqrt(a[0]);
        break;
    case B_exp: r = exp(a[0]); break;
    case B_log:
    case B_log10:
        if (a[0] <= 0) return EVAL_DOMAIN;
        r = id == B_log ? log(a[0]) : log10(a[0]);
        break;
    case B_pow:
        if ((a[0] < 0 && a[1] != floor(a[1])) || (a[0] == 0 && a[1] < 0)) return EVAL_DOMAIN;
        r = pow(a[0], a[1]);
        break;
    case B_abs:
    case B_fabs: r = fabs(a[0]); break;
    case B_floor: r = floor(a[0]); break;
    case B_ceil: r = ceil(a[0]); break;
    case B_round: r = round(a[0]); break;
    case B_trunc: r = trunc(a[0]); break;
    case B_sign: r = (a[0] > 0) - (a[0] < 0); break;
    case B_min: r = a[0] < a[1] ? a[0] : a[1]; break;
    case B_max: r = a[0] > a[1] ? a[0] : a[1]; break;
    case B_clamp: r = a[0] < a[1] ? a[1] : a[0] > a[2] ? a[2] : a[0]; break;
    case B_uniform: r = a[0] + (a[1] - a[0]) * rng_unit(rng); break;
    case B_normal: r = a[0] + a[1] * rng_normal(rng); break;
    case B_ran: r = a[0] * rng_unit(rng); break;
    case B_nran: r = a[0] + a[1] * rng_normal(rng); break;
    default: return EVAL_DOMAIN;
    }
    if (!isfinite(r)) return EVAL_NONFINITE;
    *out = r;
    return EVAL_OK;
}

int syl_power(double a, double b, double *out) {
    double args[2] = {a, b};
    return syl_builtin_apply(B_pow, args, NULL, out);
}
