/* Pícek's plant files (docs/language.md §18): read into the syntax tree a .syl model makes. */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lang/parse_state.h"

/* The keys of a Pícek file, in the order the thesis's grammar gives them. */
enum { K_ITERATION, K_ANGLE, K_REDUCTION, K_RADIUS, K_THICKNESS, K_AXIOM, K_RULE, K_COUNT };
static const char *const keys[K_COUNT] = {"iteration", "angle", "reduction", "radius", "thickness", "axiom", "rule"};

/* The L-system characters besides letters and digits: Table 3.1's turtle symbols. */
static const char symbols[] = "+-&^/\\|[]";

static int key_of(const char *s, size_t n) {
    for (int k = 0; k < K_COUNT; k++)
        if (strlen(keys[k]) == n && !memcmp(keys[k], s, n)) return k;
    return -1;
}

static bool blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

/* One line without its comment and its surrounding blanks: [b, e) of the text, columns from 1. */
typedef struct Line {
    const char *b, *e, *start; /* start: the line's first byte, for columns */
    int no;
} Line;

static bool next_line(const Source *src, size_t *pos, Line *ln) {
    if (*pos >= src->len) return false;
    const char *t = src->text, *p = t + *pos, *end = t + src->len;
    const char *nl = memchr(p, '\n', (size_t)(end - p));
    const char *stop = nl ? nl : end;
    ln->start = p;
    const char *c = memchr(p, ';', (size_t)(stop - p));
    ln->e = c ? c : stop;
    ln->b = p;
    while (ln->b < ln->e && blank(*ln->b)) ln->b++;
    while (ln->e > ln->b && blank(ln->e[-1])) ln->e--;
    ln->no++;
    *pos = (size_t)(stop - t) + (nl ? 1 : 0);
    return true;
}

static SylLoc at(const Line *ln, const char *p, size_t n) {
    int col = (int)(p - ln->start) + 1;
    return (SylLoc){ln->no, col, ln->no, col + (int)(n ? n - 1 : 0)};
}

/* The key that opens a line ("angle" of `angle: 30`) and the text after its colon, or -1. */
static int line_key(const Line *ln, const char **rest) {
    const char *p = ln->b;
    while (p < ln->e && isalpha((unsigned char)*p)) p++;
    int k = key_of(ln->b, (size_t)(p - ln->b));
    while (p < ln->e && blank(*p)) p++;
    if (k < 0 || p >= ln->e || *p != ':') return -1;
    *rest = p + 1;
    return k;
}

bool syl_picek_detect(const Source *src) {
    size_t pos = 0;
    Line ln = {0};
    while (next_line(src, &pos, &ln)) {
        if (ln.b == ln.e) continue;
        const char *rest;
        return line_key(&ln, &rest) >= 0;
    }
    return false;
}

typedef struct Reader {
    Arena *arena;
    Diag *diag;
    Model *m;
} Reader;

static Stmt *add(Reader *r, StmtKind kind, SylLoc loc) {
    Stmt *s = VEC_PUSH(r->arena, r->m->v, r->m->n, r->m->cap);
    s->kind = kind;
    s->loc = loc;
    s->block = BLOCK_PRODUCE;
    return s;
}

static Expr *num(Reader *r, double v, SylLoc loc) {
    Expr *e = arena_alloc(r->arena, sizeof *e);
    e->kind = EX_NUM;
    e->num = v;
    e->loc = loc;
    return e;
}

static void setting(Reader *r, const char *name, double v, SylLoc loc) {
    Stmt *s = add(r, ST_SETTING, loc);
    s->name = name;
    *VEC_PUSH(r->arena, s->args.v, s->args.n, s->args.cap) = num(r, v, loc);
}

static Item item(Reader *r, ItemKind kind, const char *text, size_t n, SylLoc loc) {
    Item it;
    memset(&it, 0, sizeof it);
    it.kind = kind;
    it.text = arena_strndup(r->arena, text, n);
    it.loc = loc;
    return it;
}

/* One L-system character as a module item; false (reported) when it is none. */
static bool character(Reader *r, const Line *ln, const char *p, Item *out) {
    unsigned char c = (unsigned char)*p;
    if (isalpha(c)) *out = item(r, IT_WORD, p, 1, at(ln, p, 1));
    else if (isdigit(c)) *out = item(r, IT_DIGITS, p, 1, at(ln, p, 1));
    else if (c && strchr(symbols, c)) *out = item(r, IT_SYMBOL, p, 1, at(ln, p, 1));
    else {
        size_t n = 1;
        while (c >= 0xc0 && p + n < ln->e && ((unsigned char)p[n] & 0xc0) == 0x80) n++;
        char shown[64];
        diag_error(r->diag, at(ln, p, 1),
                   "'%s' is not an L-system character of a Pícek file (letters, digits, + - & ^ / \\ | [ ])",
                   diag_quote(shown, sizeof shown, p, n));
        return false;
    }
    return true;
}

