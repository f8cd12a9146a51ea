/* Program: everything the compiler produces for one model. Immutable once built (but for the
 * functions its user binds to its `extern` declarations before deriving); the derivation
 * engine, the disassembler and the turtle read it. */
#ifndef SYL_PROGRAM_H
#define SYL_PROGRAM_H
#include <stdbool.h>
#include <stdint.h>

#include "util/arena.h"
#include "util/diag.h"
#include "lang/kinds.h"
#include "lang/turtle_commands.h"
#include "sylva/sylva.h"

/* A module code packs the symbol id (low 11 bits) and the parameter count (high 5 bits):
 * a rule for A(x) and one for A(x, y) are different entries of the dispatch table. */
enum { SYM_BITS = 11, MAX_SYMBOLS = 1 << SYM_BITS, MAX_ARITY = 31, CODE_COUNT = 1 << 16 };
#define CODE(sym, arity) ((uint16_t)((sym) | ((arity) << SYM_BITS)))
#define CODE_SYM(c) ((c) & (MAX_SYMBOLS - 1))
#define CODE_ARITY(c) ((c) >> SYM_BITS)

/* Symbols every program has, at fixed ids, because the engine treats them specially. */
enum { SYM_OPEN = 0, SYM_CLOSE = 1 };

enum { MAX_LOCALS = 255, VM_STACK = 64, SUCC_PAD = 16, SLOT_PLAN = 8 };

typedef struct Symbol {
    const char *name;
    int declared_arity; /* -1: not declared with a parameter list */
    bool declared;
    uint8_t turtle; /* its TurtleCommand (lang/turtle_commands.h), TC_NONE for others */
    SylLoc decl_loc;
} Symbol;

/* One element of a context pattern: a module to match (binding its parameters to locals
 * starting at `local`), or a bracket of a branch written in a right context. */
typedef enum { PAT_MODULE, PAT_OPEN, PAT_CLOSE } PatKind;
typedef struct PatElem {
    uint8_t kind;
    uint8_t local;
    uint16_t code;
    int32_t match; /* PAT_OPEN: index of its PAT_CLOSE */
} PatElem;

/* How a successor parameter gets its value: the common shapes `x`, `x * k`, `x / k`,
 * `x + k`, `x - k` skip the VM. */
typedef enum { SLOT_CONST, SLOT_LOCAL, SLOT_ADDK, SLOT_SUBK, SLOT_MULK, SLOT_DIVK, SLOT_CODE } SlotKind;
typedef struct Slot {
    uint8_t kind;
    uint8_t local;
    uint32_t pc;
    double k;
} Slot;

typedef struct Rule {
    uint16_t pred;            /* module code of the predecessor */
    uint8_t nlocals;          /* predecessor, then left, then right context parameters */
    uint8_t pred_arity;
    PatElem *left, *right;    /* left stored as written; matched from its end */
    int nleft, nright;
    bool right_branches;      /* its right context names a branch: matched by walking */
    /* new contexts (lpfg's `<<`, `>>`): matched in the string this step writes, so a rule
     * with `<<` applies only in forward steps and one with `>>` only in backward ones */
    PatElem *newleft, *newright;
    int nnewleft, nnewright;
    bool newright_branches;
    int32_t cond, weight;     /* code addresses, -1 when absent */
    double const_weight;      /* weight when it is a constant */
    bool weighted;
    uint16_t *succ;           /* module codes of the successor (padded: SUCC_PAD readable) */
    int nsucc;
    Slot *slots;              /* one per successor parameter, in order */
    int nslots;
    bool vm_free;             /* no slot runs the VM: emitted without a random stream */
    /* A vm_free rule of at most SLOT_PLAN slots is written as its template (the constants,
     * in one fixed-size copy), then its distinct arithmetic parameters, then its copied
     * ones and the repeats of an arithmetic one (`X(l/2)` twice divides once): no branch per
     * slot on its kind. A division by a power of two is a multiplication by its inverse,
     * which rounds the same. planned says it has a plan. */
    bool planned;
    uint8_t ncopy, narith, ndup;
    uint8_t copy_dst[SLOT_PLAN], copy_src[SLOT_PLAN], arith[SLOT_PLAN], dup_dst[SLOT_PLAN], dup_src[SLOT_PLAN];
    uint8_t arith_kind[SLOT_PLAN], arith_local[SLOT_PLAN];
    double arith_k[SLOT_PLAN];
    double tmpl[SLOT_PLAN];
    /* A plan whose copies and arithmetic all read one local, with at most one distinct
     * arithmetic value (`F(l)F(l)`, `A(s) -> F(s)[+(85)A(s/R)]…`), is blended: slot k's bits are
     * tmpl[k] | x & blend_x[k] | v & blend_v[k] (masks of all ones or none), two slots at a
     * time, x the local blend_local and v its one arithmetic value (arith[0]). */
    bool blend;
    uint8_t blend_local, blend_pairs;
    uint64_t blend_x[SLOT_PLAN], blend_v[SLOT_PLAN];
    SylLoc loc;               /* the predecessor */
    int line;
    int group;                /* index in SylProgram.groups, -1: outside any group */
    const char **names;       /* of the locals, for the disassembler */
} Rule;

