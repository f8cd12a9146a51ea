/* Grammar of .syl files (docs/language.md). One statement per line; the parser only builds the
 * syntax tree, everything else (names, arities, modules in words) is the checker's job. */
%define api.pure full
/* syl_yy, not yy: a program that links libsylva may have its own yyparse (issue 9). */
%define api.prefix {syl_yy}
%define parse.error verbose
%locations
/* One known conflict: in a directive, `~leaf (0.1)` could be a symbol followed by a tuple;
 * bison shifts, so the parentheses are the symbol's parameters, as in a successor. */
%expect 1
%define api.location.type {SylLoc}
%param {void *scanner}
%parse-param {ParseState *ps}

%code requires {
#include "lang/kinds.h"
#include "lang/parse_state.h"
/* how bison names KW_BLOCK in a message; yyerror puts the keyword written in its place */
#define BLOCK_ALIAS "block keyword"
}

%code {
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int syl_yylex(SYL_YYSTYPE *lval, SylLoc *lloc, void *scanner);
/* The parser's stack holds one to four entries per level of nesting (the lexer counts
 * parentheses exactly): full, it says "memory exhausted", reported as what it is. */
#define YYMAXDEPTH (5 * SYL_MAX_NESTING + 64)
static void yyerror(SylLoc *loc, void *scanner, ParseState *ps, const char *msg) {
    (void)scanner;
    if (ps->lex->too_deep) return; /* reported, and the rest of the file is not read */
    if (loc->first_line == ps->lex->hint_line) return; /* the lexer said what to write instead */
    if (!strcmp(msg, "memory exhausted")) {
        diag_error(ps->diag, *loc, "too deeply nested (at most %d levels)", SYL_MAX_NESTING);
        ps->lex->too_deep = ps->lex->eof_reported = 1;
        return;
    }
    bool at_eof = strstr(msg, "unexpected end of file") != NULL;
    if (at_eof && ps->lex->eof_reported) return; /* the lexer said why already */
    if (ps->lex->paren > 0 && loc->first_line > ps->lex->paren_loc.first_line) {
        /* newlines are skipped inside parentheses: the real mistake is the open one */
        if (!ps->lex->eof_reported) diag_error(ps->diag, ps->lex->paren_loc, "'(' is never closed");
        ps->lex->eof_reported = 1;
        return;
    }
    /* KW_BLOCK stands for every directive block's keyword: the message names the one written */
    char named[512];
    const char *block = strstr(msg, BLOCK_ALIAS);
    if (block) {
        snprintf(named, sizeof named, "%.*s%s%s", (int)(block - msg), msg, lang_kind_keyword(ps->lex->kind),
                 block + strlen(BLOCK_ALIAS));
        msg = named;
    }
    if (at_eof && ps->model != &ps->ast->top)
        diag_error(ps->diag, *loc, "unexpected end of file: '}' missing to close %s '%s' (line %d)",
                   lang_kind_keyword(ps->model->kind), ps->model->name, ps->model->loc.first_line);
    else if (strstr(msg, "unexpected end of line, expecting ->"))
        diag_error(ps->diag, *loc, "%s (a rule needs '->'; the settings are derive, angle, step, width, widthfactor, seed, tropism, colour, lod)",
                   msg);
    else
        diag_error(ps->diag, *loc, "%s", msg);
}

/* A numeric literal's value. One too large for a double (strtod gives inf) is an error; one
 * too small to tell from 0 is what strtod makes of it (0 or a denormal), as a user expects. */
static double literal(ParseState *ps, const char *text, SylLoc loc) {
    double v = strtod(text, NULL);
    if (isfinite(v)) return v;
    diag_error(ps->diag, loc, "number out of range (at most %g)", DBL_MAX);
    return 0;
}

static SylLoc span(SylLoc a, SylLoc b) {
    SylLoc l = a;
    l.last_line = b.last_line;
    l.last_column = b.last_column;
    return l;
}

static Expr *mk(ParseState *ps, ExprKind k, SylLoc loc) {
    Expr *e = arena_alloc(ps->arena, sizeof *e);
    e->kind = k;
    e->loc = loc;
    return e;
}
static Expr *mk_bin(ParseState *ps, ExprKind k, int op, Expr *a, Expr *b, SylLoc oploc) {
    Expr *e = mk(ps, k, oploc);
    e->op = op;
    e->a = a;
    e->b = b;
    return e;
}
static Stmt *add_stmt(ParseState *ps, StmtKind kind, SylLoc loc) {
    Stmt *s = VEC_PUSH(ps->arena, ps->model->v, ps->model->n, ps->model->cap);
    s->kind = kind;
    s->loc = loc;
    s->block = ps->block;
    s->group = ps->group;
    return s;
}
static void begin_model(ParseState *ps, SylModelKind kind, const char *name, SylLoc loc) {
    for (int i = 0; i < ps->ast->nmodels; i++)
        if (!strcmp(ps->ast->models[i].name, name)) {
            if (lang_kind_is(kind, KF_UNNAMED))
                diag_error(ps->diag, loc, "a file holds one scene (the first is at line %d)",
                           ps->ast->models[i].loc.first_line);
            else
                diag_error(ps->diag, loc, "%s '%s' is already defined at line %d", lang_kind_keyword(kind), name,
                           ps->ast->models[i].loc.first_line);
        }
    Model *m = VEC_PUSH(ps->arena, ps->ast->models, ps->ast->nmodels, ps->ast->cap);
    m->kind = kind;
    m->name = name;
    m->loc = loc;
    ps->model = m;
}

/* A group block opens in the body or inside a decompose or interpret block (as L-Py's
 * `group` sits inside its sections); groups do not nest. */
static void open_group(ParseState *ps, const char *name, SylLoc loc) {
    if (ps->group)
        diag_error(ps->diag, loc, "group '%s' stands inside group '%s' (line %d): groups do not nest", name,
                   ps->group, ps->group_loc.first_line);
    Stmt *s = add_stmt(ps, ST_GROUP, loc);
    s->name = name;
    if (!ps->group_depth++) { /* a nested one's rules stay in the outer, after its error */
        ps->group = name;
        ps->group_loc = loc;
    }
}
/* decompose and interpret blocks hold groups, not the other way round */
static void sub_block(ParseState *ps, int block, SylLoc loc) {
    if (ps->group)
        diag_error(ps->diag, loc, "a %s block stands in the lsystem's body: write `group %s { }` inside it",
                   block == BLOCK_DECOMPOSE ? "decompose" : "interpret", ps->group);
    ps->block = block;
}

static DirArg darg(DirArgKind kind, const char *text, SylLoc loc) {
    DirArg a;
    memset(&a, 0, sizeof a);
    a.kind = kind;
    a.text = text;
    a.loc = loc;
    return a;
}

static Item item(const char *text, ItemKind kind, SylLoc loc) {
    Item it;
    memset(&it, 0, sizeof it);
    it.kind = kind;
    it.text = text;
    it.loc = loc;
    return it;
}
}

