/* Pafčo's parameter files (pafco_cfg.h): each line `NAME=value` becomes the line `NAME value`
 * of a `pafco` block; the generator's reader (pafco/params.c) checks names and values, so a
 * file and a block say the same things about the same mistakes. */
#include "lang/pafco_cfg.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lang/schema.h"
#include "util/file.h"

typedef struct Line {
    const char *b, *e, *start; /* the line without surrounding blanks; its first byte */
    int no;
} Line;

static bool blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

static bool next_line(const char *t, size_t len, size_t *pos, Line *ln) {
    if (*pos >= len) return false;
    const char *p = t + *pos, *end = t + len;
    const char *nl = memchr(p, '\n', (size_t)(end - p));
    const char *stop = nl ? nl : end;
    ln->start = ln->b = p;
    ln->e = stop;
    while (ln->b < ln->e && blank(*ln->b)) ln->b++;
    while (ln->e > ln->b && blank(ln->e[-1])) ln->e--;
    ln->no++;
    *pos = (size_t)(stop - t) + (nl ? 1 : 0);
    return true;
}

static bool skipped(const Line *ln) { return ln->b == ln->e || *ln->b == '#'; }

/* The name that opens `NAME=…` (capitals, digits, _), its length; 0 when the line is not one. */
static size_t line_name(const Line *ln, const char **eq) {
    const char *p = ln->b;
    if (p >= ln->e || !(isupper((unsigned char)*p))) return 0;
    while (p < ln->e && (isupper((unsigned char)*p) || isdigit((unsigned char)*p) || *p == '_')) p++;
    size_t n = (size_t)(p - ln->b);
    while (p < ln->e && blank(*p)) p++;
    if (p >= ln->e || *p != '=') return 0;
    *eq = p;
    return n;
}

bool lang_pafco_cfg_detect(const char *text, size_t len) {
    size_t pos = 0;
    Line ln = {0};
    bool first = true;
    while (next_line(text, len, &pos, &ln)) {
        if (skipped(&ln)) continue;
        const char *eq;
        size_t n = line_name(&ln, &eq);
        if (first && !n) return false;
        first = false;
        char name[64];
        if (n && n < sizeof name) {
            memcpy(name, ln.b, n), name[n] = 0;
            if (sch_find(&sch_pafco, name, NULL)) return true;
        }
    }
    return false;
}

static SylLoc at(const Line *ln, const char *p, size_t n) {
    int col = (int)(p - ln->start) + 1;
    return (SylLoc){ln->no, col, ln->no, col + (int)(n ? n - 1 : 0)};
}

/* One value: a number, a word (true, false) or a file name. */
static void value(Arena *a, Stmt *s, const char *b, size_t n, SylLoc loc) {
    DirArg *d = VEC_PUSH(a, s->dargs.v, s->dargs.n, s->dargs.cap);
    char buf[64];
    if (n < sizeof buf) {
        memcpy(buf, b, n), buf[n] = 0;
        char *stop;
        double x = strtod(buf, &stop);
        if (stop != buf && *stop == 0 && isfinite(x) && !isalpha((unsigned char)buf[0])) {
            *d = (DirArg){.kind = DARG_NUMBER, .text = "", .loc = loc};
            d->value = arena_alloc(a, sizeof *d->value);
            *d->value = (Expr){.kind = EX_NUM, .num = x, .loc = loc};
            return;
        }
    }
    bool word = isalpha((unsigned char)*b) || *b == '_';
    for (size_t i = 0; i < n && word; i++) word = isalnum((unsigned char)b[i]) || b[i] == '_';
    *d = (DirArg){.kind = word ? DARG_WORD : DARG_STRING, .text = arena_strndup(a, b, n), .loc = loc};
}

int lang_pafco_cfg_parse(const Source *src, Arena *arena, Diag *diag, FileAst *ast) {
    memset(ast, 0, sizeof *ast);
    int before = diag->errors;
    const char *base;
    size_t bn = file_stem(src->path, &base);
    Model *m = VEC_PUSH(arena, ast->models, ast->nmodels, ast->cap);
    m->kind = SYL_MODEL_PAFCO;
    m->name = arena_strndup(arena, bn ? base : "pafco", bn ? bn : 5);
    m->loc = (SylLoc){1, 1, 1, 1};
    size_t pos = 0;
    Line ln = {0};
    while (next_line(src->text, src->len, &pos, &ln)) {
        if (skipped(&ln)) continue;
        const char *eq;
        size_t n = line_name(&ln, &eq);
        if (!n) {
            diag_error(diag, at(&ln, ln.b, 1), "expected PARAMETER=value (a name in capitals, '=', its value)");
            continue;
        }
        Stmt *s = VEC_PUSH(arena, m->v, m->n, m->cap);
        s->kind = ST_DIRECTIVE;
        s->block = BLOCK_PRODUCE;
        s->name = arena_strndup(arena, ln.b, n);
        s->loc = at(&ln, ln.b, n);
        /* the values: separated by blanks or commas (TEX_SUBORY names several files) */
        for (const char *p = eq + 1; p < ln.e;) {
            while (p < ln.e && (blank(*p) || *p == ',')) p++;
            const char *b = p;
            while (p < ln.e && !blank(*p) && *p != ',') p++;
            if (p > b) value(arena, s, b, (size_t)(p - b), at(&ln, b, (size_t)(p - b)));
        }
    }
    return diag->errors - before;
}
