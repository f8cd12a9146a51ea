/* Sapling's presets (Blender's add_curve_sapling/presets/NAME.py): one Python dictionary
 * literal of the add-on's parameters, read as a `weber` block (docs/arbaro.md#sapling). Sapling
 * is Weber & Penn's model too, so most names map one to one onto Sylva's; the table below is
 * the whole mapping, and what it leaves out is said there. Only literals are read — strings,
 * numbers, True/False/None and tuples of them — so a preset never runs as code. */
#include "lang/sapling.h"
#include "util/file.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct Lex {
    const Source *src;
    size_t at;
    int line, col;
} Lex;

typedef enum { T_END, T_PUNCT, T_STR, T_NUM, T_WORD, T_BAD } TokKind;

typedef struct Tok {
    TokKind kind;
    const char *text; /* into the source: the string's contents, the number, the word */
    size_t len;
    char punct;
    double num;
    SylLoc loc;
} Tok;

static void skip(Lex *l) { /* blanks and # comments */
    while (l->at < l->src->len) {
        char c = l->src->text[l->at];
        if (c == '#') {
            while (l->at < l->src->len && l->src->text[l->at] != '\n') l->at++, l->col++;
        } else if (c == '\n') {
            l->at++, l->line++, l->col = 1;
        } else if (c == ' ' || c == '\t' || c == '\r') {
            l->at++, l->col++;
        } else {
            return;
        }
    }
}

static Tok next(Lex *l) {
    skip(l);
    Tok t = {.loc = {l->line, l->col, l->line, l->col}};
    if (l->at >= l->src->len) return t;
    const char *s = l->src->text + l->at;
    size_t left = l->src->len - l->at, n = 1;
    if (strchr("{}(),:", *s)) {
        t.kind = T_PUNCT, t.punct = *s;
    } else if (*s == '\'' || *s == '"') {
        while (n < left && s[n] != *s && s[n] != '\n' && s[n] != '\\') n++;
        if (n >= left || s[n] != *s) {
            t.kind = T_BAD;
        } else {
            t.kind = T_STR, t.text = s + 1, t.len = n - 1;
            n++;
        }
    } else if (isdigit((unsigned char)*s) || *s == '-' || *s == '+' || *s == '.') {
        char *stop;
        t.num = strtod(s, &stop);
        n = (size_t)(stop - s);
        t.kind = n && n <= left && isfinite(t.num) && !memchr(s, 'x', n) && !memchr(s, 'X', n) ? T_NUM : T_BAD;
        if (!n) n = 1;
    } else if (isalpha((unsigned char)*s) || *s == '_') {
        while (n < left && (isalnum((unsigned char)s[n]) || s[n] == '_')) n++;
        t.kind = T_WORD, t.text = s, t.len = n;
    } else {
        t.kind = T_BAD;
    }
    if (t.kind != T_STR) t.text = t.text ? t.text : s, t.len = t.len ? t.len : n;
    l->at += n, l->col += (int)n;
    t.loc.last_column = l->col - 1;
    return t;
}

bool syl_sapling_detect(const Source *src) {
    Lex l = {.src = src, .line = 1, .col = 1};
    Tok a = next(&l), b = next(&l);
    if (a.kind != T_PUNCT || a.punct != '{' || b.kind != T_STR) return false;
    /* a dictionary literal whose keys are Sapling's: it has its per-level branch counts */
    const char *t = src->text;
    size_t n = src->len;
    static const char key[] = "'branches'", dkey[] = "\"branches\"";
    for (size_t i = 0; i + sizeof key - 1 <= n; i++)
        if (!memcmp(t + i, key, sizeof key - 1) || !memcmp(t + i, dkey, sizeof dkey - 1)) return true;
    return false;
}

/* One value: a scalar (number, string, word) or a tuple of numbers. */
typedef struct Value {
    Tok items[8];
    int n;        /* items (1 for a scalar) */
    bool tuple;
    SylLoc loc;
} Value;

