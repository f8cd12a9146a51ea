/* Arbaro's XML species files and Helios's WeberPennTreeLibrary.xml, read with libxml2 into
 * weber models (docs/arbaro.md), and grow presets (<grow-presets>, docs/growth.md#presets) into
 * grow models. Each parameter becomes a directive line at its element's XML
 * line, so that the weber reader reports a bad value or an unknown name where the XML has it.
 * libxml2 reads with no network, no DTD (a DOCTYPE stops the parse: no entity is declared,
 * so none can expand) and its default depth limit; the file's size is capped before. */
#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>

#include "util/lazy_xml.h"

#include "lang/arbaro.h"
#include "lang/textures.h"

static bool blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

bool syl_arbaro_detect(const Source *src) {
    static const char *const heads[] = {"<?xml", "<!--", "<arbaro", "<helios", ("<" SYL_GROW_PRESET_ROOT)};
    size_t i = 0;
    while (i < src->len && blank(src->text[i])) i++;
    for (size_t k = 0; k < sizeof heads / sizeof *heads; k++) {
        size_t n = strlen(heads[k]);
        if (src->len - i >= n && !memcmp(src->text + i, heads[k], n)) return true;
    }
    return false;
}

typedef struct Reader {
    const Source *src;
    Arena *arena;
    Diag *diag;
    FileAst *ast;
    size_t *lines; /* offset of each line's start; lines[0] is line 1's */
    int nlines;
    /* what libxml2 said first, and whether a DOCTYPE stopped it */
    bool failed, doctype;
    int err_line, err_col;
    char message[512];
} Reader;

/* ---- lines and columns in the source ---- */

static void index_lines(Reader *r) {
    int n = 1;
    for (size_t i = 0; i < r->src->len; i++) n += r->src->text[i] == '\n';
    r->lines = arena_alloc(r->arena, sizeof *r->lines * (size_t)n);
    r->nlines = 0;
    r->lines[r->nlines++] = 0;
    for (size_t i = 0; i < r->src->len; i++)
        if (r->src->text[i] == '\n') r->lines[r->nlines++] = i + 1;
}

/* Line no's text [*b, *e) (no newline); false when there is no such line. */
static bool line_text(const Reader *r, int no, const char **b, const char **e) {
    if (no < 1 || no > r->nlines) return false;
    *b = r->src->text + r->lines[no - 1];
    const char *end = r->src->text + r->src->len;
    const char *nl = memchr(*b, '\n', (size_t)(end - *b));
    *e = nl ? nl : end;
    return true;
}

static const char *find(const char *b, const char *e, const char *s, size_t n) {
    return n && (size_t)(e - b) >= n ? memmem(b, (size_t)(e - b), s, n) : NULL;
}

/* name in quotes in [b, e) (an attribute's value: `'Shape'`, not the Shape of `'LeafShape'`). */
static const char *quoted(const char *b, const char *e, const char *name, size_t n) {
    const char *p = find(b, e, name, n);
    while (p && !(p > b && (p[-1] == '\'' || p[-1] == '"') && p + n < e && p[n] == p[-1])) p = find(p + 1, e, name, n);
    return p;
}

/* Where the first character of a value stands in its line: after `value=` and its quote
 * (following the quoted name, for a <param>), or after the `>` of `<Name>` (Helios);
 * NULL when the line does not show it (written over several lines, or with references). */
static const char *value_start(const Reader *r, int line, const char *name, bool attribute) {
    const char *b, *e;
    if (!line_text(r, line, &b, &e)) return NULL;
    size_t n = strlen(name);
    if (!attribute) {
        const char *p = b;
        while ((p = find(p, e, name, n)) && !(p > b && p[-1] == '<')) p++;
        if (!p) return NULL;
        p = memchr(p, '>', (size_t)(e - p));
        if (!p) return NULL;
        for (p++; p < e && blank(*p); p++) {}
        return p;
    }
    const char *p = quoted(b, e, name, n);
    p = find(p ? p : b, e, "value", 5);
    if (!p) return NULL;
    p += 5;
    while (p < e && blank(*p)) p++;
    if (p >= e || *p != '=') return NULL;
    for (p++; p < e && blank(*p); p++) {}
    if (p >= e || (*p != '\'' && *p != '"')) return NULL;
    return p + 1;
}

static int column(const Reader *r, int line, const char *at) {
    return (int)(at - (r->src->text + r->lines[line - 1])) + 1;
}

/* ---- building the tree ---- */

