/* The compiler's driver: from a parsed file to the Program of one model. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "lang/compiler.h"
#include "lang/schema.h"
#include "util/file.h"

/* ---- reading sources ---- */

char *syl_read_file(const char *path, size_t *len) { return file_read(path, len); }

/* ---- the model's passes, in the order compile_model runs them ---- */

/* The file's top-level statements, then the model's: one list, in the order written. */
static Stmt **gather(Compiler *c, Model *top, Model *model, int *n) {
    Stmt **all = arena_alloc(c->tmp, sizeof *all * (size_t)(top->n + model->n + 1));
    *n = 0;
    for (int i = 0; i < top->n; i++) all[(*n)++] = &top->v[i];
    for (int i = 0; i < model->n; i++) all[(*n)++] = &model->v[i];
    return all;
}

/* The brackets' symbols come first; settings start at their defaults. */
static void set_defaults(Compiler *c, Model *model) {
    SylProgram *p = c->p;
    cc_symbol(c, "[", model->loc);
    cc_symbol(c, "]", model->loc);
    p->derive = 1;
    p->angle = 45;
    p->step = 1;
    p->width = 0.1;
    p->widthfactor = 0.7;
    p->direction_when = -1;
    p->tables[TABLE_DECOMPOSE].maxdepth = p->tables[TABLE_INTERPRET].maxdepth = 16;
}

/* Per function, curve and symbol: its definition and whether it is used, for the passes
 * after declaration. */
static void track_uses(Compiler *c, Stmt **all, int n, Model *top) {
    SylProgram *p = c->p;
    c->fn_stmts = arena_alloc(c->tmp, sizeof *c->fn_stmts * (size_t)(p->nfns + 1));
    c->fn_random = arena_alloc(c->tmp, sizeof(bool) * (size_t)(p->nfns + 1));
    c->fn_used = arena_alloc(c->tmp, sizeof(bool) * (size_t)(p->nfns + 1));
    c->curve_used = arena_alloc(c->tmp, sizeof(bool) * (size_t)(p->ncurves + 1));
    c->sym_used = arena_alloc(c->tmp, sizeof(bool) * MAX_SYMBOLS);
    for (int i = 0; i < n; i++)
        if (all[i]->kind == ST_FN) {
            int id = namemap_get(&c->fns, all[i]->name, -1);
            if (id >= 0 && !c->fn_stmts[id]) c->fn_stmts[id] = all[i];
        }
    /* what the file's top level declares is shared by its models: never "unused" in one */
    for (int i = 0; i < top->n; i++) {
        Stmt *s = &top->v[i];
        int id;
        if (s->kind == ST_FN && (id = namemap_get(&c->fns, s->name, -1)) >= 0) c->fn_used[id] = true;
        if (s->kind == ST_CURVE && (id = namemap_get(&c->curves, s->name, -1)) >= 0) c->curve_used[id] = true;
        if (s->kind == ST_MODULE && (id = namemap_get(&c->syms, s->name, -1)) >= 0) c->sym_used[id] = true;
    }
}

/* Settings and values, in the order written. */
static void evaluate_all(Compiler *c, Stmt **all, int n) {
    SylLoc seen[16] = {{0}};
    for (int i = 0; i < n; i++) {
        Stmt *s = all[i];
        if (s->kind == ST_GROUP || s->kind == ST_USE) continue; /* groups.c; misplaced ones: the parser */
        if (s->group && s->kind != ST_RULE) {
            diag_error(c->d, s->loc, "only rules may stand in a group block");
            continue;
        }
        if (s->block != BLOCK_PRODUCE && s->kind != ST_RULE && s->kind != ST_SETTING) {
            diag_error(c->d, s->loc, "only rules and maxdepth may stand in a %s block",
                       s->block == BLOCK_DECOMPOSE ? "decompose" : "interpret");
            continue;
        }
        if (s->kind == ST_SETTING) cc_setting(c, s, seen);
        else if (s->kind != ST_DIRECTIVE) cc_evaluate(c, s); /* texture lines: lang/textures.c */
    }
}

/* ignore / consider: the symbols context matching skips. An ignore list is final here; a
 * consider list is applied by apply_consider once the rules have made every symbol.
 * Returns whether the model considers. */