%union {
    char *str;
    int kind; /* SylModelKind, of a model's keyword */
    Expr *expr;
    ExprList exprs;
    Item item;
    Items items;
    NameList names;
    Production rule;
    DirArg darg;
    DirArgs dargs;
}

%token <str> WORD "name" DIGITS "integer" NUMBER "number" SPECIAL "turtle symbol" SETTING "setting" STRING "string"
%token LTLT "<<" GTGT ">>"
%token ARROW "->" NEWLINE "end of line" ANDAND "&&" OROR "||" EQ "==" NE "!=" LE "<=" GE ">="
/* The lexer gives SETTING and the KW_ tokens only as the first word of a statement that is
 * not a rule (grammar/lexer.l, lex_word); anywhere else the same words are WORD, a name. */
%token KW_MODULE "module" KW_CONST "const" KW_PARAM "param" KW_FN "fn" KW_EXTERN "extern"
%token KW_CURVE "curve" KW_AXIOM "axiom" KW_IGNORE "ignore" KW_CONSIDER "consider"
%token KW_DECOMPOSE "decompose" KW_INTERPRET "interpret" KW_GROUP "group" KW_USE "use"
/* A model's keyword (lang/kinds.def), by what its body holds: rules, the scene's lines, or a
 * named block of directive lines. Each carries its kind. */