/* The characters of [p, e), blanks between them skipped; false when one was wrong. */
static bool word(Reader *r, const Line *ln, const char *p, const char *e, Items *out) {
    memset(out, 0, sizeof *out);
    bool ok = true;
    for (; p < e; p++) {
        if (blank(*p)) continue;
        Item it;
        if (character(r, ln, p, &it)) *VEC_PUSH(r->arena, out->v, out->n, out->cap) = it;
        else ok = false;
        if ((unsigned char)*p >= 0xc0)
            while (p + 1 < e && ((unsigned char)p[1] & 0xc0) == 0x80) p++;
    }
    return ok;
}

/* A number filling [p, e): iteration's a whole one of at most 1e6 steps. */
static bool number(Reader *r, const Line *ln, int k, const char *p, const char *e, double *v) {
    while (p < e && blank(*p)) p++;
    char buf[64];
    size_t n = (size_t)(e - p);
    char *stop = NULL;
    if (n && n < sizeof buf) {
        memcpy(buf, p, n);
        buf[n] = 0;
        *v = strtod(buf, &stop);
    }
    bool whole = k != K_ITERATION || (*v >= 0 && *v <= 1e6 && *v == floor(*v));
    if (n && n < sizeof buf && stop == buf + n && isfinite(*v) && whole && (k == K_ANGLE || *v >= 0)) return true;
    diag_error(r->diag, at(ln, p < e ? p : e - 1, n ? n : 1), "'%s:' takes %s", keys[k],
               k == K_ITERATION ? "a whole number of steps (0 to 1000000)"
               : k == K_ANGLE   ? "a number of degrees"
                                : "a number, 0 or more");
    return false;
}

/* `rule: A -> successor`: one character, an arrow, the successor. */
static void rule(Reader *r, const Line *ln, const char *p, int **rules, int *nrules, int *cap) {
    while (p < ln->e && blank(*p)) p++;
    const char *arrow = NULL;
    for (const char *q = p; q + 1 < ln->e && !arrow; q++)
        if (q[0] == '-' && q[1] == '>') arrow = q;
    if (!arrow) {
        diag_error(r->diag, at(ln, ln->e > p ? ln->e - 1 : p, 1), "a rule is 'rule: A -> successor': '->' missing");
        return;
    }
    const char *pe = arrow;
    while (pe > p && blank(pe[-1])) pe--;
    if (pe - p != 1) {
        diag_error(r->diag, at(ln, p < pe ? p : arrow, p < pe ? (size_t)(pe - p) : 2),
                   "the predecessor of a Pícek rule is one character");
        return;
    }
    Production pr;
    memset(&pr, 0, sizeof pr);
    Item it;
    if (!character(r, ln, p, &it)) return;
    *VEC_PUSH(r->arena, pr.pred.v, pr.pred.n, pr.pred.cap) = it;
    if (!word(r, ln, arrow + 2, ln->e, &pr.succ)) return;
    pr.loc = it.loc;
    pr.arrow_loc = at(ln, arrow, 2);
    add(r, ST_RULE, pr.loc)->rule = pr;
    *VEC_PUSH(r->arena, *rules, *nrules, *cap) = r->m->n - 1;
}

/* The model's name: the file's, without folders and extension, made a name. */
static const char *model_name(Arena *a, const char *path) {
    const char *b = path ? strrchr(path, '/') : NULL;
    b = b ? b + 1 : path ? path : "";
    size_t n = strcspn(b, ".");
    char *s = arena_strndup(a, b, n);
    for (size_t i = 0; i < n; i++)
        if (!isalnum((unsigned char)s[i]) && s[i] != '_') s[i] = '_';
    return n && !isdigit((unsigned char)s[0]) ? s : "picek";
}

/* An interpret rule `pred -> succ…` (one-character predecessor) that the turtle alone sees. */
static void interpret(Reader *r, const char *pred, const Item *succ, int n, SylLoc loc) {
    Stmt *s = add(r, ST_RULE, loc);
    s->block = BLOCK_INTERPRET;
    Production *p = &s->rule;
    p->loc = p->arrow_loc = loc;
    *VEC_PUSH(r->arena, p->pred.v, p->pred.n, p->pred.cap) =
        item(r, isalpha((unsigned char)*pred) ? IT_WORD : IT_SYMBOL, pred, 1, loc);
    for (int j = 0; j < n; j++) *VEC_PUSH(r->arena, p->succ.v, p->succ.n, p->succ.cap) = succ[j];
}

/* The first item of items named name, or NULL. */
static const Item *first_of(const Items *items, const char *name) {
    for (int i = 0; i < items->n; i++)
        if (!strcmp(items->v[i].text, name)) return &items->v[i];
    return NULL;
}

/* The first item named name in the axiom or a successor, or NULL. */
static const Item *first_in(const Model *m, const int *rules, int nrules, const char *name) {
    const Item *it = NULL;
    for (int i = 0; i < m->n && !it; i++)
        if (m->v[i].kind == ST_AXIOM) it = first_of(&m->v[i].items, name);
    for (int i = 0; i < nrules && !it; i++) it = first_of(&m->v[rules[i]].rule.succ, name);
    return it;
}