/* A rule whose contexts are at most one module without parameters on each side, with no
 * condition and no weight: matched by comparing the neighbours' codes alone. */
#define CODE_ANY ((uint16_t)0xffff) /* no context on that side (symbol 2047 is never made) */
typedef struct FastRule {
    uint16_t left, right; /* codes, or CODE_ANY */
    const struct Rule *rule;
} FastRule;

/* A stochastic choice known before the string is read: the rules of one code, all without
 * contexts or conditions and weighted by constants (finite, >= 0), with the sum of their
 * weights in file order (finite). The draw among them is the general path's, operation for operation. */
typedef struct Choice {
    int n;
    bool zero; /* some weight is 0 */
    double total;
    const struct Rule *const *rule;
    const double *weight;
} Choice;

/* Per module code: which rules to try. A plain entry is one unconditional context-free
 * unweighted rule, emitted without any matching; fast entries are all FastRules. */
typedef struct Dispatch {
    const struct Rule *plain; /* or NULL */
    const FastRule *fast;     /* count entries, or NULL */
    union {
        /* with fast: the rule for each pair of neighbour classes (RuleTable.ctx_class), left
         * class * RuleTable.nclass + right class; NULL when there are too many classes */
        const struct Rule *const *pick;
        const Choice *choice; /* without fast: the choice, when the rules make one; or NULL */
    };
    uint32_t first;           /* index into RuleTable.order */
    uint32_t count;
} Dispatch;

typedef struct RuleTable {
    Rule *rules;
    int nrules;
    uint16_t *order;     /* rule indices grouped by predecessor code, source order kept */
    Dispatch *dispatch;  /* CODE_COUNT entries, NULL when the table is empty */
    bool has_context;
    bool ctx_left;       /* some rule has a left context */
    bool ctx_right;      /* some rule has a right context without branches: right links */
    bool ctx_branches;   /* some rule's right context names a branch: bracket pairs */
    bool ctx_index;      /* some linked context binds parameters or spans several modules */
    bool emits_params;   /* some successor has parameters */
    bool all_plain;      /* every rule is plain: no matching, no choice */
    bool has_newctx;     /* some rule has a new context: its passes run in one thread (newctx.c) */
    bool all_fast;       /* every predecessor's rules are plain or FastRules */
    bool light;          /* every code's rule is plain, fast or a Choice, and needs no VM to
                            emit: a pass costs a few ns a module and is bound by memory */
    uint8_t *stay;       /* per code: 1 + its arity when no rule rewrites it, else 0 (runs of
                            such modules are copied in one go); NULL unless all_plain */
    uint8_t *ctx_class;  /* per code: 1.. for the codes fast rules' contexts name, 0 others */
    int nclass;          /* classes including 0; 0 when the codes are too many for pick */
    bool *newleft_code;  /* CODE_COUNT entries: the codes some `<<` context names (only their
                            links are kept as the output is written); NULL without `<<` */
    bool *newright_code; /* the same for `>>` contexts that name no branch; NULL without */
    bool newright_branches; /* some `>>` context names a branch: backward passes keep every link */
    int max_succ;        /* longest successor in modules */
    int max_succ_params; /* most parameters a successor emits */
    int maxdepth;        /* decomposition / interpretation passes */
} RuleTable;