static bool value(Lex *l, Diag *diag, Value *v) {
    Tok t = next(l);
    v->loc = t.loc;
    v->n = 0;
    v->tuple = t.kind == T_PUNCT && (t.punct == '(' || t.punct == '[');
    if (t.kind == T_PUNCT && t.punct == '[') t.punct = '('; /* never written so by Sapling */
    if (!v->tuple) {
        if (t.kind != T_NUM && t.kind != T_STR && t.kind != T_WORD) {
            diag_error(diag, t.loc, "a Sapling preset's value is a number, a string, True or False, or a tuple");
            return false;
        }
        v->items[v->n++] = t;
        return true;
    }
    for (;;) {
        t = next(l);
        if (t.kind == T_PUNCT && t.punct == ')') return true;
        if (t.kind != T_NUM && t.kind != T_WORD) {
            diag_error(diag, t.loc, "a tuple of a Sapling preset holds numbers");
            return false;
        }
        if (v->n == 8) {
            diag_error(diag, t.loc, "a tuple of a Sapling preset holds at most 8 values");
            return false;
        }
        v->items[v->n++] = t;
        t = next(l);
        if (t.kind == T_PUNCT && t.punct == ')') return true;
        if (t.kind != T_PUNCT || t.punct != ',') {
            diag_error(diag, t.loc, "expected ',' or ')' in a tuple");
            return false;
        }
    }
}

/* Sapling's parameter → Sylva's weber directive. PER_LEVEL: a tuple of the 4 levels (Sapling
 * starts at the trunk, as `DownAngle 0 60 45 45` does). SKIP: Sapling's own (its curves'
 * resolution and bevel, armature and wind animation, leaf animation, root flare by another
 * law), read and left out. */
enum { ONE, PER_LEVEL, SHAPE, LEAFSHAPE, ATTRACT, PRUNE, CUSTOM, SKIP };
static const struct {
    const char *sapling, *sylva;
    int how;
} mapping[] = {
    {"levels", "Levels", ONE},           {"scale", "Scale", ONE},
    {"scaleV", "ScaleV", ONE},           {"scale0", "0Scale", ONE},
    {"scaleV0", "0ScaleV", ONE},         {"baseSize", "BaseSize", ONE},
    {"baseSplits", "0BaseSplits", ONE},  {"ratio", "Ratio", ONE},
    {"ratioPower", "RatioPower", ONE},   {"shape", "Shape", SHAPE},
    {"branches", "Branches", PER_LEVEL}, {"length", "Length", PER_LEVEL},
    {"lengthV", "LengthV", PER_LEVEL},   {"taper", "Taper", PER_LEVEL},
    {"curveRes", "CurveRes", PER_LEVEL}, {"curve", "Curve", PER_LEVEL},
    {"curveBack", "CurveBack", PER_LEVEL}, {"curveV", "CurveV", PER_LEVEL},
    {"segSplits", "SegSplits", PER_LEVEL}, {"splitAngle", "SplitAngle", PER_LEVEL},
    {"splitAngleV", "SplitAngleV", PER_LEVEL}, {"downAngle", "DownAngle", PER_LEVEL},
    {"downAngleV", "DownAngleV", PER_LEVEL}, {"rotate", "Rotate", PER_LEVEL},
    {"rotateV", "RotateV", PER_LEVEL},   {"leaves", "Leaves", ONE},
    {"leafScale", "LeafScale", ONE},     {"leafScaleX", "LeafScaleX", ONE},
    {"leafShape", "LeafShape", LEAFSHAPE}, {"attractUp", "AttractionUp", ATTRACT},
    {"pruneRatio", "PruneRatio", PRUNE}, {"pruneWidth", "PruneWidth", ONE},
    {"pruneWidthPeak", "PruneWidthPeak", ONE}, {"prunePowerLow", "PrunePowerLow", ONE},
    {"prunePowerHigh", "PrunePowerHigh", ONE}, {"seed", "Seed", ONE},
    {"splitHeight", "SaplingSplitHeight", ONE}, {"baseSize_s", "SaplingBaseSizeS", ONE},
    {"splitByLen", "SaplingSplitByLen", ONE}, {"branchDist", "SaplingBranchDist", ONE},
    {"nrings", "SaplingRings", ONE},     {"splitBias", "SaplingSplitBias", ONE},
    {"shapeS", "SaplingShapeS", SHAPE},  {"customShape", "SaplingCustom", CUSTOM},
    {"taperCrown", "SaplingTaperCrown", ONE},
};

static Stmt *directive(Arena *a, Model *m, const char *name, SylLoc loc) {
    Stmt *s = VEC_PUSH(a, m->v, m->n, m->cap);
    s->kind = ST_DIRECTIVE;
    s->block = BLOCK_PRODUCE;
    s->name = arena_strndup(a, name, strlen(name));
    s->loc = loc;
    return s;
}