%token <kind> KW_LSYSTEM "lsystem" KW_SCENE "scene" KW_BLOCK "block keyword" /* BLOCK_ALIAS */

%type <expr> expr cond_opt weight_opt use_when
%type <exprs> exprs exprs_opt args_opt points
%type <item> item hitem sym
%type <items> items hitems
%type <names> names names_opt
%type <rule> rule lhs
%type <darg> darg
%type <dargs> dargs
%type <str> gword

%right '?' ':'
%left OROR
%left ANDAND
%left EQ NE
%left '<' '>' LE GE
%left '+' '-'
%left '*' '/' '%'
%precedence UMINUS '!'
%right '^'

%%

file: %empty
    | file top
    ;

top: NEWLINE
   | decl NEWLINE
   | KW_LSYSTEM WORD '{' { begin_model(ps, $1, $2, @2); } body '}' { ps->model = &ps->ast->top; }
   | KW_SCENE '{' { begin_model(ps, $1, "scene", @1); } gbody '}' { ps->model = &ps->ast->top; }
   | KW_BLOCK WORD '{' { begin_model(ps, $1, $2, @2); } gbody '}' { ps->model = &ps->ast->top; }
   | use { diag_error(ps->diag, @1, "'use' stands in an lsystem's body, not outside a model"); }
   | error NEWLINE { yyerrok; ps->model = ps->model ? ps->model : &ps->ast->top; }
   ;

/* directive blocks and the scene: lines of directives, read by the engine that owns them */
gbody: %empty
     | gbody gstmt
     ;
gstmt: NEWLINE
     | decl NEWLINE
     | WORD dargs NEWLINE { Stmt *s = add_stmt(ps, ST_DIRECTIVE, @1); s->name = $1; s->dargs = $2; }
     | SETTING dargs NEWLINE { Stmt *s = add_stmt(ps, ST_DIRECTIVE, @1); s->name = $1; s->dargs = $2; }
     | gword dargs NEWLINE { Stmt *s = add_stmt(ps, ST_DIRECTIVE, @1); s->name = $1; s->dargs = $2; }
     | error NEWLINE { yyerrok; }
     ;
/* the lsystem words that head a line are directive words here, like any other */
gword: KW_USE { $$ = "use"; }
     | KW_GROUP { $$ = "group"; }
     | KW_BLOCK { $$ = (char *)lang_kind_keyword($1); }
     ;
dargs: %empty { memset(&$$, 0, sizeof $$); }
     | dargs darg { $$ = $1; *VEC_PUSH(ps->arena, $$.v, $$.n, $$.cap) = $2; }
     ;
darg: WORD { $$ = darg(DARG_WORD, $1, @1); }
    | STRING { $$ = darg(DARG_STRING, $1, @1); }
    | NUMBER { $$ = darg(DARG_NUMBER, $1, @1); $$.value = mk(ps, EX_NUM, @1); $$.value->num = literal(ps, $1, @1); }
    | DIGITS { $$ = darg(DARG_NUMBER, $1, @1); $$.value = mk(ps, EX_NUM, @1); $$.value->num = literal(ps, $1, @1); }
    | '-' NUMBER { $$ = darg(DARG_NUMBER, $2, @2); $$.value = mk(ps, EX_NUM, @2); $$.value->num = -literal(ps, $2, @2); }
    | '-' DIGITS { $$ = darg(DARG_NUMBER, $2, @2); $$.value = mk(ps, EX_NUM, @2); $$.value->num = -literal(ps, $2, @2); }
    | SPECIAL args_opt { $$ = darg(DARG_SYMBOL, $1, @1); $$.args = $2; }
    | '(' exprs ')' { $$ = darg(DARG_TUPLE, "(", @1); $$.args = $2; }
    ;

body: %empty
    | body stmt
    ;