/* Table 2.2 rolls left with `/` and right with `\`, the other way round from ABOP and Sylva: the
 * interpret rule `/ -> \\(angle)` (and back) turns the file's roll into Sylva's. The successor
 * has a parameter, so a second pass matches it no more. */
static void roll(Reader *r, const Model *m, const int *rules, int nrules, const char *sym, const char *as,
                 double angle) {
    const Item *at = first_in(m, rules, nrules, sym);
    if (!at) return;
    SylLoc loc = at->loc; /* copied: the rule's statement may move m->v */
    Item to = item(r, IT_SYMBOL, as, 1, loc);
    to.parens = true;
    *VEC_PUSH(r->arena, to.args.v, to.args.n, to.args.cap) = num(r, angle, loc);
    interpret(r, sym, &to, 1, loc);
}

int syl_picek_parse(const Source *src, Arena *arena, Diag *diag, FileAst *ast) {
    memset(ast, 0, sizeof *ast);
    int before = diag->errors;
    Model *m = VEC_PUSH(arena, ast->models, ast->nmodels, ast->cap);
    m->kind = SYL_MODEL_LSYSTEM;
    m->name = model_name(arena, src->path);
    m->loc = (SylLoc){1, 1, 1, 1};
    Reader r = {arena, diag, m};
    SylLoc seen[K_COUNT] = {{0}};
    double value[K_COUNT] = {0};
    int *rules = NULL, nrules = 0, cap = 0; /* statement indices: m->v moves as it grows */
    size_t pos = 0;
    Line ln = {0};
    while (next_line(src, &pos, &ln)) {
        if (ln.b == ln.e) continue;
        const char *rest;
        int k = line_key(&ln, &rest);
        if (k < 0) {
            const char *w = ln.b;
            while (w < ln.e && !blank(*w) && *w != ':') w++;
            diag_error(diag, at(&ln, ln.b, (size_t)(w > ln.b ? w - ln.b : 1)),
                       "a line of a Pícek file is 'iteration:', 'angle:', 'reduction:', 'radius:', "
                       "'thickness:', 'axiom:' or 'rule:' and its value (';' starts a comment)");
            continue;
        }
        SylLoc loc = at(&ln, ln.b, (size_t)(rest - ln.b));
        if (k != K_RULE && seen[k].first_line) {
            diag_error(diag, loc, "'%s:' is given twice (first at line %d)", keys[k], seen[k].first_line);
            continue;
        }
        if (k == K_RULE) rule(&r, &ln, rest, &rules, &nrules, &cap);
        else if (k == K_AXIOM) {
            Items items;
            if (word(&r, &ln, rest, ln.e, &items)) {
                if (!items.n) diag_error(diag, loc, "'axiom:' needs at least one character");
                else add(&r, ST_AXIOM, loc)->items = items;
            }
        } else if (number(&r, &ln, k, rest, ln.e, &value[k])) {
            static const char *const name[K_COUNT] = {"derive", "angle", NULL, "width", "width"};
            if ((k == K_RADIUS || k == K_THICKNESS) && (seen[K_RADIUS].first_line || seen[K_THICKNESS].first_line))
                diag_error(diag, loc, "'radius:' and 'thickness:' both set the first width: give one");
            else if (name[k])
                setting(&r, name[k], k == K_RADIUS ? 2 * value[k] : value[k], loc);
        }
        seen[k] = loc;
    }
    if (!seen[K_AXIOM].first_line && diag->errors == before)
        diag_error(diag, m->loc, "a Pícek file needs an 'axiom:' line");
    /* A uniform choice among the rules that share a predecessor: each weighs 1. */
    int share[256] = {0}; /* rules per predecessor, a single byte */
    for (int i = 0; i < nrules; i++) share[(unsigned char)m->v[rules[i]].rule.pred.v[0].text[0]]++;
    for (int i = 0; i < nrules; i++) {
        Production *pi = &m->v[rules[i]].rule;
        if (share[(unsigned char)pi->pred.v[0].text[0]] > 1) pi->weight = num(&r, 1, pi->arrow_loc);
    }
    /* The thesis's turtle draws `L` as a leaf and tapers every segment by `reduction`: interpret
     * rules say so to Sylva's, and leave the derived string as the file makes it. */
    const Item *leaf = first_in(m, rules, nrules, "L");
    if (leaf) {
        SylLoc loc = leaf->loc; /* copied: the rule's statement may move m->v */
        interpret(&r, "L", (Item[]){item(&r, IT_SYMBOL, "~leaf", 5, loc)}, 1, loc);
    }
    if (seen[K_REDUCTION].first_line && value[K_REDUCTION] != 1) {
        SylLoc loc = seen[K_REDUCTION];
        setting(&r, "widthfactor", value[K_REDUCTION], loc);
        interpret(&r, "F", (Item[]){item(&r, IT_WORD, "G", 1, loc), item(&r, IT_SYMBOL, "!", 1, loc)}, 2, loc);
    }
    double angle = seen[K_ANGLE].first_line ? value[K_ANGLE] : 45; /* Sylva's default angle */
    roll(&r, m, rules, nrules, "/", "\\", angle);
    roll(&r, m, rules, nrules, "\\", "/", angle);
    return diag->errors - before;
}