static void number(Arena *a, Stmt *s, double v, SylLoc loc) {
    DirArg *d = VEC_PUSH(a, s->dargs.v, s->dargs.n, s->dargs.cap);
    d->kind = DARG_NUMBER;
    d->text = "";
    d->loc = loc;
    d->value = arena_alloc(a, sizeof *d->value);
    d->value->kind = EX_NUM;
    d->value->num = v;
    d->value->loc = loc;
}

static void word(Arena *a, Stmt *s, const char *w, SylLoc loc) {
    DirArg *d = VEC_PUSH(a, s->dargs.v, s->dargs.n, s->dargs.cap);
    *d = (DirArg){.kind = DARG_WORD, .text = arena_strndup(a, w, strlen(w)), .loc = loc};
}

static bool num_of(const Tok *t, double *v) {
    if (t->kind == T_NUM) return *v = t->num, true;
    if (t->kind == T_WORD && t->len == 4 && !memcmp(t->text, "True", 4)) return *v = 1, true;
    if (t->kind == T_WORD && t->len == 5 && !memcmp(t->text, "False", 5)) return *v = 0, true;
    if (t->kind == T_STR) { /* Sapling keeps some choices as strings of digits: shape '7' */
        char buf[32];
        if (t->len == 0 || t->len >= sizeof buf) return false;
        memcpy(buf, t->text, t->len), buf[t->len] = 0;
        char *stop;
        *v = strtod(buf, &stop);
        return *stop == 0 && isfinite(*v);
    }
    return false;
}

/* What a key's value means depends on other keys, read first wherever they stand. */
typedef struct Context {
    bool prune;               /* Sapling's `prune` switch, which turns pruneRatio on or off */
    double length[4];         /* `length` per level, which lengthV is a share of */
} Context;

/* The number of top-level key `name` (a scalar), from a copy of the lexer; false: none. */
static bool scan_number(Lex scan, const char *name, double *x) {
    size_t n = strlen(name);
    for (Tok t = next(&scan); t.kind != T_END && t.kind != T_BAD; t = next(&scan))
        if (t.kind == T_STR && t.len == n && !memcmp(t.text, name, n)) {
            Tok colon = next(&scan), val = next(&scan);
            return colon.kind == T_PUNCT && colon.punct == ':' && num_of(&val, x);
        }
    return false;
}

/* The numbers of top-level tuple `name` into out[0..3] (left as they are when absent). */
static void scan_tuple(Lex scan, const char *name, double out[4]) {
    size_t n = strlen(name);
    for (Tok t = next(&scan); t.kind != T_END && t.kind != T_BAD; t = next(&scan))
        if (t.kind == T_STR && t.len == n && !memcmp(t.text, name, n)) {
            Tok colon = next(&scan), open = next(&scan);
            if (colon.kind != T_PUNCT || colon.punct != ':' || open.kind != T_PUNCT || open.punct != '(') return;
            for (int i = 0; i < 4; i++) {
                Tok v = next(&scan);
                if (!num_of(&v, &out[i])) return;
                Tok sep = next(&scan);
                if (sep.kind != T_PUNCT || sep.punct != ',') return;
            }
            return;
        }
}

