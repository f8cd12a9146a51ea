/* The compiler's driver: from a parsed file to the Program of one model. */
#include <errno.h>
#include <stdarg.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "compiler.h"
#include "opcodes.h"
#include "sot/params.h" /* the growth engine checks grow and scene directives (see below) */

/* ---- reading sources ---- */

char *syl_read_file(const char *path, size_t *len) {
    FILE *f = strcmp(path, "-") ? fopen(path, "rb") : stdin;
    if (!f) return NULL;
    errno = 0;
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    for (size_t got; buf && (got = fread(buf + n, 1, cap - n, f)) > 0;) {
        n += got;
        if (n == cap) {
            char *nb = realloc(buf, cap *= 2);
            if (!nb) { free(buf); buf = NULL; }
            buf = nb;
        }
    }
    int err = ferror(f) ? (errno ? errno : EIO) : 0;
    if (f != stdin) fclose(f);
    if (err || !buf) {
        free(buf);
        errno = err ? err : ENOMEM;
        return NULL;
    }
    buf[n] = 0; /* n < cap: the loop grows the buffer when it fills */
    *len = n;
    return buf;
}

/* ---- declarations ---- */

static bool defined_elsewhere(Compiler *c, const char *name, SylLoc loc) {
    if (namemap_get(&c->values, name, -1) >= 0 || namemap_get(&c->fns, name, -1) >= 0 ||
        namemap_get(&c->curves, name, -1) >= 0) {
        diag_error(c->d, loc, "'%s' is already defined", name);
        return true;
    }
    return false;
}

static void declare(Compiler *c, Stmt *s, bool top) {
    SylProgram *p = c->p;
    switch (s->kind) {
    case ST_MODULE: {
        int len = (int)strlen(s->name);
        int sym = cc_symbol(c, s->name, s->loc);
        Symbol *y = &p->syms[sym];
        int arity = s->has_params ? s->params.n : -1;
        if (y->declared && arity >= 0 && y->declared_arity >= 0 && arity != y->declared_arity) {
            diag_error(c->d, s->loc, "module '%s' was declared with %d parameter%s at line %d", s->name,
                       y->declared_arity, y->declared_arity == 1 ? "" : "s", y->decl_loc.first_line);
            arity = y->declared_arity; /* keep the first, so its uses are not reported again */
        }
        if (arity > MAX_ARITY) diag_error(c->d, s->loc, "a module has at most %d parameters", MAX_ARITY);
        if (!y->declared || arity >= 0) y->declared_arity = arity;
        if (!y->declared) y->decl_loc = s->loc;
        y->declared = true;
        namemap_put(&c->declared, y->name, sym);
        if (len > c->max_declared_len) c->max_declared_len = len;
        break;
    }
    case ST_CONST:
    case ST_PARAM: {
        if (defined_elsewhere(c, s->name, s->loc)) break;
        Value *v = VEC_PUSH(c->tmp, c->vals, c->nvals, c->valcap);
        v->name = s->name;
        v->loc = s->loc;
        v->is_param = s->kind == ST_PARAM;
        v->top = top;
        namemap_put(&c->values, s->name, c->nvals - 1);
        break;
    }
    case ST_FN: {
        if (defined_elsewhere(c, s->name, s->loc)) break;
        for (int i = 0; i < s->params.n; i++)
            for (int j = 0; j < i; j++)
                if (!strcmp(s->params.v[i], s->params.v[j]))
                    diag_error(c->d, s->params.locs[i], "parameter '%s' is named twice", s->params.v[i]);
        if (s->params.n > MAX_LOCALS) {
            diag_error(c->d, s->loc, "a function has at most %d parameters", MAX_LOCALS);
            break;
        }
        Function *f = VEC_PUSH(&p->arena, p->fns, p->nfns, p->fncap);
        f->name = arena_strndup(&p->arena, s->name, strlen(s->name));
        f->nparams = s->params.n;
        f->loc = s->loc;
        f->names = arena_alloc(&p->arena, sizeof *f->names * (size_t)(f->nparams + 1));
        for (int i = 0; i < f->nparams; i++)
            f->names[i] = arena_strndup(&p->arena, s->params.v[i], strlen(s->params.v[i]));
        namemap_put(&c->fns, s->name, p->nfns - 1);
        break;
    }
    case ST_CURVE: {
        if (defined_elsewhere(c, s->name, s->loc)) break;
        Curve *cv = VEC_PUSH(&p->arena, p->curves, p->ncurves, p->curvecap);
        cv->name = arena_strndup(&p->arena, s->name, strlen(s->name));
        cv->loc = s->loc;
        namemap_put(&c->curves, s->name, p->ncurves - 1);
        break;
    }
    default: break;
    }
}