typedef struct Function {
    const char *name;
    const char **names; /* of the parameters */
    int nparams;
    uint32_t pc;
    SylLoc loc;
    int state; /* 0 not compiled, 1 compiling, 2 compiled, 3 its body has an error (no code) */
    /* `extern`: what the program's user binds (syl_program_bind_extern), else the default body
     * when it has one; never folded at compile time */
    bool external, has_default;
    SylExternFn bound;
    void *bound_user;
} Function;

typedef struct Curve {
    const char *name;
    SylLoc loc;
    double *x, *y;
    int n;
} Curve;

static inline double curve_eval(const Curve *c, double x) {
    if (x <= c->x[0]) return c->y[0];
    if (x >= c->x[c->n - 1]) return c->y[c->n - 1];
    int i = 1;
    while (c->x[i] < x) i++;
    double t = (x - c->x[i - 1]) / (c->x[i] - c->x[i - 1]);
    return c->y[i - 1] + t * (c->y[i] - c->y[i - 1]);
}

/* The curve called name, NULL if there is none (a strands block names its curves). */
const Curve *lang_curve_find(const SylProgram *p, const char *name);

typedef struct ParamInfo {
    const char *name;
    double value;
    bool overridden;
} ParamInfo;

enum { TABLE_PRODUCE, TABLE_DECOMPOSE, TABLE_INTERPRET, TABLE_COUNT };

/* A group of rules (a table of a table L-system): its rules take part in the steps where one
 * of its `use` conditions holds. A set of groups is a bitmask, so a model has at most 64. */
enum { MAX_GROUPS = 64 };
typedef struct Group {
    const char *name;
    SylLoc loc;       /* its first block */
    int32_t *when;    /* code of each `use` condition (local 0 is `step`); -1: every step */
    SylLoc *when_loc;
    int nwhen;
} Group;

struct SylProgram {
    SylModelKind kind;
    SylDirective *directives, *scene;
    int ndirectives, nscene;
    bool has_scene;
    bool first_model;       /* the file's first model (or its scene, when it holds no model):
                               the one whose validation covers the scene block, so that checking
                               every model of the file reports the scene once */
    bool uses_queries;      /* ?P ?H ?L ?U ?E appear: the turtle fills them after every step */
    bool uses_env;          /* ?E appears: the environment answers it after every step */
    SylOverride *overrides; /* the --set values it was compiled with, for its file's other models */
    int noverrides;
    const char **roots;     /* the real paths of the folders the files it names may be in:
                               its own, then --allow-path's (syl_program_file) */
    int nroots;
    const char **set_local; /* per --set: the name within this model ("Birch.lambda" in Birch:
                               "lambda"), NULL when meant for another model (lang/overrides.c) */
    bool sibling;           /* compiled for another model of the file: --set names it lacks are
                               not errors */
    Arena arena;
    Source src;
    SylSink sink;           /* SylCompileOptions.sink, copied: its diagnostics' records go there */
    bool has_sink;
    char *text; /* owned copy of the source */
    const char *name;
    SylLoc model_loc; /* where the model (or the file's scene) begins */
    SylLoc scene_loc; /* where the file's scene begins (has_scene) */
    struct SchCache *read_cache; /* the block's reading, kept at compile time (lang/schema.h) */

    Symbol *syms;
    int nsyms, symcap;

    uint32_t *code;  /* bytecode of every expression */
    SylLoc *code_loc; /* source location per instruction, for runtime errors */
    int ncode, codecap;
    double *consts;
    int nconsts, constcap;
    Function *fns;
    int nfns, fncap;
    Curve *curves;
    int ncurves, curvecap;
    ParamInfo *params;
    int nparams, paramcap;

    RuleTable tables[TABLE_COUNT];
    Group *groups;
    int ngroups;
    uint64_t grouped[TABLE_COUNT]; /* the groups that hold rules of each table */
    bool may_cut;        /* a successor or the axiom holds `%`: cut after every step */
    Rule axiom;          /* the axiom, as a rule with no predecessor */
    bool skip[MAX_SYMBOLS]; /* ignored in context matching */