static Stmt *add(Reader *r, Model *m, const char *name, int line, int col) {
    Stmt *s = VEC_PUSH(r->arena, m->v, m->n, m->cap);
    s->kind = ST_DIRECTIVE;
    s->block = BLOCK_PRODUCE;
    s->name = arena_strndup(r->arena, name, strlen(name));
    s->loc = (SylLoc){line, col, line, col + (int)strlen(name) - (name[0] != 0)};
    return s;
}

static Expr *number_expr(Reader *r, double v, SylLoc loc) {
    Expr *e = arena_alloc(r->arena, sizeof *e);
    memset(e, 0, sizeof *e);
    e->kind = EX_NUM;
    e->num = v;
    e->loc = loc;
    return e;
}

/* s[0..n) as a finite decimal number. */
static bool decimal(const char *s, size_t n, double *v) {
    char buf[64];
    if (!n || n >= sizeof buf || memchr(s, 'x', n) || memchr(s, 'X', n) || memchr(s, 'p', n) || memchr(s, 'P', n))
        return false;
    memcpy(buf, s, n);
    buf[n] = 0;
    char *stop;
    *v = strtod(buf, &stop);
    return stop == buf + n && isfinite(*v) && !blank(buf[0]);
}

/* A grow preset's `(x,y,z)` or `~leaf(0.06)` (preset.c writes them without blanks): its
 * numbers into a's list; false when one is not a number or the parentheses do not close. */
static bool number_list(Reader *r, DirArg *a, const char *open, const char *end) {
    if (*open != '(' || end[-1] != ')') return false;
    for (const char *p = open + 1; p < end;) {
        const char *q = p;
        while (q < end - 1 && *q != ',') q++;
        double v;
        if (!decimal(p, (size_t)(q - p), &v)) return false;
        *VEC_PUSH(r->arena, a->args.v, a->args.n, a->args.cap) = number_expr(r, v, a->loc);
        p = q + 1;
    }
    return true;
}

/* A value word: a number when strtod reads all of it as a finite decimal, a tuple or a
 * symbol as a grow preset writes them, else a word (LeafShape disc2; the weber reader says
 * what a parameter takes). */
static void argument(Reader *r, Stmt *s, const char *tok, size_t n, SylLoc loc) {
    DirArg *a = VEC_PUSH(r->arena, s->dargs.v, s->dargs.n, s->dargs.cap);
    a->text = arena_strndup(r->arena, tok, n);
    a->loc = loc;
    double v;
    const char *paren = memchr(tok, '(', n);
    if (decimal(tok, n, &v)) {
        a->kind = DARG_NUMBER;
        a->value = number_expr(r, v, loc);
    } else if (n > 2 && tok[0] == '(' && number_list(r, a, tok, tok + n)) {
        a->kind = DARG_TUPLE;
        a->text = "(";
    } else if (n > 1 && tok[0] == '~' && (!paren || number_list(r, a, paren, tok + n))) {
        a->kind = DARG_SYMBOL;
        a->text = arena_strndup(r->arena, tok, paren ? (size_t)(paren - tok) : n);
    } else {
        a->args.n = 0;
        a->kind = DARG_WORD;
    }
}

/* The value's words, each at its column when the line shows it (else at the value's). */
static void arguments(Reader *r, Stmt *s, const char *value, int line, const char *start) {
    const char *b = NULL, *e = NULL;
    line_text(r, line, &b, &e);
    const char *from = start;
    int vcol = start ? column(r, line, start) : 1;
    for (const char *p = value; *p;) {
        while (*p && blank(*p)) p++;
        if (!*p) break;
        const char *q = p;
        while (*q && !blank(*q)) q++;
        size_t n = (size_t)(q - p);
        const char *at = from ? find(from, e, p, n) : NULL;
        int col = at ? column(r, line, at) : vcol;
        if (at) from = at + n;
        argument(r, s, p, n, (SylLoc){line, col, line, col + (int)n - 1});
        p = q;
    }
}

static int line_of(xmlNodePtr n) {
    long l = xmlGetLineNo(n);
    return l > 0 && l <= INT_MAX ? (int)l : 1;
}

static SylLoc element_loc(const Reader *r, xmlNodePtr n) {
    int line = line_of(n), col = 1;
    const char *b, *e, *at;
    if (line_text(r, line, &b, &e) && (at = find(b, e, (const char *)n->name, strlen((const char *)n->name))) &&
        at > b && at[-1] == '<')
        col = (int)(at - b);
    return (SylLoc){line, col, line, col};
}