static const SylOverride *find_override(Compiler *c, const char *name) {
    for (int i = c->opt->noverrides - 1; i >= 0; i--) /* the last one given wins */
        if (!strcmp(c->opt->overrides[i].name, name)) return &c->opt->overrides[i];
    return NULL;
}

/* Values, in the order written: a const may use the ones before it. */
static void evaluate(Compiler *c, Stmt *s) {
    SylProgram *p = c->p;
    if (s->kind == ST_CONST || s->kind == ST_PARAM) {
        int id = namemap_get(&c->values, s->name, -1);
        if (id < 0 || c->vals[id].loc.first_line != s->loc.first_line ||
            c->vals[id].loc.first_column != s->loc.first_column)
            return; /* a duplicate, already reported */
        Value *v = &c->vals[id];
        const SylOverride *o = s->kind == ST_PARAM ? find_override(c, s->name) : NULL;
        double x = 0;
        bool ok = cc_const(c, s->value, &x);
        if (o) x = o->value, ok = true;
        v->v = x;
        v->known = true; /* even when it failed: its uses are not errors of their own */
        (void)ok;
        if (s->kind == ST_PARAM) {
            ParamInfo *pi = VEC_PUSH(&p->arena, p->params, p->nparams, p->paramcap);
            pi->name = arena_strndup(&p->arena, s->name, strlen(s->name));
            pi->value = x;
            pi->overridden = o != NULL;
        }
    } else if (s->kind == ST_CURVE) {
        int id = namemap_get(&c->curves, s->name, -1);
        if (id < 0 || p->curves[id].loc.first_line != s->loc.first_line ||
            p->curves[id].loc.first_column != s->loc.first_column)
            return; /* a duplicate name, already reported */
        Curve *cv = &p->curves[id];
        int n = s->args.n / 2;
        cv->x = arena_alloc(&p->arena, sizeof(double) * (size_t)n);
        cv->y = arena_alloc(&p->arena, sizeof(double) * (size_t)n);
        for (int i = 0; i < n; i++) {
            if (!cc_const(c, s->args.v[2 * i], &cv->x[i]) || !cc_const(c, s->args.v[2 * i + 1], &cv->y[i]))
                continue;
            if (i > 0 && cv->x[i] <= cv->x[i - 1])
                diag_error(c->d, s->args.v[2 * i]->loc, "a curve's x values must increase");
        }
        cv->n = n;
    }
}

typedef struct SettingDef {
    const char *name;
    int block; /* -1: the model's level; else only in decompose/interpret blocks */
    double min, max;
    bool integer;
    int nargs;       /* values it takes */
    bool repeatable; /* colour: once per index */
} SettingDef;

static const SettingDef settings[] = {
    {"derive", -1, 0, 1e6, true, 1, false},
    {"angle", -1, -1e9, 1e9, false, 1, false},
    {"step", -1, -1e9, 1e9, false, 1, false},
    {"width", -1, 0, 1e9, false, 1, false},
    {"seed", -1, 0, 9007199254740991.0, true, 1, false},
    {"maxdepth", 1, 1, 1000, true, 1, false},
    {"widthfactor", -1, 0, 1e9, false, 1, false},
    {"tropism", -1, -1e9, 1e9, false, 4, false}, /* direction x, y, z and elasticity */
    {"colour", -1, 0, 255, false, 4, true},      /* index, then red, green, blue in 0..1 */
};

