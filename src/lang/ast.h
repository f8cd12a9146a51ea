/* The syntax tree of a .syl file, exactly as written; nothing is resolved yet. */
#ifndef SYL_AST_H
#define SYL_AST_H
#include <stdbool.h>

#include "util/arena.h"
#include "util/diag.h"
#include "sylva/sylva.h"

typedef enum {
    EX_NUM,  /* num */
    EX_NAME, /* name */
    EX_CALL, /* name(args) */
    EX_UNARY, /* op a: '-' or '!' */
    EX_BINARY, /* a op b: + - * / % ^ < > LE GE EQ NE */
    EX_AND,  /* a && b */
    EX_OR,   /* a || b */
    EX_COND, /* a ? b : c */
    EX_LOCAL, /* resolved by the compiler: a bound parameter, op = its slot */
} ExprKind;

/* Binary operators that need two characters. */
enum { BIN_LE = 256, BIN_GE, BIN_EQ, BIN_NE };

typedef struct Expr Expr;
typedef struct ExprList {
    Expr **v;
    int n, cap;
} ExprList;

struct Expr {
    ExprKind kind;
    int op;
    SylLoc loc;
    double num;
    const char *name;
    Expr *a, *b, *c;
    ExprList args;
};

/* A module item as written. A WORD may stand for several modules ("FX"); the checker
 * splits it once every `module` declaration is known. DIGITS is a run of digit modules. */
typedef enum { IT_WORD, IT_DIGITS, IT_SYMBOL } ItemKind;
typedef struct Item {
    ItemKind kind;
    const char *text;
    SylLoc loc;
    ExprList args;
    bool parens; /* written with (), possibly empty */
} Item;
typedef struct Items {
    Item *v;
    int n, cap;
} Items;

typedef struct NameList {
    const char **v;
    SylLoc *locs;
    int n, cap, lcap;
} NameList;

typedef struct Production {
    Items left, pred, right, succ;
    bool has_left, has_right, star; /* star: written `-> *` */
    Items newleft, newright; /* new contexts: `L << A`, `A >> R` (lpfg) */
    bool has_newleft, has_newright;
    SylLoc newleft_loc, newright_loc; /* the << and the >> */
    Expr *cond, *weight;
    SylLoc loc, arrow_loc;
} Production;

/* One argument of a directive line in a grow or scene block: a word, a number, a string, a
 * turtle symbol with parameters (~leaf(0.06)) or a parenthesised tuple of expressions. */
typedef enum { DARG_WORD, DARG_NUMBER, DARG_STRING, DARG_SYMBOL, DARG_TUPLE } DirArgKind;
typedef struct DirArg {
    DirArgKind kind;
    const char *text;
    Expr *value;   /* DARG_NUMBER */
    ExprList args; /* DARG_TUPLE, DARG_SYMBOL */
    SylLoc loc;
} DirArg;
typedef struct DirArgs {
    DirArg *v;
    int n, cap;
} DirArgs;

typedef enum {
    ST_DIRECTIVE, /* name args: a line of a grow or scene block */
    ST_CONST,     /* name = value */
    ST_PARAM,     /* name = value, overridable */
    ST_FN,        /* name(params) = value; external: `extern`, value NULL without a default */
    ST_CURVE,     /* name = points (args: x0, y0, x1, y1, ...) */
    ST_MODULE,    /* name(params) declaration; nparams < 0 when written without () */
    ST_SETTING,   /* name args */
    ST_IGNORE,    /* items */
    ST_CONSIDER,  /* items */
    ST_AXIOM,     /* items */
    ST_RULE,      /* rule */
    ST_GROUP,     /* name: a group block opens (its rules follow, with group = name) */
    ST_USE,       /* name, value: `use name when value` (value NULL: at every step) */
} StmtKind;

enum { BLOCK_PRODUCE, BLOCK_DECOMPOSE, BLOCK_INTERPRET, BLOCK_COUNT };

typedef struct Stmt {
    StmtKind kind;
    int block; /* BLOCK_* the statement stands in */
    const char *group; /* the group block it stands in, or NULL */
    SylLoc loc;
    const char *name;
    Expr *value;
    ExprList args;
    NameList params;
    bool has_params;
    bool external; /* ST_FN written `extern` */
    Items items;
    Production rule;
    DirArgs dargs;
    const Source *file; /* a directive spliced from another file (splice.c); NULL: this file's */
} Stmt;

typedef struct Model {
    SylModelKind kind;
    const char *name; /* NULL for the file's top level; "scene" for the scene */
    SylLoc loc;
    Stmt *v;
    int n, cap;
} Model;

typedef struct FileAst {
    Model top; /* statements outside any model: shared by all models of the file */
    Model *models;
    int nmodels, cap;
} FileAst;

/* Parse source text into ast. Returns the number of errors (reported through diag). */
int syl_parse(const Source *src, Arena *arena, Diag *diag, FileAst *ast);
/* An image, a mesh, an archive or another binary given as a model (foreign.c): one error that
 * says which; true when it is one. */
bool syl_not_a_model(const Source *src, Diag *diag);

#endif