static bool named(xmlNodePtr n, const char *name) {
    return n->type == XML_ELEMENT_NODE && !strcmp((const char *)n->name, name);
}

/* An attribute's value copied into the arena (NULL when absent). */
static const char *attr(Reader *r, xmlNodePtr n, const char *name) {
    xmlChar *v = xmlGetProp(n, (const xmlChar *)name);
    if (!v) return NULL;
    const char *s = arena_strndup(r->arena, (const char *)v, strlen((const char *)v));
    xmlFree(v);
    return s;
}

static Model *model(Reader *r, xmlNodePtr n, const char *name, SylModelKind kind) {
    Model *m = VEC_PUSH(r->arena, r->ast->models, r->ast->nmodels, r->ast->cap);
    m->kind = kind;
    m->name = name;
    m->loc = element_loc(r, n);
    return m;
}

/* An element that holds no model's parameter: text other than blanks is a mistake. */
static void stray_text(Reader *r, xmlNodePtr n, const char *where) {
    if (n->type != XML_TEXT_NODE && n->type != XML_CDATA_SECTION_NODE) return;
    for (const xmlChar *c = n->content; c && *c; c++)
        if (!blank((char)*c)) {
            diag_error(r->diag, element_loc(r, n->parent), "text is not read inside %s: parameters are elements",
                       where);
            return;
        }
}

/* <bark file='F' tile='U V'/> or <leaf_texture file='F'/> (lang_textures_xml writes them;
 * Arbaro's reader skips elements other than <param>): a texture line, the images of
 * <leaf_texture> elements in a row one line. */
static void texture_element(Reader *r, Model *m, xmlNodePtr n, SylLoc loc) {
    const char *el = (const char *)n->name, *file = attr(r, n, "file"), *tile = attr(r, n, "tile");
    bool bark = !strcmp(el, "bark");
    if (!file || !*file || (tile && !bark)) {
        diag_error(r->diag, loc, bark ? "a <bark> needs a file attribute (and may have tile='U V')"
                                      : "a <%s> needs a file attribute, and no other", el);
        return;
    }
    Stmt *last = m->n ? &m->v[m->n - 1] : NULL, *s = last;
    if (bark || !last || strcmp(last->name, el) || !last->dargs.n || last->dargs.v[0].kind != DARG_STRING)
        s = add(r, m, el, loc.first_line, loc.first_column + 1);
    DirArg *a = VEC_PUSH(r->arena, s->dargs.v, s->dargs.n, s->dargs.cap);
    *a = (DirArg){.kind = DARG_STRING, .text = file, .loc = loc};
    if (tile) {
        a = VEC_PUSH(r->arena, s->dargs.v, s->dargs.n, s->dargs.cap);
        *a = (DirArg){.kind = DARG_WORD, .text = "tile", .loc = loc};
        arguments(r, s, tile, loc.first_line, NULL);
    }
}

/* <species name='…'> holding <param name='…' value='…'/>: Arbaro's conventions, which grow
 * presets follow (a directive's name and its words). */
static void species(Reader *r, xmlNodePtr sp, SylModelKind kind) {
    const char *name = attr(r, sp, "name");
    if (!name || !*name) {
        diag_error(r->diag, element_loc(r, sp), "a <species> needs a name attribute (the model's name)");
        return;
    }
    Model *m = model(r, sp, name, kind);
    if (kind == SYL_MODEL_WEBER) {
        Stmt *conv = add(r, m, "convention", m->loc.first_line, m->loc.first_column);
        DirArg *a = VEC_PUSH(r->arena, conv->dargs.v, conv->dargs.n, conv->dargs.cap);
        *a = (DirArg){.kind = DARG_WORD, .text = "arbaro", .loc = m->loc};
    }
    for (xmlNodePtr n = sp->children; n; n = n->next) {
        stray_text(r, n, "a <species>");
        if (n->type != XML_ELEMENT_NODE) continue;
        SylLoc loc = element_loc(r, n);
        if (lang_texture_line((const char *)n->name)) {
            texture_element(r, m, n, loc);
            continue;
        }
        if (!named(n, "param")) {
            char shown[64];
            diag_error(r->diag, loc, "a <species> holds <param name=… value=…/> elements, not <%s>",
                       diag_quote(shown, sizeof shown, (const char *)n->name, strlen((const char *)n->name)));
            continue;
        }
        const char *pname = attr(r, n, "name"), *value = attr(r, n, "value");
        if (!pname || !*pname || !value) {
            diag_error(r->diag, loc, "a <param> needs a name and a value attribute");
            continue;
        }
        const char *b, *e, *at = NULL;
        if (line_text(r, loc.first_line, &b, &e)) at = quoted(b, e, pname, strlen(pname));
        Stmt *s = add(r, m, pname, loc.first_line, at ? column(r, loc.first_line, at) : loc.first_column);
        arguments(r, s, value, loc.first_line, value_start(r, loc.first_line, pname, true));
    }
}