stmt: NEWLINE
    | decl NEWLINE
    | SETTING exprs NEWLINE { Stmt *s = add_stmt(ps, ST_SETTING, @1); s->name = $1; s->args = $2; }
    | SETTING ':' exprs NEWLINE { Stmt *s = add_stmt(ps, ST_SETTING, @1); s->name = $1; s->args = $3; }
    /* a texture line (lang/textures.def): a file name, then words and numbers, as in a block */
    | SETTING STRING dargs NEWLINE {
          Stmt *s = add_stmt(ps, ST_DIRECTIVE, @1); s->name = $1;
          *VEC_PUSH(ps->arena, s->dargs.v, s->dargs.n, s->dargs.cap) = darg(DARG_STRING, $2, @2);
          for (int k = 0; k < $3.n; k++) *VEC_PUSH(ps->arena, s->dargs.v, s->dargs.n, s->dargs.cap) = $3.v[k];
      }
    | KW_IGNORE colon_opt items NEWLINE { add_stmt(ps, ST_IGNORE, @1)->items = $3; }
    | KW_CONSIDER colon_opt items NEWLINE { add_stmt(ps, ST_CONSIDER, @1)->items = $3; }
    | KW_AXIOM colon_opt items NEWLINE { add_stmt(ps, ST_AXIOM, @1)->items = $3; }
    | rule NEWLINE { add_stmt(ps, ST_RULE, $1.loc)->rule = $1; }
    | KW_DECOMPOSE '{' { sub_block(ps, BLOCK_DECOMPOSE, @1); } body '}' { ps->block = BLOCK_PRODUCE; }
    | KW_INTERPRET '{' { sub_block(ps, BLOCK_INTERPRET, @1); } body '}' { ps->block = BLOCK_PRODUCE; }
    | group
    | use
    | error NEWLINE { yyerrok; }
    ;

/* `direction backward when EXPR`: a setting whose value holds on the steps where EXPR does */
stmt: SETTING WORD WORD expr NEWLINE {
          Stmt *s = add_stmt(ps, ST_SETTING, @1); s->name = $1;
          Expr *e = mk(ps, EX_NAME, @2); e->name = $2;
          *VEC_PUSH(ps->arena, s->args.v, s->args.n, s->args.cap) = e;
          if (strcmp($3, "when")) diag_error(ps->diag, @3, "expected `when` after '%s %s'", $1, $2);
          s->value = $4;
      }
    ;

/* The book's and cpfg's `axiom:`, `ignore:`, `derive:`: the colon means nothing more. */
colon_opt: %empty
         | ':'
         ;

decl: KW_CONST { ps->decl = ST_CONST; } defs
    | KW_PARAM { ps->decl = ST_PARAM; } defs
    | KW_FN WORD '(' names_opt ')' '=' expr {
          Stmt *s = add_stmt(ps, ST_FN, @2);
          s->name = $2; s->params = $4; s->has_params = true; s->value = $7;
      }
    /* a function the program's user binds (Python, C): its arity, and an optional default body */
    | KW_EXTERN WORD '(' names_opt ')' {
          Stmt *s = add_stmt(ps, ST_FN, @2);
          s->name = $2; s->params = $4; s->has_params = true; s->external = true;
      }
    | KW_EXTERN WORD '(' names_opt ')' '=' expr {
          Stmt *s = add_stmt(ps, ST_FN, @2);
          s->name = $2; s->params = $4; s->has_params = true; s->value = $7; s->external = true;
      }
    | KW_CURVE WORD '=' points {
          Stmt *s = add_stmt(ps, ST_CURVE, @2);
          s->name = $2; s->args = $4;
      }
    | KW_MODULE mdecls
    ;

defs: def
    | defs ',' def
    ;
def: WORD '=' expr { Stmt *s = add_stmt(ps, ps->decl, @1); s->name = $1; s->value = $3; }
   ;

mdecls: mdecl
      | mdecls ',' mdecl
      ;
mdecl: WORD { add_stmt(ps, ST_MODULE, @1)->name = $1; }
     | WORD '(' names_opt ')' {
           Stmt *s = add_stmt(ps, ST_MODULE, @1);
           s->name = $1; s->params = $3; s->has_params = true;
       }
     ;

names_opt: %empty { memset(&$$, 0, sizeof $$); }
         | names
         ;
names: WORD { memset(&$$, 0, sizeof $$);
              *VEC_PUSH(ps->arena, $$.v, $$.n, $$.cap) = $1;
              $$.n--; *VEC_PUSH(ps->arena, $$.locs, $$.n, $$.lcap) = @1; }
     | names ',' WORD { $$ = $1;
              *VEC_PUSH(ps->arena, $$.v, $$.n, $$.cap) = $3;
              $$.n--; *VEC_PUSH(ps->arena, $$.locs, $$.n, $$.lcap) = @3; }
     ;