    int derive;
    int lod;             /* the `lod` setting: levels of detail for `sylva mesh` (0: none) */
    double angle, step, width, widthfactor;
    double tropism[4];      /* direction and elasticity; elasticity 0: none */
    float colours[256][3];  /* `colour` settings, where colour_set */
    bool colour_set[256];
    uint64_t seed;
    /* `direction D [when EXPR]`: steps are derived backward when backward is true and
     * direction_when (code over the local `step`, -1: none) holds, or is absent */
    bool backward;
    int32_t direction_when;
};

/* A warning about p's source at line:col, as syl_program_report_error reports an error. */
void program_warning(const SylProgram *p, FILE *out, int line, int col, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));

/* A message of p's engines without a place in its source (a limit, a file that cannot be
 * read): to p's sink as a record with no line, else as text to out (diag_say). path NULL:
 * shown "sylva". */
void program_say(const SylProgram *p, FILE *out, int severity, const char *path, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
#define program_say_error(p, out, ...) program_say((p), (out), DIAG_ERROR, NULL, __VA_ARGS__)
/* The same three to a sink instead of a stream: p's sink when it has one, else sink (NULL:
 * nowhere), for the calls that take a sink (an ecosystem's read, check and terrain). */
void program_error_to(const SylProgram *p, const SylSink *sink, int line, int col, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
void directive_error_to(const SylProgram *p, const SylSink *sink, const SylDirective *d, const SylDirArg *a,
                        const char *fmt, ...) __attribute__((format(printf, 5, 6)));
void program_say_to(const SylProgram *p, const SylSink *sink, int severity, const char *path, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
/* whether a message for p goes anywhere (its sink or out) */
static inline bool program_heard(const SylProgram *p, FILE *out);

/* syl_model_list, with each model's kind in kinds[i] (NULL: not wanted). */
int lang_list_models(const char *path, const char *text, size_t len, const char **names, SylModelKind *kinds,
                     int max, char *buf, size_t bufsize);

/* grow, weber, strands and ecosystem blocks are lines of directives read by their engines, not rules */
static inline bool syl_kind_has_directives(SylModelKind k) { return lang_kind_is(k, KF_DIRECTIVES); }

/* The sink of the program's diagnostics (SylCompileOptions.sink), NULL: its callers' FILE. */
static inline const SylSink *program_sink(const SylProgram *p) { return p->has_sink ? &p->sink : NULL; }
static inline bool program_heard(const SylProgram *p, FILE *out) { return out || (p && p->has_sink); }
/* The `lod N` line of a grow, weber or strands block (lod.c): its check (the error count, 0
 * or 1, reported at the line), a --set lod= value's, and the levels the block asks for (its
 * last line, then the last --set lod=; 0: none). */
/* syl_compile_model with a sink for the model's records (NULL: diag), for as long as it lives. */
SylProgram *lang_compile_sibling(const SylProgram *p, const char *model, FILE *diag, const SylSink *sink,
                                 int *status);
int lang_lod_check(const SylProgram *p, const SylDirective *d, FILE *diag);
int lang_lod_set_check(const SylProgram *p, double v, const char *typed, FILE *diag);
double lang_directive_lod(const SylProgram *p);
/* Scan a directive block's lod once, while compiling, for lang_directive_lod to answer. */
void lang_keep_lod(SylProgram *p);

/* Whether symbol sym is a query module (?P ?H ?L ?U ?E): the turtle fills it after every step. */
static inline bool lang_symbol_is_query(const SylProgram *p, int sym) {
    return (turtle_command_flags(p->syms[sym].turtle) & TF_QUERY) != 0;
}

/* Resolve the folders p's named files may be in (lang/files.c): its own, then opt's. */
void lang_program_roots(SylProgram *p, const SylCompileOptions *opt);
/* Whether a file the model names (a "file.syl:Model" without its model), beside the model's
 * file (file_beside), can be read: 1, with an error at line:col that names it as written and
 * where it was looked for, when it cannot. */
int lang_check_file(const SylProgram *p, FILE *diag, const char *what, const char *file, int line, int col);

#endif
