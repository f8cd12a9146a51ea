/* Built-in functions of the expression language, shared by the compiler (for folding)
 * and the VM (for running). Trigonometry works in degrees, as in cpfg. */
#ifndef SYL_BUILTINS_H
#define SYL_BUILTINS_H
#include "util/rng.h"

typedef struct Builtin {
    const char *name;
    int nargs;
    int random; /* draws from the module's random stream: never folded */
} Builtin;

extern const Builtin syl_builtins[];
extern const int syl_builtin_count;

int syl_builtin_find(const char *name); /* -1 if none */

/* Status of an evaluation; names for messages in syl_eval_error_text. */
enum {
    EVAL_OK,
    EVAL_DIV_ZERO,
    EVAL_DOMAIN,
    EVAL_NONFINITE,
    EVAL_DEPTH,
    EVAL_NEG_WEIGHT,
    EVAL_EXTERN,  /* the function bound to an extern failed */
    EVAL_UNBOUND, /* an extern without a default body, and nothing bound to it */
};
const char *syl_eval_error_text(int status);

/* Apply builtin id to args; random builtins draw from rng (may be NULL when folding). */
int syl_builtin_apply(int id, const double *args, Rng *rng, double *out);

/* The `^` operator: pow with its domain checked. */
int syl_power(double a, double b, double *out);

#endif