points: '(' expr ',' expr ')' { memset(&$$, 0, sizeof $$);
              *VEC_PUSH(ps->arena, $$.v, $$.n, $$.cap) = $2;
              *VEC_PUSH(ps->arena, $$.v, $$.n, $$.cap) = $4; }
      | points ',' '(' expr ',' expr ')' { $$ = $1;
              *VEC_PUSH(ps->arena, $$.v, $$.n, $$.cap) = $4;
              *VEC_PUSH(ps->arena, $$.v, $$.n, $$.cap) = $6; }
      ;

/* ---- tables: groups of rules and the steps that use them (docs/language.md, Tables) ---- */

group: KW_GROUP WORD '{' { open_group(ps, $2, @2); } body '}' { if (!--ps->group_depth) ps->group = NULL; }
     ;
use: KW_USE WORD use_when NEWLINE {
         if (ps->group || ps->block != BLOCK_PRODUCE)
             diag_error(ps->diag, @1, "'use' stands in the lsystem's body, not inside %s block",
                        ps->group ? "a group" : ps->block == BLOCK_DECOMPOSE ? "a decompose" : "an interpret");
         Stmt *s = add_stmt(ps, ST_USE, @2); s->name = $2; s->value = $3;
     }
   ;
/* `when EXPR`, or nothing: the group is used at every step */
use_when: %empty { $$ = NULL; }
        | WORD expr {
              if (strcmp($1, "when")) diag_error(ps->diag, @1, "write 'use NAME when CONDITION'");
              $$ = $2;
          }
        ;

/* ---- productions ---- */

rule: lhs cond_opt ARROW items weight_opt {
          $$ = $1; $$.cond = $2; $$.succ = $4; $$.weight = $5; $$.arrow_loc = @3;
      }
    | lhs cond_opt ARROW '*' weight_opt {
          $$ = $1; $$.cond = $2; $$.star = true; $$.weight = $5; $$.arrow_loc = @3;
      }
    ;

lhs: hitems { memset(&$$, 0, sizeof $$); $$.pred = $1; $$.loc = @1; }
   | hitems '<' hitems { memset(&$$, 0, sizeof $$); $$.left = $1; $$.has_left = true;
                         $$.pred = $3; $$.loc = @3; }
   | hitems '>' hitems { memset(&$$, 0, sizeof $$); $$.pred = $1; $$.right = $3;
                         $$.has_right = true; $$.loc = @1; }
   | hitems '<' hitems '>' hitems { memset(&$$, 0, sizeof $$); $$.left = $1; $$.has_left = true;
                         $$.pred = $3; $$.right = $5; $$.has_right = true; $$.loc = @3; }
   ;