static bool read_skips(Compiler *c, Stmt **all, int n, bool *considered) {
    SylProgram *p = c->p;
    bool consider = false;
    SylLoc skip_loc = {0};
    for (int i = 0; i < n; i++) {
        Stmt *s = all[i];
        if (s->kind != ST_IGNORE && s->kind != ST_CONSIDER) continue;
        if (skip_loc.first_line && (s->kind == ST_CONSIDER) != consider)
            diag_error(c->d, s->loc, "use either ignore or consider, not both");
        consider = s->kind == ST_CONSIDER;
        skip_loc = s->loc;
        Mods ms;
        cc_split(c, &s->items, &ms);
        for (int j = 0; j < ms.n; j++) {
            if (cc_is_bracket(ms.v[j].sym)) diag_error(c->d, ms.v[j].loc, "brackets cannot be ignored");
            else if (ms.v[j].args.n) diag_error(c->d, ms.v[j].loc, "write the module without parameters here");
            if (consider) considered[ms.v[j].sym] = true;
            else p->skip[ms.v[j].sym] = true;
        }
    }
    return consider;
}

/* Rules into their tables, and the axiom. */
static void compile_rules(Compiler *c, Stmt **all, int n, Model *model) {
    SylProgram *p = c->p;
    int axioms = 0;
    int counts[TABLE_COUNT] = {0};
    for (int i = 0; i < n; i++)
        if (all[i]->kind == ST_RULE) counts[all[i]->block]++;
    for (int t = 0; t < TABLE_COUNT; t++)
        p->tables[t].rules = arena_alloc(&p->arena, sizeof(Rule) * (size_t)(counts[t] ? counts[t] : 1));
    for (int i = 0; i < n; i++) {
        Stmt *s = all[i];
        if (s->kind == ST_RULE) {
            RuleTable *t = &p->tables[s->block];
            Rule *r = &t->rules[t->nrules++];
            cc_rule(c, s, r);
            r->group = cc_group_of(p, s->group);
            if (r->group >= 0) p->grouped[s->block] |= 1ull << r->group;
        } else if (s->kind == ST_AXIOM) {
            if (axioms++) {
                diag_error(c->d, s->loc, "a model has one axiom");
                continue;
            }
            Mods ms;
            cc_split(c, &s->items, &ms);
            Scope none = {0};
            p->axiom.loc = s->loc;
            cc_warn_words(c, &s->items);
            cc_successor(c, &ms, &none, &p->axiom, "the axiom");
        }
    }
    if (!axioms && lang_kind_is(model->kind, KF_RULES)) diag_error(c->d, model->loc, "model '%s' has no axiom", model->name);
}

static void apply_consider(Compiler *c, const bool *considered) {
    SylProgram *p = c->p;
    for (int s = 0; s < p->nsyms; s++) p->skip[s] = !cc_is_bracket(s) && !considered[s];
}

/* Whether the axiom or a rule uses a query module (the turtle fills them after every step)
 * and ?E (the environment answers it). */
static void mark_queries(Compiler *c) {
    SylProgram *p = c->p;
    for (int s = 0; s < p->nsyms; s++)
        if (c->sym_used[s] && lang_symbol_is_query(p, s)) {
            p->uses_queries = true;
            if (p->syms[s].turtle == TC_QUERY_E) p->uses_env = true;
        }
}

/* Whether the axiom or a successor of a production or decomposition holds `%`: only then
 * does a step end with the cut pass. */
static void mark_cut(Compiler *c) {
    SylProgram *p = c->p;
    const Rule *r = &p->axiom;
    for (int t = -1; t <= TABLE_DECOMPOSE && !p->may_cut; t++)
        for (int i = 0; i < (t < 0 ? 1 : p->tables[t].nrules) && !p->may_cut; i++) {
            if (t >= 0) r = &p->tables[t].rules[i];
            for (int k = 0; k < r->nsucc; k++)
                if (p->syms[CODE_SYM(r->succ[k])].turtle == TC_CUT) p->may_cut = true;
        }
}

