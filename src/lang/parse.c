/* Runs the flex scanner and the bison parser over one source text. */
#include <setjmp.h>
#include <string.h>

#include "lang/arbaro.h"
#include "lang/kinds.h"
#include "lang/pafco_cfg.h"
#include "lang/parse_state.h"
#include "lang/sapling.h"
#include "parser.h"
#define YYSTYPE SYL_YYSTYPE /* as in grammar/lexer.l */
#define YYLTYPE SYL_YYLTYPE
#include "lexer.h"

/* The words that head a statement; the ones that open a model are the kinds' (lang/kinds.def,
 * lang_kind_token). */
const SylKeyword syl_keywords[] = {
    {"module", KW_MODULE}, {"const", KW_CONST}, {"param", KW_PARAM},
    {"fn", KW_FN}, {"extern", KW_EXTERN}, {"curve", KW_CURVE}, {"axiom", KW_AXIOM}, {"ignore", KW_IGNORE},
    {"consider", KW_CONSIDER}, {"decompose", KW_DECOMPOSE}, {"interpret", KW_INTERPRET},
    {"group", KW_GROUP}, {"use", KW_USE}, {NULL, 0},
};

/* A model's keyword is one of three tokens, by what its body holds: rules (KW_LSYSTEM), the
 * file's unnamed scene (KW_SCENE) or directive lines (KW_BLOCK); each carries its kind. */
int lang_kind_token(SylModelKind k) {
    return lang_kind_is(k, KF_RULES) ? KW_LSYSTEM : lang_kind_is(k, KF_UNNAMED) ? KW_SCENE : KW_BLOCK;
}

int syl_yyparse(void *scanner, ParseState *ps);

int syl_parse(const Source *src, Arena *arena, Diag *diag, FileAst *ast) {
    memset(ast, 0, sizeof *ast);
    int before = diag->errors;
    LexState ls = {.line = 1, .col = 1, .arena = arena, .diag = diag, .text = src->text, .len = src->len,
                   .at_start = 1};
    ParseState ps = {.lex = &ls, .arena = arena, .diag = diag, .ast = ast, .model = &ast->top};
    yyscan_t scanner;
    if (syl_yylex_init_extra(&ls, &scanner)) {
        diag_error(diag, (SylLoc){0}, "cannot start the lexer");
        return 1;
    }
    /* Out of memory in the scanner or the arena unwinds to here: free the scanner, then go
     * on to the caller's target (the compiler's), or report it when there is none. */
    jmp_buf *outer = arena->oom, oom;
    int rc = 1, failed = 1; /* both set only on the way that does not jump */
    if (!setjmp(oom)) {
        arena->oom = &oom;
        if (syl_arbaro_detect(src)) {
            rc = syl_arbaro_parse(src, arena, diag, ast);
        } else if (syl_foreign_file(src, diag)) {
            rc = 1;
        } else if (syl_picek_detect(src)) {
            rc = syl_picek_parse(src, arena, diag, ast);
        } else if (syl_sapling_detect(src)) {
            rc = syl_sapling_parse(src, arena, diag, ast);
        } else if (lang_pafco_cfg_detect(src->text, src->len)) {
            rc = lang_pafco_cfg_parse(src, arena, diag, ast);
        } else {
            YY_BUFFER_STATE buf = syl_yy_scan_bytes(src->text, (int)src->len, scanner);
            rc = syl_yyparse(scanner, &ps);
            syl_yy_delete_buffer(buf, scanner);
        }
        failed = 0;
    }
    syl_yylex_destroy(scanner);
    arena->oom = outer;
    if (failed && outer) longjmp(*outer, 1);
    if (failed) diag_error(diag, (SylLoc){0}, "out of memory");
    if (rc && diag->errors == before) diag_error(diag, (SylLoc){0}, "could not parse the file");
    return diag->errors - before;
}