/* ---- new contexts (lpfg's `<<` and `>>`): the string being produced in this step ---- */
lhs: hitems LTLT hitems { memset(&$$, 0, sizeof $$); $$.newleft = $1; $$.has_newleft = true;
                          $$.newleft_loc = @2; $$.pred = $3; $$.loc = @3; }
   | hitems GTGT hitems { memset(&$$, 0, sizeof $$); $$.pred = $1; $$.newright = $3;
                          $$.has_newright = true; $$.newright_loc = @2; $$.loc = @1; }
   | hitems LTLT hitems '>' hitems { memset(&$$, 0, sizeof $$); $$.newleft = $1; $$.has_newleft = true;
                          $$.newleft_loc = @2; $$.pred = $3; $$.right = $5; $$.has_right = true; $$.loc = @3; }
   | hitems '<' hitems GTGT hitems { memset(&$$, 0, sizeof $$); $$.left = $1; $$.has_left = true;
                          $$.pred = $3; $$.newright = $5; $$.has_newright = true; $$.newright_loc = @4;
                          $$.loc = @3; }
   | hitems LTLT hitems GTGT hitems { memset(&$$, 0, sizeof $$); $$.newleft = $1; $$.has_newleft = true;
                          $$.newleft_loc = @2; $$.pred = $3; $$.newright = $5; $$.has_newright = true;
                          $$.newright_loc = @4; $$.loc = @3; }
   /* one kind of context on a side: said here, where both are seen */
   | hitems '<' hitems LTLT hitems { memset(&$$, 0, sizeof $$); $$.pred = $5; $$.loc = @5;
                          diag_error(ps->diag, @4, "a left context is old (`<`) or new (`<<`), not both: "
                                     "write `L < A` or `L << A`"); }
   | hitems LTLT hitems '<' hitems { memset(&$$, 0, sizeof $$); $$.pred = $5; $$.loc = @5;
                          diag_error(ps->diag, @4, "a left context is new (`<<`) or old (`<`), not both: "
                                     "write `L << A` or `L < A`"); }
   | hitems GTGT hitems '>' hitems { memset(&$$, 0, sizeof $$); $$.pred = $1; $$.loc = @1;
                          diag_error(ps->diag, @4, "a right context is new (`>>`) or old (`>`), not both: "
                                     "write `A >> R` or `A > R`"); }
   | hitems '>' hitems GTGT hitems { memset(&$$, 0, sizeof $$); $$.pred = $1; $$.loc = @1;
                          diag_error(ps->diag, @4, "a right context is old (`>`) or new (`>>`), not both: "
                                     "write `A > R` or `A >> R`"); }
   ;

cond_opt: %empty { $$ = NULL; }
        | ':' expr { $$ = $2; }
        ;
weight_opt: %empty { $$ = NULL; }
          | ':' expr { $$ = $2; }
          ;

/* Module sequences. Braces are polygon modules in successors and axioms, but never in
 * a rule's head, so that a `}` at the start of a line always closes a block. */
items: %empty { memset(&$$, 0, sizeof $$); }
     | items item { $$ = $1; *VEC_PUSH(ps->arena, $$.v, $$.n, $$.cap) = $2; }
     | items ANDAND args_opt { $$ = $1; /* `&&` here is two pitch-down modules */
           *VEC_PUSH(ps->arena, $$.v, $$.n, $$.cap) = item("&", IT_SYMBOL, @2);
           Item *it = VEC_PUSH(ps->arena, $$.v, $$.n, $$.cap);
           *it = item("&", IT_SYMBOL, @2); it->args = $3; it->parens = @3.first_line > 0; }
     | items OROR args_opt { $$ = $1;
           *VEC_PUSH(ps->arena, $$.v, $$.n, $$.cap) = item("|", IT_SYMBOL, @2);
           Item *it = VEC_PUSH(ps->arena, $$.v, $$.n, $$.cap);
           *it = item("|", IT_SYMBOL, @2); it->args = $3; it->parens = @3.first_line > 0; }
     ;
item: hitem
    | '{' args_opt { $$ = item("{", IT_SYMBOL, @1); $$.args = $2; $$.parens = @2.first_line > 0; }
    | '}' args_opt { $$ = item("}", IT_SYMBOL, @1); $$.args = $2; $$.parens = @2.first_line > 0; }
    ;
hitems: hitem { memset(&$$, 0, sizeof $$); *VEC_PUSH(ps->arena, $$.v, $$.n, $$.cap) = $1; }
      | hitems hitem { $$ = $1; *VEC_PUSH(ps->arena, $$.v, $$.n, $$.cap) = $2; }
      ;
hitem: WORD args_opt { $$ = item($1, IT_WORD, @1); $$.args = $2; $$.parens = @2.first_line > 0; }
     | DIGITS args_opt { $$ = item($1, IT_DIGITS, @1); $$.args = $2; $$.parens = @2.first_line > 0; }
     | sym args_opt { $$ = $1; $$.args = $2; $$.parens = @2.first_line > 0; }
     | '[' { $$ = item("[", IT_SYMBOL, @1); }
     | ']' { $$ = item("]", IT_SYMBOL, @1); }
     ;