static void compile_model(Compiler *c, Model *top, Model *model) {
    SylProgram *p = c->p;
    int n;
    Stmt **all = gather(c, top, model, &n);
    set_defaults(c, model);
    for (int i = 0; i < n; i++) cc_declare(c, all[i], i < top->n);
    track_uses(c, all, n, top);
    cc_localise_overrides(c);
    cc_check_overrides(c);
    evaluate_all(c, all, n);
    cc_apply_overrides(c);
    for (int i = 0; i < p->nfns; i++) cc_function(c, i);
    bool considered[MAX_SYMBOLS] = {false};
    bool consider = read_skips(c, all, n, considered);
    cc_groups(c, all, n);
    compile_rules(c, all, n, model);
    mark_cut(c);
    if (consider) apply_consider(c, considered);
    for (int t = 0; t < TABLE_COUNT; t++) cc_build_table(c, &p->tables[t]);
    mark_queries(c);
}

/* ---- entry points ---- */

/* The named model, or the file's first lsystem or grow block (a scene is not a model). */
static Model *find_model(FileAst *ast, const char *name) {
    for (int i = 0; i < ast->nmodels; i++)
        if (!lang_kind_is(ast->models[i].kind, KF_UNNAMED) && (!name || !strcmp(ast->models[i].name, name)))
            return &ast->models[i];
    return NULL;
}

static Model *find_scene(FileAst *ast) {
    for (int i = 0; i < ast->nmodels; i++)
        if (lang_kind_is(ast->models[i].kind, KF_UNNAMED)) return &ast->models[i];
    return NULL;
}

/* Evaluate the directive lines of a grow or scene block. Numbers and tuples may use the
 * constants and parameters known so far. */
static void directives(Compiler *c, Model *m, SylDirective **out, int *nout) {
    SylProgram *p = c->p;
    int n = 0;
    for (int i = 0; i < m->n; i++) n += m->v[i].kind == ST_DIRECTIVE;
    *out = arena_alloc(&p->arena, sizeof **out * (size_t)(n ? n : 1));
    *nout = 0;
    for (int i = 0; i < m->n; i++) {
        Stmt *s = &m->v[i];
        if (s->kind != ST_DIRECTIVE) continue;
        SylDirective *d = &(*out)[(*nout)++];
        d->name = arena_strndup(&p->arena, s->name, strlen(s->name));
        d->line = s->loc.first_line;
        d->col = s->loc.first_column;
        if (s->file) {
            d->file = s->file->path;
            d->file_text = s->file->text;
            d->file_len = s->file->len;
        }
        d->nargs = s->dargs.n;
        SylDirArg *args = arena_alloc(&p->arena, sizeof *args * (size_t)(s->dargs.n ? s->dargs.n : 1));
        d->args = args;
        for (int k = 0; k < s->dargs.n; k++) {
            const DirArg *a = &s->dargs.v[k];
            SylDirArg *o = &args[k];
            o->kind = (SylDirArgKind)a->kind;
            o->text = arena_strndup(&p->arena, a->text, strlen(a->text));
            o->line = a->loc.first_line;
            o->col = a->loc.first_column;
            if (a->kind == DARG_NUMBER) o->num = a->value->num;
            /* a word may name a curve (a strands block's per-order functions): that uses it */
            int cid;
            if (a->kind == DARG_WORD && c->curve_used && (cid = namemap_get(&c->curves, a->text, -1)) >= 0)
                c->curve_used[cid] = true;
            if (a->args.n) {
                double *vals = arena_alloc(&p->arena, sizeof *vals * (size_t)a->args.n);
                for (int j = 0; j < a->args.n; j++) cc_const(c, a->args.v[j], &vals[j]);
                o->values = vals;
                o->nvalues = a->args.n;
            }
        }
    }
}

/* What syl_compile frees when out of memory unwinds it (arena.h): kept off its stack,
 * since locals changed after setjmp are lost by longjmp. */
typedef struct CompileGuard {
    jmp_buf oom;
    SylProgram *p;
    Arena tmp;
} CompileGuard;

