/* Internal to src/lang: the state of one compilation and the pieces that share it. */
#ifndef SYL_COMPILER_H
#define SYL_COMPILER_H
#include "lang/ast.h"
#include "lang/program.h"
#include "sylva/sylva.h"
#include "util/namemap.h"

/* A named value known at compile time: a const or a param. */
typedef struct Value {
    const char *name;
    SylLoc loc;
    bool is_param, known, used;
    bool top; /* defined outside any model: shared, so not reported as unused */
    double v;
} Value;

/* Names bound inside one expression: rule parameters or function parameters. */
typedef struct Scope {
    const char **names;
    int n;
    bool *used;
} Scope;

/* One expression's code, built apart and appended whole (a nested function compile may
 * append in the middle); jump operands are relative to the chunk until then. */
typedef struct Emitter {
    uint32_t *code;
    SylLoc *loc;
    int n, cap, loccap;
    int depth, maxdepth;
} Emitter;

/* A module after words were split: symbol id and its argument expressions. */
typedef struct Mod {
    int sym;
    SylLoc loc;
    ExprList args;
} Mod;
typedef struct Mods {
    Mod *v;
    int n, cap;
} Mods;

typedef struct Compiler {
    SylProgram *p;
    Diag *d;
    Arena *tmp; /* AST and scratch, freed after compilation */
    const SylCompileOptions *opt;
    NameMap values, fns, curves, syms, declared;
    Value *vals;
    int nvals, valcap;
    int max_declared_len;
    bool usage_error; /* an error of the command line (--set), not of the model */
    Stmt **fn_stmts; /* per function: its definition */
    bool *fn_random; /* per function: its body draws random numbers */
    bool *fn_used, *curve_used;
    bool *sym_used;  /* per symbol: appears in an axiom or a rule */
    int depth;       /* of cc_fold's recursion, through nested function compiles too */
    bool too_deep;   /* that was reported */
    const char *extern_called; /* an extern function the expression cc_const folds calls */
    int warn;        /* SYL_WARN_*: which warnings to report (all with lint) */
    const FileAst *ast; /* the whole file: its models' names qualify --set names */
} Compiler;

/* How deep cc_fold (and so code generation) may recurse: the parser bounds nesting, but a
 * chain such as 1+1+...+1 is as deep as it is long. */
#define CC_MAX_DEPTH 4000

/* expr.c */
Expr *cc_fold(Compiler *c, Expr *e, Scope *s, bool *random);
bool cc_const(Compiler *c, Expr *e, double *out); /* compile-time value or an error */
/* Fold, emit and append; returns its pc. *random (may be NULL) tells whether it draws. */
int32_t cc_expr(Compiler *c, Expr *e, Scope *s, bool *random);
void cc_function(Compiler *c, int fn);

/* declare.c */
void cc_declare(Compiler *c, Stmt *s, bool top); /* top: outside any model */
void cc_evaluate(Compiler *c, Stmt *s);            /* a const, param or curve, in the order written */

/* overrides.c: --set */
void cc_localise_overrides(Compiler *c);
const SylOverride *cc_find_override(Compiler *c, const char *name); /* the last one given wins */
void cc_check_overrides(Compiler *c);  /* every name reaches something, before evaluation */
void cc_apply_overrides(Compiler *c);  /* settings, once the model's own are read */

/* settings.c: a setting set by --set. -1: no setting of that name; 0: it failed (reported);
 * 1: stored. */
int cc_setting_override(Compiler *c, const char *name, double v, const char *typed);
int cc_setting_names(const char **out, int max); /* the names --set reaches, for suggestions */

/* rules.c */
static inline bool cc_is_bracket(int sym) { return sym == SYM_OPEN || sym == SYM_CLOSE; }
bool cc_code_constant(const SylProgram *p, int32_t pc, double *v); /* PUSHK k; RET */
void cc_rule(Compiler *c, const Stmt *s, Rule *out);
/* A successor (or the axiom: what names it in messages) over the rule's bound names. */
void cc_successor(Compiler *c, const Mods *ms, Scope *s, Rule *r, const char *what);
void cc_build_table(Compiler *c, RuleTable *t); /* dispatch and fast paths, once its rules are in */

/* groups.c */
int cc_group_of(const SylProgram *p, const char *name); /* its index, -1: none (or name NULL) */
void cc_groups(Compiler *c, Stmt **all, int n);           /* groups and `use` lines, before the rules */

/* settings.c */
/* A setting statement; seen: where each was first set, to report one set twice. */
void cc_setting(Compiler *c, Stmt *s, SylLoc *seen);

/* modules.c */
int cc_symbol(Compiler *c, const char *name, SylLoc loc);
void cc_split(Compiler *c, const Items *items, Mods *out);

/* lint.c */
/* splice.c: a weber block's `from "file"`: that file's parameters before the block's lines */
void cc_splice_from(Compiler *c, Model *m);
void cc_lint(Compiler *c);
/* The warnings of mistakes (c->warn), also printed by the commands that derive. */
void cc_warn(Compiler *c);
void cc_warn_words(Compiler *c, const Items *items); /* "did you mean", in a successor or the axiom */
/* The closest declared module to word (NULL: none close), for messages. */
const char *cc_near_module(Compiler *c, const char *word);

#endif