sym: '+' { $$ = item("+", IT_SYMBOL, @1); }
   | '-' { $$ = item("-", IT_SYMBOL, @1); }
   | '&' { $$ = item("&", IT_SYMBOL, @1); }
   | '^' { $$ = item("^", IT_SYMBOL, @1); }
   | '\\' { $$ = item("\\", IT_SYMBOL, @1); }
   | '/' { $$ = item("/", IT_SYMBOL, @1); }
   | '|' { $$ = item("|", IT_SYMBOL, @1); }
   | '!' { $$ = item("!", IT_SYMBOL, @1); }
   | '\'' { $$ = item("'", IT_SYMBOL, @1); }
   | '$' { $$ = item("$", IT_SYMBOL, @1); }
   | '%' { $$ = item("%", IT_SYMBOL, @1); }
   | '.' { $$ = item(".", IT_SYMBOL, @1); }
   | ';' { $$ = item(";", IT_SYMBOL, @1); }
   | ',' { $$ = item(",", IT_SYMBOL, @1); }
   | '~' { $$ = item("~", IT_SYMBOL, @1); }
   | SPECIAL { $$ = item($1, IT_SYMBOL, @1); }
   ;
/* An empty location (line 0) tells "no parentheses" from "()". */
args_opt: %empty { memset(&$$, 0, sizeof $$); @$.first_line = 0; }
        | '(' exprs_opt ')' { $$ = $2; }
        ;

/* ---- expressions ---- */

exprs_opt: %empty { memset(&$$, 0, sizeof $$); }
         | exprs
         ;
exprs: expr { memset(&$$, 0, sizeof $$); *VEC_PUSH(ps->arena, $$.v, $$.n, $$.cap) = $1; }
     | exprs ',' expr { $$ = $1; *VEC_PUSH(ps->arena, $$.v, $$.n, $$.cap) = $3; }
     ;

expr: NUMBER { $$ = mk(ps, EX_NUM, @1); $$->num = literal(ps, $1, @1); }
    | DIGITS { $$ = mk(ps, EX_NUM, @1); $$->num = literal(ps, $1, @1); }
    | WORD { $$ = mk(ps, EX_NAME, @1); $$->name = $1; }
    | WORD '(' exprs_opt ')' { $$ = mk(ps, EX_CALL, span(@1, @4)); $$->name = $1; $$->args = $3; }
    | '(' expr ')' { $$ = $2; }
    | expr '+' expr { $$ = mk_bin(ps, EX_BINARY, '+', $1, $3, @2); }
    | expr '-' expr { $$ = mk_bin(ps, EX_BINARY, '-', $1, $3, @2); }
    | expr '*' expr { $$ = mk_bin(ps, EX_BINARY, '*', $1, $3, @2); }
    | expr '/' expr { $$ = mk_bin(ps, EX_BINARY, '/', $1, $3, @2); }
    | expr '%' expr { $$ = mk_bin(ps, EX_BINARY, '%', $1, $3, @2); }
    | expr '^' expr { $$ = mk_bin(ps, EX_BINARY, '^', $1, $3, @2); }
    | expr '<' expr { $$ = mk_bin(ps, EX_BINARY, '<', $1, $3, @2); }
    | expr '>' expr { $$ = mk_bin(ps, EX_BINARY, '>', $1, $3, @2); }
    | expr LE expr { $$ = mk_bin(ps, EX_BINARY, BIN_LE, $1, $3, @2); }
    | expr GE expr { $$ = mk_bin(ps, EX_BINARY, BIN_GE, $1, $3, @2); }
    | expr EQ expr { $$ = mk_bin(ps, EX_BINARY, BIN_EQ, $1, $3, @2); }
    | expr NE expr { $$ = mk_bin(ps, EX_BINARY, BIN_NE, $1, $3, @2); }
    | expr ANDAND expr { $$ = mk_bin(ps, EX_AND, 0, $1, $3, @2); }
    | expr OROR expr { $$ = mk_bin(ps, EX_OR, 0, $1, $3, @2); }
    | expr '?' expr ':' expr { $$ = mk_bin(ps, EX_COND, 0, $1, $3, @2); $$->c = $5; }
    | '-' expr %prec UMINUS { $$ = mk(ps, EX_UNARY, @1); $$->op = '-'; $$->a = $2; }
    | '+' expr %prec UMINUS { $$ = $2; }
    | '!' expr { $$ = mk(ps, EX_UNARY, @1); $$->op = '!'; $$->a = $2; }
    ;

%%