static void setting(Compiler *c, Stmt *s, SylLoc *seen) {
    SylProgram *p = c->p;
    int i = 0, n = (int)(sizeof settings / sizeof *settings);
    while (i < n && strcmp(settings[i].name, s->name)) i++;
    if (i == n) return; /* the lexer only makes SETTING of known names */
    const SettingDef *def = &settings[i];
    if ((def->block < 0) != (s->block == BLOCK_PRODUCE)) {
        diag_error(c->d, s->loc, def->block < 0 ? "'%s' belongs to the model, not to a block"
                                                : "'%s' belongs in a decompose or interpret block",
                   s->name);
        return;
    }
    if (s->args.n != def->nargs) {
        if (def->nargs == 1) diag_error(c->d, s->loc, "'%s' takes one value", s->name);
        else diag_error(c->d, s->loc, "'%s' takes %d values separated by commas", s->name, def->nargs);
        return;
    }
    int slot = def->block < 0 ? i : i + s->block; /* maxdepth per block */
    if (!def->repeatable) {
        if (seen[slot].first_line) {
            diag_error(c->d, s->loc, "'%s' is set twice (first at line %d)", s->name, seen[slot].first_line);
            return;
        }
        seen[slot] = s->loc;
    }
    double v[4];
    for (int k = 0; k < def->nargs; k++)
        if (!cc_const(c, s->args.v[k], &v[k])) return;
    if (!strcmp(s->name, "colour")) {
        if (v[0] != floor(v[0]) || v[0] < 0 || v[0] > 255) {
            diag_error(c->d, s->args.v[0]->loc, "a colour index is a whole number from 0 to 255");
            return;
        }
        for (int k = 1; k < 4; k++)
            if (v[k] < 0 || v[k] > 1) {
                diag_error(c->d, s->args.v[k]->loc, "colour components go from 0 to 1");
                return;
            }
        int idx = (int)v[0];
        for (int k = 0; k < 3; k++) p->colours[idx][k] = (float)v[k + 1];
        p->colour_set[idx] = true;
        return;
    }
    if (!strcmp(s->name, "tropism")) {
        for (int k = 0; k < 4; k++) p->tropism[k] = v[k];
        return;
    }
    if (v[0] < def->min || v[0] > def->max) {
        diag_error(c->d, s->args.v[0]->loc, "'%s' %.15g is out of range (%s %.17g)", s->name, v[0],
                   v[0] > def->max ? "at most" : "at least", v[0] > def->max ? def->max : def->min);
        return;
    }
    if (def->integer && v[0] != floor(v[0])) {
        diag_error(c->d, s->args.v[0]->loc, "'%s' must be %s from %.15g to %.17g", s->name,
                   def->integer ? "a whole number" : "a number", def->min, def->max);
        return;
    }
    if (!strcmp(s->name, "derive")) p->derive = (int)v[0];
    else if (!strcmp(s->name, "angle")) p->angle = v[0];
    else if (!strcmp(s->name, "step")) p->step = v[0];
    else if (!strcmp(s->name, "width")) p->width = v[0];
    else if (!strcmp(s->name, "seed")) p->seed = (uint64_t)v[0];
    else if (!strcmp(s->name, "widthfactor")) p->widthfactor = v[0];
    else p->tables[s->block == BLOCK_DECOMPOSE ? TABLE_DECOMPOSE : TABLE_INTERPRET].maxdepth = (int)v[0];
}

/* ---- rules ---- */

static bool is_bracket(int sym) { return sym == SYM_OPEN || sym == SYM_CLOSE; }

static uint16_t module_code(Compiler *c, const Mod *m) {
    const Symbol *y = &c->p->syms[m->sym];
    int n = m->args.n;
    c->sym_used[m->sym] = true;
    if (n > MAX_ARITY) {
        diag_error(c->d, m->loc, "a module has at most %d parameters", MAX_ARITY);
        n = MAX_ARITY;
    }
    if (is_bracket(m->sym) && n) diag_error(c->d, m->loc, "a bracket takes no parameters");
    if (y->declared && y->declared_arity >= 0 && n != y->declared_arity)
        diag_error(c->d, m->loc, "module '%s' takes %d parameter%s (declared at line %d), not %d", y->name,
                   y->declared_arity, y->declared_arity == 1 ? "" : "s", y->decl_loc.first_line, n);
    return CODE(m->sym, n);
}

/* Bind a pattern module's parameters (which must be names) to fresh locals. */
static int bind(Compiler *c, const Mod *m, Scope *s) {
    int first = s->n;
    for (int i = 0; i < m->args.n; i++) {
        Expr *e = m->args.v[i];
        if (e->kind != EX_NAME) {
            diag_error(c->d, e->loc, "parameters in a rule's predecessor and contexts must be names");
            continue;
        }
        for (int j = 0; j < s->n; j++)
            if (!strcmp(s->names[j], e->name))
                diag_error(c->d, e->loc, "parameter '%s' is bound twice in this rule", e->name);
        if (s->n >= MAX_LOCALS) {
            diag_error(c->d, e->loc, "a rule binds at most %d parameters", MAX_LOCALS);
            return first;
        }
        s->names[s->n++] = e->name;
    }
    return first;
}

