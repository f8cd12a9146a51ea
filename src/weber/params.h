/* The parameters of a `weber` block (Weber & Penn 1995 with Arbaro's additions): one table,
 * params.def, gives every name, type, range, default and meaning; the block's directives
 * are read into WeberParams against it. */
#ifndef WEBER_PARAMS_H
#define WEBER_PARAMS_H
#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "lang/schema.h"
#include "sylva/sylva.h"

enum { WP_NUM = SCH_NUMBER, WP_INT = SCH_INTEGER, WP_LEAFSHAPE = SCH_ENUM }; /* params.def's types */
enum { WEBER_ARBARO, WEBER_PAPER }; /* convention: shapes 0 and 5, AttractionUp, split angle */
enum { WEBER_LEAF_DISC, WEBER_LEAF_SQUARE, WEBER_LEAF_SPHERE, WEBER_LEAF_PALM };

typedef struct WeberParams {
#define WP_G(f, ...) double f;
#define WP_L(f, ...) double f[4];
#include "params.def"
#undef WP_G
#undef WP_L
    int leaf_kind;       /* WEBER_LEAF_*, from LeafShape */
    int leaf_tris;       /* triangles a face: disc1..disc9 the oval's; disc 6; square 2; palm 6 */
    int convention;      /* WEBER_ARBARO (default) or WEBER_PAPER */
    bool has_seed;
    uint64_t seed;       /* `Seed N`; Arbaro's command line default is 13 */
    const char *envelope;            /* `envelope "crown.obj"`: a closed mesh to prune to (NULL: none) */
    const SylDirective *envelope_at; /* where it was named, for errors */
    int lod;             /* `lod N`: the levels of detail `sylva mesh` writes (Sylva's; 0: none) */
} WeberParams;

typedef struct WeberParamInfo {
    const char *name;   /* Arbaro's name; a per-level one without its digit */
    bool per_level;
    int type;           /* WP_* */
    double lo, hi;
    bool lo_open, hi_open;
    double def[4];      /* a global's default is def[0] */
    size_t offset;      /* of the double (global) or double[4] (per level) in WeberParams */
    const char *meaning;
} WeberParamInfo;

extern const WeberParamInfo weber_param_table[];
extern const int weber_param_count;

/* Level n's row of a per-level parameter: levels above 3 reuse level 3. */
static inline int weber_lv(int level) { return level > 3 ? 3 : level < 0 ? 0 : level; }

/* Arbaro's defaults. */
void weber_params_default(WeberParams *w);
/* Defaults, then the block's directives; every bad name or value is reported to diag
 * (file:line:col, the line and a caret) through syl_directive_report_error. Returns the error count. */
int weber_params_read(const SylProgram *p, WeberParams *out, FILE *diag);
/* The same for `sylva check`: the error count, negative when every error was of --set. */
int weber_params_check(const SylProgram *p, FILE *diag);

#endif