/* Helios's names: its per-level lists are `nLength` (Sylva's `Length` list), its base splits
 * `BaseSplits`; its own extras (files and colours of its renderer, and split sizes its
 * generator alone reads) are skipped. */
static const char *const helios_skipped[] = {"LeafFile",   "WoodFile",      "WoodColor",      "LeafAngleDist",
                                             "BaseSplitSize", "BaseSplitSizeV", "BaseSizeV", "BaseSplitsV"};

static void helios_tree(Reader *r, xmlNodePtr t) {
    const char *name = attr(r, t, "label");
    if (!name || !*name) {
        diag_error(r->diag, element_loc(r, t), "a <WeberPennTree> needs a label attribute (the model's name)");
        return;
    }
    Model *m = model(r, t, name, SYL_MODEL_WEBER);
    for (xmlNodePtr n = t->children; n; n = n->next) {
        stray_text(r, n, "a <WeberPennTree>");
        if (n->type != XML_ELEMENT_NODE) continue;
        const char *el = (const char *)n->name;
        bool skip = false;
        for (size_t k = 0; k < sizeof helios_skipped / sizeof *helios_skipped; k++) skip |= !strcmp(el, helios_skipped[k]);
        if (skip) continue;
        const char *pname = !strcmp(el, "BaseSplits")                                   ? "0BaseSplits"
                            : el[0] == 'n' && isupper((unsigned char)el[1]) ? el + 1
                                                                                          : el;
        SylLoc loc = element_loc(r, n);
        xmlChar *content = xmlNodeGetContent(n);
        const char *value = content ? arena_strndup(r->arena, (const char *)content, strlen((const char *)content)) : "";
        xmlFree(content);
        Stmt *s = add(r, m, pname, loc.first_line, loc.first_column + 1);
        arguments(r, s, value, loc.first_line, value_start(r, loc.first_line, el, false));
    }
}

/* ---- libxml2 ---- */

static void on_error(void *user, xmlErrorPtr e) {
    Reader *r = ((xmlParserCtxtPtr)user)->_private;
    if (!r || r->failed || e->level < XML_ERR_ERROR) return;
    r->failed = true;
    r->err_line = e->line;
    r->err_col = e->int2;
    snprintf(r->message, sizeof r->message, "%s", e->message ? e->message : "malformed XML");
    size_t n = strlen(r->message);
    while (n && blank(r->message[n - 1])) r->message[--n] = 0;
}

static void on_doctype(void *user, const xmlChar *name, const xmlChar *ext, const xmlChar *sys) {
    (void)name, (void)ext, (void)sys;
    xmlParserCtxtPtr ctxt = user;
    Reader *r = ctxt->_private;
    if (r && !r->failed) {
        r->doctype = r->failed = true;
        r->err_line = xmlSAX2GetLineNumber(ctxt);
        r->err_col = 1;
    }
    xmlStopParser(ctxt);
}

/* Helios's file opens with `<?xml version=1.0?>`, unquoted: blanked (its line kept), as
 * Helios's own reader takes it. */
static char *helios_prolog(Reader *r, size_t *len) {
    const char *t = r->src->text;
    size_t i = 0;
    while (i < r->src->len && blank(t[i])) i++;
    static const char bad[] = "<?xml version=1.0?>";
    if (r->src->len - i < sizeof bad - 1 || memcmp(t + i, bad, sizeof bad - 1)) return NULL;
    char *copy = arena_strndup(r->arena, t, r->src->len);
    memset(copy + i, ' ', sizeof bad - 1);
    *len = r->src->len;
    return copy;
}

static void report_libxml(Reader *r) {
    if (r->doctype) {
        const char *b, *e, *at = NULL;
        if (line_text(r, r->err_line, &b, &e)) at = find(b, e, "<!DOCTYPE", 9);
        int col = at ? column(r, r->err_line, at) : 1;
        diag_error(r->diag, ((SylLoc){r->err_line, col, r->err_line, col + 8}),
                   "a species file has no DTD: <!DOCTYPE is not read (entities are never expanded)");
        return;
    }
    int line = r->err_line > 0 && r->err_line <= r->nlines ? r->err_line : 0;
    int col = r->err_col > 0 ? r->err_col : 1;
    diag_error(r->diag, ((SylLoc){line, col, line, col}), "malformed XML: %s", r->message);
}

