/* The directives of a `grow` block: params.def is their table, sch_grow its rows, and the
 * schema's keyed reader (lang/schema_keyed.c) reads the lines and --set with it, as every
 * kind's are read. What is grow's own is here: where each value is stored in GrowParams,
 * what a mode sets besides itself (whorled 3: three buds a node), and the checks across
 * directives once all are read. docs/growth.md is the user's side of the table. */
#include "sot/params.h"
#include "sot/reader.h"
#include "sot/shoot_rule.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "lang/program.h"
#include "lang/schema.h"
#include "sylva/grow.h"
#include "sylva/lod.h"
#include "sylva/skeleton.h"

_Static_assert(MAX_ORGANS == 8, "params.def's organ row says at most 8 organ lines");

/* Where each row of params.def is stored (its order is sch_grow's). */
#define AT_NUM SCH_AT_F32
#define AT_INT SCH_AT_INT
#define AT_SEED SCH_AT_U64
#define AT_BOOL SCH_AT_BOOL
#define AT_VEC3 SCH_AT_F32X3
#define AT_WORD SCH_AT_U8
#define AT_NAME SCH_AT_TEXT
#define OFF_G(f) offsetof(GrowParams, f), sizeof((GrowParams *)0)->f
#define OFF_O(f) offsetof(OrganSpec, f), sizeof((OrganSpec *)0)->f
#define OFF_N(f) 0, 0
#define MODE_AT_G SCH_AT_INT /* a mode of GrowParams is an int, of an organ line a byte */
#define MODE_AT_O SCH_AT_U8
#define MODE_AT_N SCH_AT_NONE
#define UNPAREN(...) __VA_ARGS__
#define GROW_MODES(base, f, dir, dw, w, values, grp, mean, ...) static const int f##_values[] = {UNPAREN values};
#include "sot/params.def"
static const SchSlot grow_slots[] = {
#define GROW_VALUE(nm, ty, l, h, f, d, u, mean) {AT_##ty, OFF_G(f), NULL},
#define GROW_KEY(base, f, dir, wh, nm, ty, l, h, d, w, u, mean) {AT_##ty, OFF_##base(f), NULL},
#define GROW_MODES(base, f, dir, dw, w, values, grp, mean, ...) {MODE_AT_##base, OFF_##base(f), f##_values},
#include "sot/params.def"
};

/* What a mode sets besides itself: buds per node and their usual divergence; shed off. */
static void mode_read(void *base, const SchRow *row, int word, int count) {
    GrowParams *g = base;
    if (!strcmp(row->name, "buds")) {
        int m = phyllotaxis_values[word];
        g->laterals = m == PHYL_ALTERNATE ? 1 : m == PHYL_OPPOSITE ? 2 : count;
        g->divergence = m == PHYL_ALTERNATE ? 137.5f : m == PHYL_OPPOSITE ? 90.0f : 180.0f / (float)count;
    }
    if (!strcmp(row->name, "shed")) g->shed_threshold = 0, g->bare_trunk = 0;
}

static const SchKeyed grow_keyed = {
    .t = &sch_grow,
    .slots = grow_slots,
    .nslots = (int)(sizeof grow_slots / sizeof *grow_slots),
    .groups = (const SchGroup[]){{"organ", offsetof(GrowParams, organs), sizeof(OrganSpec), offsetof(GrowParams, norgans)}},
    .ngroups = 1,
    .mode_read = mode_read,
};

void grow_params_default(GrowParams *g) {
    memset(g, 0, sizeof *g);
    sch_keyed_defaults(&grow_keyed, g);
    g->laterals = 1; /* buds alternate */
    g->sun[1] = 1;
}

/* The shoot rule's model compiles, is an lsystem and rewrites `shoot`. */
static void check_rule(Reader *r, const SylDirective *dirs, int n, GrowParams *g) {
    int line = 0, col = 0;
    for (int i = 0; i < n; i++)
        if (!strcmp(dirs[i].name, "shoot"))
            for (int j = 0; j < dirs[i].nargs; j++)
                if (dirs[i].args[j].kind == SYL_DARG_WORD && !strcmp(dirs[i].args[j].text, g->rule))
                    line = dirs[i].args[j].line, col = dirs[i].args[j].col;
    int status = 0;
    SylProgram *q = syl_compile_model(r->p, g->rule, NULL, &status);
    const char *why = shoot_rule_check(q);
    size_t len = 0;
    const char *text = syl_program_source(r->p, &len);
    const char *names[256];
    char buf[8192];
    int nm = q ? 0 : syl_model_list(syl_program_path(r->p), text, len, names, 256, buf, sizeof buf);
    bool exists = false;
    for (int i = 0; i < nm; i++) exists |= !strcmp(names[i], g->rule);
    if (!q && !exists) ERR(r, line, col, "the shoot rule '%s' is not a model of this file", g->rule);
    else if (!q) ERR(r, line, col, "the shoot rule '%s' does not compile (see `sylva check %s:%s`)", g->rule,
                     syl_program_path(r->p), g->rule);
    else if (why) ERR(r, line, col, "the shoot rule '%s' %s", g->rule, why);
    syl_program_free(q);
}