static SylProgram *compile_text(CompileGuard *g, const char *path, const char *text, size_t len,
                                const SylCompileOptions *opt, int *status) {
    static const SylCompileOptions defaults = {0};
    if (!opt) opt = &defaults;
    SylProgram *p = calloc(1, sizeof *p);
    if (!p) {
        *status = SYL_ELIMIT;
        return NULL;
    }
    g->p = p;
    p->read_cache = arena_alloc(&p->arena, sizeof *p->read_cache); /* zeroed; NULL: nothing kept */
    p->arena.oom = &g->oom;
    g->tmp.oom = &g->oom;
    if (text) {
        p->text = malloc(len + 1);
        if (p->text) memcpy(p->text, text, len);
    } else {
        /* a scene's plant file is named by the model: a regular file only */
        p->text = opt->sibling ? file_read_named(path, &len, NULL) : file_read(path, &len);
        if (!p->text) {
            int e = errno; /* before the message, which may change it */
            diag_say(opt->diag, opt->sink, DIAG_ERROR, NULL, "cannot read '%s': %s", path, file_strerror(e));
            arena_free(&p->arena); /* the read cache's room */
            free(p);
            *status = SYL_EIO;
            return NULL;
        }
    }
    if (!p->text) {
        arena_free(&p->arena);
        free(p);
        *status = SYL_ELIMIT;
        return NULL;
    }
    if (len >= 3 && !memcmp(p->text, "\xef\xbb\xbf", 3)) { /* a UTF-8 byte order mark: not part of the text */
        memmove(p->text, p->text + 3, len - 3 + (text ? 0 : 1));
        len -= 3;
    }
    /* the path is kept: callers may free theirs while the program lives on */
    p->src = (Source){.path = arena_strndup(&p->arena, path, strlen(path)), .text = p->text, .len = len};
    lang_program_roots(p, opt);
    if (opt->noverrides > 0) {
        p->overrides = arena_alloc(&p->arena, (size_t)opt->noverrides * sizeof *p->overrides);
        for (int i = 0; i < opt->noverrides; i++) {
            const char *name = opt->overrides[i].name;
            p->overrides[i].name = arena_strndup(&p->arena, name, strlen(name));
            p->overrides[i].value = opt->overrides[i].value;
        }
        p->noverrides = opt->noverrides;
    }
    p->sibling = opt->sibling;
    if (opt->sink) p->sink = *opt->sink, p->has_sink = true;
    Arena *tmp = &g->tmp;
    Diag d = {.out = opt->diag, .sink = program_sink(p), .src = &p->src};
    /* a sibling's warnings were its file's, reported with the model it serves: once */
    int warn = opt->sibling ? 0 : opt->lint ? SYL_WARN_MISTAKES | SYL_WARN_DRAWS : opt->warn;
    Compiler c = {.p = p, .d = &d, .tmp = tmp, .opt = opt, .warn = warn};
    namemap_init(&c.values, tmp);
    namemap_init(&c.fns, tmp);
    namemap_init(&c.curves, tmp);
    namemap_init(&c.syms, tmp);
    namemap_init(&c.declared, tmp);
    FileAst ast;
    *status = SYL_OK;
    if (syl_not_a_model(&p->src, &d)) {
        *status = SYL_EUSAGE;
    } else if (syl_parse(&p->src, tmp, &d, &ast) == 0) {
        c.ast = &ast;
        Model *m = find_model(&ast, opt->model);
        Model *scene = find_scene(&ast);
        if (!m && opt->model) {
            diag_error(&d, (SylLoc){0}, "no lsystem '%s' in this file", opt->model);
            *status = SYL_EUSAGE;
        } else if (!m && scene) {
            /* A file with a scene and no model of its own: its plants come from other files. */
            p->name = "scene";
            p->kind = SYL_MODEL_SCENE;
            p->model_loc = scene->loc;
            compile_model(&c, &ast.top, scene);
            p->has_scene = true;
            p->scene_loc = scene->loc;
            p->first_model = true;
            directives(&c, scene, &p->scene, &p->nscene);
        } else if (!m) {
            diag_error(&d, (SylLoc){0}, "this file holds no lsystem");
        } else {
            p->name = arena_strndup(&p->arena, m->name, strlen(m->name));
            p->kind = m->kind;
            p->model_loc = m->loc;
            cc_splice_from(&c, m);
            compile_model(&c, &ast.top, m);
            /* a directive block's lines; an lsystem's texture lines (lang/textures.def) */
            directives(&c, m, &p->directives, &p->ndirectives);
            if (scene) {
                p->has_scene = true;
                p->scene_loc = scene->loc;
                directives(&c, scene, &p->scene, &p->nscene);
            }
            p->first_model = m == find_model(&ast, NULL);
        }
        /* after the directives, whose (expr) values use params too */
        if (opt->lint && !d.errors && (m || scene)) cc_lint(&c);
        if (c.warn && !d.errors && (m || scene)) cc_warn(&c);
    }
    arena_free(tmp);
    g->p = NULL;
    p->arena.oom = NULL; /* the target dies with syl_compile's frame */
    if (d.errors) {
        if (!*status) *status = c.usage_error ? SYL_EUSAGE : SYL_EMODEL;
        syl_program_free(p);
        return NULL;
    }
    return p;
}