static void read_document(Reader *r, xmlDocPtr doc) {
    xmlNodePtr root = xmlDocGetRootElement(doc);
    if (!root) {
        diag_error(r->diag, (SylLoc){0}, "this XML file has no element");
        return;
    }
    /* which kind of file: its root element says */
    bool helios = named(root, "helios"), grow = named(root, SYL_GROW_PRESET_ROOT);
    if (!helios && !grow && !named(root, "arbaro")) {
        char shown[64];
        diag_error(r->diag, element_loc(r, root),
                   "not an Arbaro species file (<arbaro>), a grow preset file (<" SYL_GROW_PRESET_ROOT
                   ">) nor a Helios tree library (<helios>): its root is <%s>",
                   diag_quote(shown, sizeof shown, (const char *)root->name, strlen((const char *)root->name)));
        return;
    }
    const char *want = helios ? "WeberPennTree" : "species", *rootname = (const char *)root->name;
    for (xmlNodePtr n = root->children; n; n = n->next) {
        char where[32];
        snprintf(where, sizeof where, "<%s>", rootname);
        stray_text(r, n, where);
        if (n->type != XML_ELEMENT_NODE) continue;
        if (!named(n, want)) {
            char shown[64];
            diag_error(r->diag, element_loc(r, n), "<%s> holds <%s> elements, not <%s>", rootname, want,
                       diag_quote(shown, sizeof shown, (const char *)n->name, strlen((const char *)n->name)));
            continue;
        }
        if (helios) helios_tree(r, n);
        else species(r, n, grow ? SYL_MODEL_GROW : SYL_MODEL_WEBER);
    }
    if (!r->ast->nmodels && !r->diag->errors)
        diag_error(r->diag, element_loc(r, root), "this file holds no <%s>", want);
}

/* libxml2's parse and the walk, guarded: out of memory in the arena unwinds through here,
 * and libxml2's document is freed first. */
static void read_guarded(Reader *r, xmlParserCtxtPtr ctxt, const char *text, size_t len) {
    Arena *arena = r->arena;
    jmp_buf *outer = arena->oom, oom;
    xmlDocPtr volatile doc = NULL;
    volatile int failed = 1;
    /* what libxml2 reports without its parser context (an encoding it cannot convert) goes
     * to this thread's handler: to ours too, not raw to stderr; restored on every way out */
    xmlStructuredErrorFunc before_handler = xmlStructuredError;
    void *before_user = xmlStructuredErrorContext;
    xmlSetStructuredErrorFunc(ctxt, on_error);
    if (!setjmp(oom)) {
        arena->oom = &oom;
        ctxt->_private = r;
        doc = xmlCtxtReadMemory(ctxt, text, (int)len, r->src->path, NULL,
                                XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING | XML_PARSE_BIG_LINES);
        if (r->failed || !doc) {
            if (!r->failed) snprintf(r->message, sizeof r->message, "libxml2 could not read it"), r->failed = true;
            report_libxml(r);
        } else {
            read_document(r, doc);
        }
        failed = 0;
    }
    arena->oom = outer;
    xmlSetStructuredErrorFunc(before_user, before_handler);
    xmlFreeDoc(doc);
    xmlFreeParserCtxt(ctxt);
    if (failed && outer) longjmp(*outer, 1);
    if (failed) diag_error(r->diag, (SylLoc){0}, "out of memory");
}

int syl_arbaro_parse(const Source *src, Arena *arena, Diag *diag, FileAst *ast) {
    memset(ast, 0, sizeof *ast);
    int before = diag->errors;
    Reader r = {.src = src, .arena = arena, .diag = diag, .ast = ast};
    if (src->len > ARBARO_MAX_BYTES || src->len > INT_MAX) {
        diag_error(diag, (SylLoc){0}, "an XML species file of more than %u MiB is not read", ARBARO_MAX_BYTES >> 20);
        return 1;
    }
    index_lines(&r);
    size_t len = src->len;
    const char *text = helios_prolog(&r, &len);
    if (!text) text = src->text;
    xmlParserCtxtPtr ctxt = xmlNewParserCtxt();
    if (!ctxt) {
        diag_error(diag, (SylLoc){0}, "out of memory");
        return 1;
    }
    ctxt->sax->serror = on_error;
    ctxt->sax->internalSubset = on_doctype;
    read_guarded(&r, ctxt, text, len);
    return diag->errors - before;
}
