/* State shared by the flex lexer and the bison parser (internal to src/lang). */
#ifndef SYL_PARSE_STATE_H
#define SYL_PARSE_STATE_H
#include "lang/ast.h"

/* How deeply parentheses and other constructs may nest: bounds the parser's stack and the
 * checker's and compiler's recursion over the tree (docs/language.md, Limits). */
#define SYL_MAX_NESTING 1000

typedef struct LexState {
    int line, col, paren;
    int too_deep; /* "too deeply nested" was reported: the file ends there */
    int eof_done; /* a final NEWLINE was sent, so a file may end without one */
    int eof_reported; /* an error at the end of the file was reported already */
    SylLoc paren_loc; /* the outermost open parenthesis */
    Arena *arena;
    Diag *diag;
    SylLoc comment_loc;
} LexState;

typedef struct ParseState {
    LexState *lex;
    Arena *arena;
    Diag *diag;
    FileAst *ast;
    Model *model; /* where statements go: a model, or the file's top level */
    int block;    /* BLOCK_* */
    StmtKind decl; /* ST_CONST or ST_PARAM while reading a definition list */
} ParseState;

/* Words the lexer returns as SETTING rather than as a name (NULL-terminated). */
extern const char *const syl_setting_names[];

#endif