SylProgram *syl_compile(const char *path, const char *text, size_t len, const SylCompileOptions *opt,
                        int *status) {
    CompileGuard *g = calloc(1, sizeof *g);
    if (!g) {
        *status = SYL_ELIMIT;
        return NULL;
    }
    if (setjmp(g->oom)) {
        arena_free(&g->tmp);
        syl_program_free(g->p);
        free(g);
        if (opt) diag_say(opt->diag, opt->sink, DIAG_ERROR, NULL, "out of memory while compiling '%s'", path);
        *status = SYL_ELIMIT;
        return NULL;
    }
    SylProgram *p = compile_text(g, path, text, len, opt, status);
    free(g);
    if (p) lang_keep_lod(p); /* before the hook, whose readers ask for it */
    /* What the language leaves to others (grow and scene directives) is checked by the
     * caller's hook, once the program is whole: a sibling model it compiles is a compile of
     * its own, not one nested in this. */
    int invalid = p && opt && opt->validate ? opt->validate(opt->validate_user, p, opt->diag) : 0;
    if (invalid) {
        syl_program_free(p);
        *status = invalid < 0 ? SYL_EUSAGE : SYL_EMODEL;
        return NULL;
    }
    return p;
}

SylProgram *syl_compile_model(const SylProgram *p, const char *model, FILE *diag, int *status) {
    return lang_compile_sibling(p, model, diag, NULL, status);
}

SylProgram *lang_compile_sibling(const SylProgram *p, const char *model, FILE *diag, const SylSink *sink,
                                 int *status) {
    SylCompileOptions opt = {.model = model, .overrides = p->overrides, .noverrides = p->noverrides, .diag = diag,
                             .sink = sink, .sibling = 1, .allow_paths = p->roots, .nallow_paths = p->nroots};
    return syl_compile(p->src.path, p->src.text, p->src.len, &opt, status);
}

int syl_model_list(const char *path, const char *text, size_t len, const char **names, int max, char *buf,
                    size_t bufsize) {
    return lang_list_models(path, text, len, names, NULL, max, buf, bufsize);
}

int lang_list_models(const char *path, const char *text, size_t len, const char **names, SylModelKind *kinds,
                     int max, char *buf, size_t bufsize) {
    if (len >= 3 && !memcmp(text, "\xef\xbb\xbf", 3)) text += 3, len -= 3; /* as syl_compile */
    Source src = {.path = path, .text = text, .len = len};
    Arena tmp = {0};
    Diag d = {0};
    FileAst ast;
    int n = 0;
    size_t used = 0;
    if (syl_parse(&src, &tmp, &d, &ast) == 0)
        for (int i = 0; i < ast.nmodels && n < max; i++) {
            if (lang_kind_is(ast.models[i].kind, KF_UNNAMED)) continue;
            size_t l = strlen(ast.models[i].name) + 1;
            if (used + l > bufsize) break;
            memcpy(buf + used, ast.models[i].name, l);
            if (kinds) kinds[n] = ast.models[i].kind;
            names[n++] = buf + used;
            used += l;
        }
    arena_free(&tmp);
    return n;
}