static void pattern(Compiler *c, const Mods *ms, bool branches, Scope *s, PatElem **out, int *nout) {
    *nout = ms->n;
    *out = arena_alloc(&c->p->arena, sizeof **out * (size_t)(ms->n ? ms->n : 1));
    int stack[64], depth = 0;
    for (int i = 0; i < ms->n; i++) {
        const Mod *m = &ms->v[i];
        PatElem *pe = &(*out)[i];
        pe->code = module_code(c, m);
        if (m->sym == SYM_OPEN || m->sym == SYM_CLOSE) {
            if (!branches) {
                diag_error(c->d, m->loc, "a left context cannot hold branches");
                continue;
            }
            if (m->sym == SYM_OPEN) {
                pe->kind = PAT_OPEN;
                if (depth == 64) diag_error(c->d, m->loc, "branches nested too deeply");
                else stack[depth++] = i;
            } else if (!depth) {
                diag_error(c->d, m->loc, "']' without '[' in a right context");
            } else {
                pe->kind = PAT_CLOSE;
                (*out)[stack[--depth]].match = i;
            }
        } else {
            pe->kind = PAT_MODULE;
            pe->local = (uint8_t)bind(c, m, s);
        }
    }
    if (depth) diag_error(c->d, ms->v[stack[depth - 1]].loc, "'[' without ']' in a right context");
}

/* The constant an expression compiled to, if it is one (PUSHK k; RET). */
bool cc_code_constant(const SylProgram *p, int32_t pc, double *v) {
    if (pc < 0 || INSTR_OP(p->code[pc]) != OP_PUSHK || INSTR_OP(p->code[pc + 1]) != OP_RET) return false;
    *v = p->consts[INSTR_A(p->code[pc])];
    return true;
}

static void successor(Compiler *c, const Mods *ms, Scope *s, Rule *r, const char *what) {
    SylProgram *p = c->p;
    r->nsucc = ms->n;
    r->succ = arena_alloc(&p->arena, sizeof *r->succ * (size_t)(ms->n + SUCC_PAD));
    int nslots = 0, depth = 0;
    SylLoc open[64];
    for (int i = 0; i < ms->n; i++) nslots += ms->v[i].args.n;
    r->slots = arena_alloc(&p->arena, sizeof *r->slots * (size_t)(nslots ? nslots : 1));
    r->nslots = 0;
    for (int i = 0; i < ms->n; i++) {
        const Mod *m = &ms->v[i];
        r->succ[i] = module_code(c, m);
        if (m->sym == SYM_OPEN) open[depth++ & 63] = m->loc;
        if (m->sym == SYM_CLOSE && --depth < 0) {
            diag_error(c->d, m->loc, "']' closes no branch");
            depth = 0;
        }
        for (int j = 0; j < m->args.n && r->nslots < nslots; j++) {
            Slot *sl = &r->slots[r->nslots++];
            bool random = false;
            int before = c->d->errors;
            Expr *e = cc_fold(c, m->args.v[j], s, &random);
            if (c->d->errors != before) continue;
            if (e->kind == EX_NUM) {
                sl->kind = SLOT_CONST;
                sl->k = e->num;
            } else if (e->kind == EX_LOCAL) {
                sl->kind = SLOT_LOCAL;
                sl->local = (uint8_t)e->op;
            } else if (e->kind == EX_BINARY && e->a->kind == EX_LOCAL && e->b->kind == EX_NUM &&
                       (e->op == '+' || e->op == '-' || e->op == '*' || e->op == '/')) {
                sl->kind = e->op == '+' ? SLOT_ADDK : e->op == '-' ? SLOT_SUBK : e->op == '*' ? SLOT_MULK : SLOT_DIVK;
                sl->local = (uint8_t)e->a->op;
                sl->k = e->b->num;
                int32_t pc = cc_expr(c, e, s, NULL); /* LOCAL x; op k; RET */
                sl->pc = pc < 0 ? 0 : (uint32_t)pc + 1; /* the operator: where an overflow is reported */
            } else {
                sl->kind = SLOT_CODE;
                int32_t pc = cc_expr(c, e, s, NULL);
                sl->pc = pc < 0 ? 0 : (uint32_t)pc;
            }
        }
    }
    if (depth) diag_error(c->d, open[(depth - 1) & 63], "a '[' in %s is never closed", what);
}

