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
    /* Words are contextual: a keyword or setting word is one only as the first word of a
     * statement that is not a rule (docs/language.md, Names). The lexer reads ahead in text. */
    const char *text;
    size_t len, pos; /* pos: just after the token being read */
    int at_start;    /* the next token begins a statement */
    int first;       /* the first token of the current statement */
    /* Other programs' spellings (docs/language.md §18): the lexer accepts the ones with one
     * meaning and says what to write instead of the others. */
    int prev;      /* the token before the one being read */
    int cond;      /* in a rule's condition (after its ':', before its arrow): '=' is '==' */
    int after_eq;  /* a definition's '=' was read in this statement: an expression follows */
    int hint_line; /* a line whose mistake the lexer explained: the parser stays silent there */
    int arrow_known; /* arrow_at is known for this statement */
    size_t arrow_at; /* just after the start of its rule's arrow; 0: it has none ahead */
    int kind;        /* the model kind of the last keyword that opens a model */
} LexState;

typedef struct ParseState {
    LexState *lex;
    Arena *arena;
    Diag *diag;
    FileAst *ast;
    Model *model; /* where statements go: a model, or the file's top level */
    int block;    /* BLOCK_* */
    const char *group; /* the group block being read, or NULL */
    SylLoc group_loc;
    int group_depth;   /* group blocks open (more than one is an error) */
    StmtKind decl; /* ST_CONST or ST_PARAM while reading a definition list */
} ParseState;

/* The language's keywords and their tokens (parse.c), ended by {NULL, 0}. */
typedef struct SylKeyword {
    const char *word;
    int token;
} SylKeyword;
extern const SylKeyword syl_keywords[];
/* The token a model kind's keyword is (parse.c). */
int lang_kind_token(SylModelKind k);

/* Pícek's plant files (picek.c): whether the text is one (its first line that is not blank
 * or a `;` comment opens with one of its keys and a colon), and reading it into ast as one
 * lsystem named after the file. Returns the number of errors. */
bool syl_picek_detect(const Source *src);
int syl_picek_parse(const Source *src, Arena *arena, Diag *diag, FileAst *ast);

/* A whole cpfg (.l) or L-Py (.lpy) file (foreign.c): reported as such; true when it is one. */
bool syl_foreign_file(const Source *src, Diag *diag);

/* The setting words, from settings.c's one table: the i-th, NULL past the last. */
const char *syl_setting_name(int i);

#endif