/* One key and value into the model: the mapping's directive, or nothing. */
static void put(Arena *a, Diag *diag, Model *m, const Tok *key, const Value *v, const Context *cx) {
    bool prune = cx->prune;
    int k = -1;
    for (size_t i = 0; i < sizeof mapping / sizeof *mapping; i++)
        if (strlen(mapping[i].sapling) == key->len && !memcmp(mapping[i].sapling, key->text, key->len)) k = (int)i;
    if (k < 0) return; /* Sapling's own: its curves, armature, wind and animation */
    int how = mapping[k].how;
    if (how == CUSTOM) { /* its custom shape's four values: base, middle, where the middle is, tip */
        static const char *const part[] = {"SaplingCustomBase", "SaplingCustomMid", "SaplingCustomPeak", "SaplingCustomTip"};
        double c;
        for (int i = 0; i < v->n && i < 4; i++)
            if (num_of(&v->items[i], &c)) number(a, directive(a, m, part[i], key->loc), c, v->items[i].loc);
        return;
    }
    if ((how == PER_LEVEL) != v->tuple && how != ATTRACT) { /* attractUp: a tuple since Sapling 0.3, one value before */
        diag_error(diag, v->loc, "Sapling's '%s' is %s", mapping[k].sapling,
                   v->tuple ? "one value, not a tuple" : "a tuple of one value per level");
        return;
    }
    double x;
    if (how == LEAFSHAPE) { /* hexagons and rectangles: Sylva's disc and square */
        const Tok *t = &v->items[0];
        const char *shape = t->kind == T_STR && t->len == 4 && !memcmp(t->text, "rect", 4) ? "square" : "disc";
        word(a, directive(a, m, "LeafShape", key->loc), shape, v->loc);
        return;
    }
    if (how == ATTRACT) { /* one value per level in Sapling; Weber–Penn's is one: the last level's that is set */
        double last = 0;
        for (int i = 0; i < v->n; i++)
            if (num_of(&v->items[i], &x) && x != 0) last = x;
        number(a, directive(a, m, "AttractionUp", key->loc), last, v->loc);
        return;
    }
    Stmt *s = directive(a, m, mapping[k].sylva, key->loc);
    for (int i = 0; i < v->n; i++) {
        if (!num_of(&v->items[i], &x)) {
            diag_error(diag, v->items[i].loc, "Sapling's '%s' takes numbers", mapping[k].sapling);
            return;
        }
        if (how == PRUNE && !prune) x = 0; /* pruning off: no envelope */
        /* Sapling's lengthV is a share of the level's length, Weber & Penn's LengthV a length */
        if (how == PER_LEVEL && !strcmp(mapping[k].sylva, "LengthV")) x *= cx->length[i < 4 ? i : 3];
        /* Sapling's trunk count: 0 there means one trunk, Weber & Penn's 0Branches is 1 */
        if (how == PER_LEVEL && i == 0 && !strcmp(mapping[k].sylva, "Branches") && x < 1) x = 1;
        number(a, s, x, v->items[i].loc);
    }
}

int syl_sapling_parse(const Source *src, Arena *arena, Diag *diag, FileAst *ast) {
    memset(ast, 0, sizeof *ast);
    int before = diag->errors;
    Lex l = {.src = src, .line = 1, .col = 1};
    Tok open = next(&l);
    /* the model's name: the preset's file name without folder and extension */
    const char *base;
    size_t bn = file_stem(src->path, &base);
    Model *m = VEC_PUSH(arena, ast->models, ast->nmodels, ast->cap);
    m->kind = SYL_MODEL_WEBER;
    m->name = arena_strndup(arena, bn ? base : "sapling", bn ? bn : 7);
    m->loc = open.loc;
    word(arena, directive(arena, m, "convention", open.loc), "arbaro", open.loc);
    /* Sapling's own laws of how many children, splits and tip stems (weber/sapling.c) */
    number(arena, directive(arena, m, "SaplingLaw", open.loc), 1, open.loc);
    /* read first, wherever it stands: `prune` for pruneRatio */
    Context cx = {.prune = true, .length = {1, 1, 1, 1}};
    double x;
    if (scan_number(l, "prune", &x)) cx.prune = x != 0;
    scan_tuple(l, "length", cx.length);
    for (;;) {
        Tok key = next(&l);
        if (key.kind == T_PUNCT && key.punct == '}') break;
        if (key.kind != T_STR) {
            diag_error(diag, key.loc, key.kind == T_END ? "the preset ends before its closing '}'"
                                                         : "expected a parameter's name in quotes");
            break;
        }
        Tok colon = next(&l);
        if (colon.kind != T_PUNCT || colon.punct != ':') {
            diag_error(diag, colon.loc, "expected ':' after a parameter's name");
            break;
        }
        Value v;
        if (!value(&l, diag, &v)) break;
        put(arena, diag, m, &key, &v, &cx);
        Tok sep = next(&l);
        if (sep.kind == T_PUNCT && sep.punct == '}') break;
        if (sep.kind != T_PUNCT || sep.punct != ',') {
            diag_error(diag, sep.loc, "expected ',' or '}' after a value");
            break;
        }
    }
    if (diag->errors == before) {
        Tok rest = next(&l);
        if (rest.kind != T_END) diag_error(diag, rest.loc, "text after the preset's closing '}'");
    }
    return diag->errors - before;
}