static void compile_rule(Compiler *c, const Stmt *s, Rule *out) {
    SylProgram *p = c->p;
    memset(out, 0, sizeof *out);
    Mods pred, left, right, succ;
    cc_split(c, &s->rule.pred, &pred);
    cc_split(c, &s->rule.left, &left);
    cc_split(c, &s->rule.right, &right);
    cc_split(c, &s->rule.succ, &succ);
    out->loc = s->rule.loc;
    out->line = s->rule.loc.first_line;
    out->cond = out->weight = -1;
    if (pred.n != 1 || is_bracket(pred.v[0].sym)) {
        diag_error(c->d, s->rule.loc, "a predecessor is one module (write contexts with < and >)");
        return;
    }
    const char *names[MAX_LOCALS];
    Scope scope = {.names = names};
    out->pred = module_code(c, &pred.v[0]);
    out->pred_arity = (uint8_t)CODE_ARITY(out->pred);
    bind(c, &pred.v[0], &scope);
    pattern(c, &left, false, &scope, &out->left, &out->nleft);
    pattern(c, &right, true, &scope, &out->right, &out->nright);
    out->nlocals = (uint8_t)scope.n;
    out->names = arena_alloc(&p->arena, sizeof *out->names * (size_t)(scope.n + 1));
    for (int i = 0; i < scope.n; i++) out->names[i] = arena_strndup(&p->arena, names[i], strlen(names[i]));
    if (s->rule.cond) {
        out->cond = cc_expr(c, s->rule.cond, &scope, NULL);
        double v;
        if (cc_code_constant(p, out->cond, &v) && v != 0) out->cond = -1; /* always true */
    }
    if (s->rule.weight) {
        out->weighted = true;
        int32_t pc = cc_expr(c, s->rule.weight, &scope, NULL);
        double v;
        if (cc_code_constant(p, pc, &v)) {
            out->const_weight = v;
            if (v < 0) diag_error(c->d, s->rule.weight->loc, "a weight must not be negative");
        } else {
            out->weight = pc;
        }
    }
    successor(c, &succ, &scope, out, "this successor");
}

static void build_table(Compiler *c, RuleTable *t) {
    SylProgram *p = c->p;
    if (!t->nrules) return;
    t->dispatch = arena_alloc(&p->arena, sizeof *t->dispatch * CODE_COUNT);
    t->order = arena_alloc(&p->arena, sizeof *t->order * (size_t)t->nrules);
    for (int i = 0; i < t->nrules; i++) t->dispatch[t->rules[i].pred].count++;
    uint32_t at = 0;
    for (int code = 0; code < CODE_COUNT; code++) {
        t->dispatch[code].first = at;
        at += t->dispatch[code].count;
        t->dispatch[code].count = 0;
    }
    for (int i = 0; i < t->nrules; i++) {
        Rule *r = &t->rules[i];
        Dispatch *d = &t->dispatch[r->pred];
        t->order[d->first + d->count++] = (uint16_t)i;
        if (r->nleft || r->nright) t->has_context = true;
        if (r->nleft) t->ctx_left = true;
        for (int k = 0; k < r->nright; k++)
            if (r->right[k].kind != PAT_MODULE) t->ctx_branches = true;
        if (r->nright) t->ctx_right = true;
        if (r->nleft > 1 || r->nright > 1) t->ctx_index = true;
        for (int k = 0; k < r->nleft; k++)
            if (CODE_ARITY(r->left[k].code)) t->ctx_index = true;
        for (int k = 0; k < r->nright; k++)
            if (CODE_ARITY(r->right[k].code)) t->ctx_index = true;
        if (r->nslots) t->emits_params = true;
        if (r->nsucc > t->max_succ) t->max_succ = r->nsucc;
        if (r->nslots > t->max_succ_params) t->max_succ_params = r->nslots;
    }
    t->all_plain = true;
    for (int code = 0; code < CODE_COUNT; code++) {
        Dispatch *d = &t->dispatch[code];
        if (d->count > 1) t->all_plain = false;
        if (d->count != 1) continue;
        const Rule *r = &t->rules[t->order[d->first]];
        if (!r->nleft && !r->nright && r->cond < 0 && !r->weighted) d->plain = r;
        else t->all_plain = false;
    }
    for (int code = 0; code < CODE_COUNT; code++) {
        Dispatch *d = &t->dispatch[code];
        if (!d->count || d->plain) continue;
        bool fast = true;
        for (uint32_t k = 0; k < d->count && fast; k++) {
            const Rule *r = &t->rules[t->order[d->first + k]];
            fast = r->nleft <= 1 && r->nright <= 1 && r->cond < 0 && !r->weighted &&
                   (!r->nleft || !CODE_ARITY(r->left[0].code)) &&
                   (!r->nright || (r->right[0].kind == PAT_MODULE && !CODE_ARITY(r->right[0].code)));
        }
        if (!fast) continue;
        FastRule *f = arena_alloc(&p->arena, sizeof *f * d->count);
        for (uint32_t k = 0; k < d->count; k++) {
            const Rule *r = &t->rules[t->order[d->first + k]];
            f[k].left = r->nleft ? r->left[0].code : CODE_ANY;
            f[k].right = r->nright ? r->right[0].code : CODE_ANY;
            f[k].rule = r;
        }
        d->fast = f;
    }
}