/* Checks across directives, once all are read. */
static void check_whole(Reader *r, const SylDirective *dirs, int n, GrowParams *g) {
    if (g->space != SPACEM_OFF && g->perception <= g->occupancy) {
        int line = 0, col = 0;
        for (int i = 0; i < n; i++)
            if (!strcmp(dirs[i].name, "space")) line = dirs[i].line, col = dirs[i].col;
        ERR(r, line, col, "'space': perception (%g) must reach beyond occupancy (%g)", g->perception, g->occupancy);
    }
    if (g->alloc == ALLOC_PRIORITY && g->wmin > g->wmax) {
        int line = 0, col = 0;
        for (int i = 0; i < n; i++)
            if (!strcmp(dirs[i].name, "allocate")) line = dirs[i].line, col = dirs[i].col;
        ERR(r, line, col, "'allocate priority': wmin (%g) must not exceed wmax (%g)", g->wmin, g->wmax);
    }
    float s = sqrtf(g->sun[0] * g->sun[0] + g->sun[1] * g->sun[1] + g->sun[2] * g->sun[2]);
    if (!(s > 0) || g->sun[1] <= 0) {
        int line = 0, col = 0;
        for (int i = 0; i < n; i++)
            if (!strcmp(dirs[i].name, "light")) line = dirs[i].line, col = dirs[i].col;
        ERR(r, line, col, "'light': the sun must be above the horizon (y > 0)");
    } else
        for (int k = 0; k < 3; k++) g->sun[k] /= s;
    const double deg = 3.14159265358979323846 / 180;
    g->tropism_sin = (float)sin(g->tropism_angle * deg);
    g->tropism_cos = (float)cos(g->tropism_angle * deg);
    g->jitter_cos = g->jitter > 0 ? (float)cos(g->jitter * deg) : 1;
    g->branch_sin = (float)sin(g->branch_angle * deg);
    g->branch_cos = (float)cos(g->branch_angle * deg);
    if (g->voxel <= 0) g->voxel = g->internode;
    if (g->foliage <= 0) g->foliage = 0.4f * g->internode;
    if (g->rule[0]) check_rule(r, dirs, n, g);
}

static int read_all(const SylProgram *p, GrowParams *g, FILE *diag, int *set_errors) {
    grow_params_default(g);
    g->from = p;
    g->seed = syl_program_seed(p) ? syl_program_seed(p) : 1;
    sch_count_read(p);
    int errors = sch_read_keyed(p, &grow_keyed, g, diag, set_errors);
    Reader r = {.p = p, .diag = diag, .errors = errors};
    int n = 0;
    const SylDirective *dirs = syl_program_directives(p, &n);
    check_whole(&r, dirs, n, g);
    return r.errors;
}

int grow_params_read(const SylProgram *p, GrowParams *g, FILE *diag) {
    if (sch_kept(p, g, sizeof *g)) return 0;
    int set_errors;
    return read_all(p, g, diag, &set_errors);
}

/* What is statically sure to grow nothing: no year (shoots need light and room, which only
 * growing tells). */
static void warn_grows_nothing(const SylProgram *p, const GrowParams *g, FILE *diag) {
    if (g->years) return;
    int n = 0, line = 0, col = 0;
    const SylDirective *dirs = syl_program_directives(p, &n);
    for (int i = 0; i < n; i++)
        if (!strcmp(dirs[i].name, "years")) line = dirs[i].line, col = dirs[i].col;
    const char *set = "";
    for (int i = 0; i < p->noverrides; i++)
        if (p->set_local[i] && !strcmp(p->set_local[i], "years")) line = col = 0, set = " by --set";
    program_warning(p, diag, line, col, "grow block '%s' grows nothing: years is 0%s (the tree is its root)",
                    syl_program_name(p), set);
}

int sot_check_grow(const SylProgram *p, FILE *diag) {
    GrowParams g;
    int set_errors, errors = read_all(p, &g, diag, &set_errors);
    if (!errors) warn_grows_nothing(p, &g, diag);
    if (!errors) sch_keep(p, &g, sizeof g); /* the growth takes it: read once */
    return errors && errors == set_errors ? -errors : errors; /* only the command line's */
}