static void compile_model(Compiler *c, Model *top, Model *model) {
    SylProgram *p = c->p;
    Stmt **all = arena_alloc(c->tmp, sizeof *all * (size_t)(top->n + model->n + 1));
    int n = 0;
    for (int i = 0; i < top->n; i++) all[n++] = &top->v[i];
    for (int i = 0; i < model->n; i++) all[n++] = &model->v[i];

    cc_symbol(c, "[", model->loc);
    cc_symbol(c, "]", model->loc);
    p->derive = 1;
    p->angle = 45;
    p->step = 1;
    p->width = 0.1;
    p->widthfactor = 0.7;
    p->tables[TABLE_DECOMPOSE].maxdepth = p->tables[TABLE_INTERPRET].maxdepth = 16;

    for (int i = 0; i < n; i++) declare(c, all[i], i < top->n);
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
    for (int i = 0; i < c->opt->noverrides; i++) {
        int id = namemap_get(&c->values, c->opt->overrides[i].name, -1);
        if (c->opt->sibling) continue;
        if (id < 0 || !c->vals[id].is_param) c->usage_error = true;
        if (id < 0 || !c->vals[id].is_param)
            diag_error(c->d, (SylLoc){0}, "--set %s: model '%s' has no parameter '%s'%s",
                       c->opt->overrides[i].name, p->name, c->opt->overrides[i].name,
                       id >= 0 ? " (it is a const; declare it with `param` to set it)" : "");
    }

    SylLoc seen[16] = {{0}};
    for (int i = 0; i < n; i++) {
        Stmt *s = all[i];
        if (s->block != BLOCK_PRODUCE && s->kind != ST_RULE && s->kind != ST_SETTING) {
            diag_error(c->d, s->loc, "only rules and maxdepth may stand in a %s block",
                       s->block == BLOCK_DECOMPOSE ? "decompose" : "interpret");
            continue;
        }
        if (s->kind == ST_SETTING) setting(c, s, seen);
        else evaluate(c, s);
    }
    for (int i = 0; i < p->nfns; i++) cc_function(c, i);

    /* ignore / consider: the symbols context matching skips */
    bool consider = false, considered[MAX_SYMBOLS] = {false};
    SylLoc skip_loc = {0};
    int axioms = 0;
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
            if (is_bracket(ms.v[j].sym)) diag_error(c->d, ms.v[j].loc, "brackets cannot be ignored");
            else if (ms.v[j].args.n) diag_error(c->d, ms.v[j].loc, "write the module without parameters here");
            if (consider) considered[ms.v[j].sym] = true;
            else p->skip[ms.v[j].sym] = true;
        }
    }

    /* rules and the axiom */
    int counts[TABLE_COUNT] = {0};
    for (int i = 0; i < n; i++)
        if (all[i]->kind == ST_RULE) counts[all[i]->block]++;
    for (int t = 0; t < TABLE_COUNT; t++)
        p->tables[t].rules = arena_alloc(&p->arena, sizeof(Rule) * (size_t)(counts[t] ? counts[t] : 1));
    for (int i = 0; i < n; i++) {
        Stmt *s = all[i];
        if (s->kind == ST_RULE) {
            RuleTable *t = &p->tables[s->block];
            compile_rule(c, s, &t->rules[t->nrules++]);
        } else if (s->kind == ST_AXIOM) {
            if (axioms++) {
                diag_error(c->d, s->loc, "a model has one axiom");
                continue;
            }
            Mods ms;
            cc_split(c, &s->items, &ms);
            Scope none = {0};
            p->axiom.loc = s->loc;
            successor(c, &ms, &none, &p->axiom, "the axiom");
        }
    }
    if (!axioms && model->kind == MODEL_LSYSTEM) diag_error(c->d, model->loc, "model '%s' has no axiom", model->name);
    if (consider)
        for (int s = 0; s < p->nsyms; s++) p->skip[s] = !is_bracket(s) && !considered[s];
    for (int t = 0; t < TABLE_COUNT; t++) build_table(c, &p->tables[t]);
    for (int s = 0; s < p->nsyms; s++)
        if (c->sym_used[s] && lang_symbol_is_query(p, s)) {
            p->uses_queries = true;
            if (p->syms[s].turtle == TC_QUERY_E) p->uses_env = true;
        }
    if (c->opt->lint && !c->d->errors) cc_lint(c);
}

/* ---- entry points ---- */

/* The named model, or the file's first lsystem or grow block (a scene is not a model). */
static Model *find_model(FileAst *ast, const char *name) {
    for (int i = 0; i < ast->nmodels; i++)
        if (ast->models[i].kind != MODEL_SCENE && (!name || !strcmp(ast->models[i].name, name)))
            return &ast->models[i];
    return NULL;
}

static Model *find_scene(FileAst *ast) {
    for (int i = 0; i < ast->nmodels; i++)
        if (ast->models[i].kind == MODEL_SCENE) return &ast->models[i];
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
    p->arena.oom = &g->oom;
    g->tmp.oom = &g->oom;
    if (text) {
        p->text = malloc(len + 1);
        if (p->text) memcpy(p->text, text, len);
    } else {
        p->text = syl_read_file(path, &len);
        if (!p->text) {
            if (opt->diag) fprintf(opt->diag, "sylva: error: cannot read '%s': %s\n", path, strerror(errno));
            free(p);
            *status = SYL_EIO;
            return NULL;
        }
    }
    if (!p->text) {
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
    if (opt->noverrides > 0) {
        p->overrides = arena_alloc(&p->arena, (size_t)opt->noverrides * sizeof *p->overrides);
        for (int i = 0; i < opt->noverrides; i++) {
            const char *name = opt->overrides[i].name;
            p->overrides[i].name = arena_strndup(&p->arena, name, strlen(name));
            p->overrides[i].value = opt->overrides[i].value;
        }
        p->noverrides = opt->noverrides;
    }
    Arena *tmp = &g->tmp;
    Diag d = {.out = opt->diag, .src = &p->src};
    Compiler c = {.p = p, .d = &d, .tmp = tmp, .opt = opt};
    namemap_init(&c.values, tmp);
    namemap_init(&c.fns, tmp);
    namemap_init(&c.curves, tmp);
    namemap_init(&c.syms, tmp);
    namemap_init(&c.declared, tmp);
    FileAst ast;
    *status = SYL_OK;
    if (syl_parse(&p->src, tmp, &d, &ast) == 0) {
        Model *m = find_model(&ast, opt->model);
        Model *scene = find_scene(&ast);
        if (!m && opt->model) {
            diag_error(&d, (SylLoc){0}, "no lsystem '%s' in this file", opt->model);
            *status = SYL_EUSAGE;
        } else if (!m && scene) {
            /* A file with a scene and no model of its own: its plants come from other files. */
            p->name = "scene";
            p->kind = SYL_MODEL_SCENE;
            compile_model(&c, &ast.top, scene);
            p->has_scene = true;
            directives(&c, scene, &p->scene, &p->nscene);
            if (!d.errors) d.errors += sot_check_scene(p, opt->diag);
        } else if (!m) {
            diag_error(&d, (SylLoc){0}, "this file holds no lsystem");
        } else {
            p->name = arena_strndup(&p->arena, m->name, strlen(m->name));
            p->kind = m->kind == MODEL_GROW ? SYL_MODEL_GROW : SYL_MODEL_LSYSTEM;
            compile_model(&c, &ast.top, m);
            if (m->kind == MODEL_GROW) directives(&c, m, &p->directives, &p->ndirectives);
            if (scene) {
                p->has_scene = true;
                directives(&c, scene, &p->scene, &p->nscene);
            }
            /* Growth directives are checked here, by the growth engine's own table
             * (src/sot/params.c), so `sylva check` reports them. The scene is checked with
             * the file's first model only, so that checking every model reports it once. */
            if (!opt->sibling && !d.errors && m->kind == MODEL_GROW) d.errors += sot_check_grow(p, opt->diag);
            if (!opt->sibling && !d.errors && scene && m == find_model(&ast, NULL))
                d.errors += sot_check_scene(p, opt->diag);
        }
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
        if (opt && opt->diag) fprintf(opt->diag, "sylva: error: out of memory while compiling '%s'\n", path);
        *status = SYL_ELIMIT;
        return NULL;
    }
    SylProgram *p = compile_text(g, path, text, len, opt, status);
    free(g);
    return p;
}

SylProgram *syl_compile_model(const SylProgram *p, const char *model, FILE *diag, int *status) {
    SylCompileOptions opt = {.model = model, .overrides = p->overrides, .noverrides = p->noverrides, .diag = diag,
                             .sibling = 1};
    return syl_compile(p->src.path, p->src.text, p->src.len, &opt, status);
}

int syl_list_models(const char *path, const char *text, size_t len, const char **names, int max, char *buf,
                    size_t bufsize) {
    if (len >= 3 && !memcmp(text, "\xef\xbb\xbf", 3)) text += 3, len -= 3; /* as syl_compile */
    Source src = {.path = path, .text = text, .len = len};
    Arena tmp = {0};
    Diag d = {0};
    FileAst ast;
    int n = 0;
    size_t used = 0;
    if (syl_parse(&src, &tmp, &d, &ast) == 0)
        for (int i = 0; i < ast.nmodels && n < max; i++) {
            if (ast.models[i].kind == MODEL_SCENE) continue;
            size_t l = strlen(ast.models[i].name) + 1;
            if (used + l > bufsize) break;
            memcpy(buf + used, ast.models[i].name, l);
            names[n++] = buf + used;
            used += l;
        }
    arena_free(&tmp);
    return n;
}

void syl_program_free(SylProgram *p) {
    if (!p) return;
    arena_free(&p->arena);
    free(p->text);
    free(p);
}

const char *syl_program_name(const SylProgram *p) { return p->name; }
SylModelKind syl_program_kind(const SylProgram *p) { return p->kind; }
const char *syl_program_path(const SylProgram *p) { return p->src.path; }
const char *syl_program_source(const SylProgram *p, size_t *len) {
    *len = p->src.len;
    return p->src.text;
}

const SylDirective *syl_program_directives(const SylProgram *p, int *n) {
    *n = p->ndirectives;
    return p->directives;
}

const SylDirective *syl_program_scene(const SylProgram *p, int *n) {
    *n = p->nscene;
    return p->has_scene ? p->scene : NULL;
}

void syl_program_error(const SylProgram *p, FILE *out, int line, int col, const char *fmt, ...) {
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    Diag d = {.out = out, .src = &p->src};
    diag_error(&d, ((SylLoc){line, col, line, col}), "%s", msg);
}
int syl_program_steps(const SylProgram *p) { return p->derive; }
uint64_t syl_program_seed(const SylProgram *p) { return p->seed; }
int syl_program_symbol_count(const SylProgram *p) { return p->nsyms; }
const char *syl_program_symbol_name(const SylProgram *p, int sym) {
    return sym >= 0 && sym < p->nsyms ? p->syms[sym].name : NULL;
}
int syl_program_symbol_find(const SylProgram *p, const char *name) {
    for (int i = 0; i < p->nsyms; i++)
        if (!strcmp(p->syms[i].name, name)) return i;
    return -1;
}
double syl_program_setting(const SylProgram *p, const char *name) {
    if (!strcmp(name, "angle")) return p->angle;
    if (!strcmp(name, "step")) return p->step;
    if (!strcmp(name, "width")) return p->width;
    if (!strcmp(name, "derive")) return p->derive;
    if (!strcmp(name, "widthfactor")) return p->widthfactor;
    return NAN;
}
