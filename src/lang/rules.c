/* Rules: a rule's patterns and successor compiled, and the dispatch tables built over them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lang/compiler.h"
#include "lang/groups.h"
#include "lang/opcodes.h"

static uint16_t module_code(Compiler *c, const Mod *m) {
    const Symbol *y = &c->p->syms[m->sym];
    int n = m->args.n;
    c->sym_used[m->sym] = true;
    if (n > MAX_ARITY) {
        diag_error(c->d, m->loc, "a module has at most %d parameters", MAX_ARITY);
        n = MAX_ARITY;
    }
    if (cc_is_bracket(m->sym) && n) diag_error(c->d, m->loc, "a bracket takes no parameters");
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

/* k is 2^e with 1/k a normal number: x / k and x * (1 / k) are then the same double. */
static bool power_of_two(double k) {
    int e;
    return isfinite(k) && frexp(k, &e) == 0.5 && e > -1020 && e < 1020;
}

/* Slot k of r's plan, arithmetic: computed once however often it is written. */
static void plan_arith(Rule *r, int k) {
    const Slot *sl = &r->slots[k];
    int kind = sl->kind;
    double m = sl->k;
    if (kind == SLOT_DIVK && power_of_two(m)) kind = SLOT_MULK, m = 1 / m;
    for (int a = 0; a < r->narith; a++)
        if (r->arith_kind[a] == kind && r->arith_local[a] == sl->local && r->arith_k[a] == m &&
            signbit(r->arith_k[a]) == signbit(m)) {
            r->dup_dst[r->ndup] = (uint8_t)k;
            r->dup_src[r->ndup++] = r->arith[a];
            return;
        }
    r->arith_kind[r->narith] = (uint8_t)kind;
    r->arith_local[r->narith] = sl->local;
    r->arith_k[r->narith] = m;
    r->arith[r->narith++] = (uint8_t)k;
}

/* The blended form of a plan (Rule.blend), when its shape allows one. */
static void plan_blend(Rule *r) {
    if (!r->planned || r->narith > 1 || !r->nslots) return;
    int local = r->narith ? r->arith_local[0] : r->ncopy ? r->copy_src[0] : -1;
    if (local < 0) return; /* constants only: the template is the plan */
    for (int c = 0; c < r->ncopy; c++)
        if (r->copy_src[c] != local) return;
    for (int c = 0; c < r->ncopy; c++) r->blend_x[r->copy_dst[c]] = UINT64_MAX;
    for (int a = 0; a < r->narith; a++) r->blend_v[r->arith[a]] = UINT64_MAX;
    for (int d = 0; d < r->ndup; d++) r->blend_v[r->dup_dst[d]] = UINT64_MAX;
    r->blend_local = (uint8_t)local;
    r->blend_pairs = (uint8_t)((r->nslots + 1) / 2);
    r->blend = true;
}

void cc_successor(Compiler *c, const Mods *ms, Scope *s, Rule *r, const char *what) {
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
    r->vm_free = true;
    for (int k = 0; k < r->nslots; k++)
        if (r->slots[k].kind == SLOT_CODE) r->vm_free = false;
    r->planned = r->vm_free && r->nslots <= SLOT_PLAN;
    for (int k = 0; r->planned && k < r->nslots; k++) {
        const Slot *sl = &r->slots[k];
        if (sl->kind == SLOT_CONST) r->tmpl[k] = sl->k;
        else if (sl->kind == SLOT_LOCAL) {
            r->copy_dst[r->ncopy] = (uint8_t)k;
            r->copy_src[r->ncopy++] = sl->local;
        } else plan_arith(r, k);
    }
    plan_blend(r);
}

void cc_rule(Compiler *c, const Stmt *s, Rule *out) {
    SylProgram *p = c->p;
    memset(out, 0, sizeof *out);
    out->group = -1;
    Mods pred, left, right, succ, newleft, newright;
    cc_split(c, &s->rule.pred, &pred);
    cc_split(c, &s->rule.left, &left);
    cc_split(c, &s->rule.right, &right);
    cc_split(c, &s->rule.newleft, &newleft);
    cc_split(c, &s->rule.newright, &newright);
    cc_split(c, &s->rule.succ, &succ);
    cc_warn_words(c, &s->rule.succ);
    out->loc = s->rule.loc;
    out->line = s->rule.loc.first_line;
    out->cond = out->weight = -1;
    if (pred.n != 1 || cc_is_bracket(pred.v[0].sym)) {
        const Item *w = s->rule.pred.n == 1 && s->rule.pred.v[0].kind == IT_WORD ? &s->rule.pred.v[0] : NULL;
        const char *near = w ? cc_near_module(c, w->text) : NULL;
        if (near) /* Leef beside a declared Leaf */
            diag_error(c->d, s->rule.loc, "'%s' is not a declared module (did you mean '%s'?)", w->text, near);
        else if (w)
            diag_error(c->d, s->rule.loc,
                       "'%s' is not a declared module: declare it with `module %s`, or write one module "
                       "(a predecessor is one; contexts go with < and >)",
                       w->text, w->text);
        else diag_error(c->d, s->rule.loc, "a predecessor is one module (write contexts with < and >)");
        return;
    }
    const char *names[MAX_LOCALS];
    Scope scope = {.names = names};
    out->pred = module_code(c, &pred.v[0]);
    out->pred_arity = (uint8_t)CODE_ARITY(out->pred);
    bind(c, &pred.v[0], &scope);
    pattern(c, &left, false, &scope, &out->left, &out->nleft);
    pattern(c, &right, true, &scope, &out->right, &out->nright);
    for (int k = 0; k < out->nright; k++)
        if (out->right[k].kind != PAT_MODULE) out->right_branches = true;
    if (s->rule.has_newleft && s->rule.has_newright)
        diag_error(c->d, s->rule.newright_loc,
                   "a rule has a new left context (`<<`, forward steps) or a new right context (`>>`, "
                   "backward steps), not both");
    pattern(c, &newleft, false, &scope, &out->newleft, &out->nnewleft);
    pattern(c, &newright, true, &scope, &out->newright, &out->nnewright);
    for (int k = 0; k < out->nnewright; k++)
        if (out->newright[k].kind != PAT_MODULE) out->newright_branches = true;
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
    cc_successor(c, &succ, &scope, out, "this successor");
}

/* Fast rules are looked up, not scanned: each code a fast rule's context names gets a class
 * 1..K (0: every other code, and no neighbour), and each fast predecessor a table of the
 * first of its rules that matches each pair of neighbour classes. */
enum { MAX_CLASSES = 16 };
static bool build_pick(RuleTable *t, const uint16_t *codes, int ncodes, Arena *a) {
    int n = 1;
    t->ctx_class = arena_alloc_sparse(a, CODE_COUNT);
    if (!t->ctx_class) return false;
    for (int i = 0; i < ncodes; i++) {
        const Dispatch *d = &t->dispatch[codes[i]];
        for (uint32_t j = 0; d->fast && j < d->count; j++) {
            uint16_t side[2] = {d->fast[j].left, d->fast[j].right};
            for (int k = 0; k < 2; k++)
                if (side[k] != CODE_ANY && !t->ctx_class[side[k]]) {
                    if (n == MAX_CLASSES) return true; /* too many: the rules are scanned (nclass 0) */
                    t->ctx_class[side[k]] = (uint8_t)n++;
                }
        }
    }
    t->nclass = n;
    for (int i = 0; i < ncodes; i++) {
        Dispatch *d = &t->dispatch[codes[i]];
        if (!d->fast) continue;
        const Rule **pick = arena_alloc(a, sizeof *pick * (size_t)(n * n));
        if (!pick) return false;
        for (int lc = 0; lc < n; lc++)
            for (int rc = 0; rc < n; rc++)
                for (uint32_t k = 0; k < d->count && !pick[lc * n + rc]; k++) {
                    const FastRule *f = &d->fast[k];
                    if ((f->left == CODE_ANY || t->ctx_class[f->left] == lc) &&
                        (f->right == CODE_ANY || t->ctx_class[f->right] == rc))
                        pick[lc * n + rc] = f->rule;
                }
        d->pick = pick;
    }
    return true;
}

/* d's Choice, when its rules make one (program.h). False when out of memory. */
static bool build_choice(const RuleTable *t, Dispatch *d, Arena *a) {
    if (d->count < 2) return true;
    double total = 0;
    for (uint32_t k = 0; k < d->count; k++) {
        const Rule *r = &t->rules[t->order[d->first + k]];
        if (r->nleft || r->nright || r->nnewleft || r->nnewright || r->cond >= 0 || !r->weighted || r->weight >= 0 ||
            !isfinite(r->const_weight) || r->const_weight < 0)
            return true;
        total += r->const_weight; /* as the general path sums them (rewrite.c, weigh) */
    }
    if (!isfinite(total)) return true;
    Choice *c = arena_alloc(a, sizeof *c);
    const Rule **rule = arena_alloc(a, sizeof *rule * d->count);
    double *weight = arena_alloc(a, sizeof *weight * d->count);
    if (!c || !rule || !weight) return false;
    for (uint32_t k = 0; k < d->count; k++) {
        rule[k] = &t->rules[t->order[d->first + k]];
        weight[k] = rule[k]->const_weight;
    }
    *c = (Choice){(int)d->count, false, total, rule, weight};
    for (uint32_t k = 0; k < d->count; k++) c->zero |= weight[k] == 0;
    d->choice = c;
    return true;
}

static int by_code(const void *a, const void *b) { return (int)*(const uint16_t *)a - (int)*(const uint16_t *)b; }

/* Dispatch and fast paths over the rules pick[0..npick) of t->rules, tried in that order.
 * Only the entries of the codes the rules rewrite are written: the rest of the dispatch
 * stays in pages never touched (arena_alloc_sparse), and start-up costs what the model
 * uses, not 65,536 entries per table. */
static bool build(RuleTable *t, const uint16_t *pick, int npick, Arena *a) {
    t->dispatch = arena_alloc_sparse(a, sizeof *t->dispatch * CODE_COUNT);
    t->order = arena_alloc(a, sizeof *t->order * (size_t)(npick ? npick : 1));
    uint16_t *codes = arena_alloc(a, sizeof *codes * (size_t)(npick ? npick : 1)); /* distinct, ascending */
    if (!t->dispatch || !t->order || !codes) return false;
    int ncodes = 0;
    for (int i = 0; i < npick; i++)
        if (!t->dispatch[t->rules[pick[i]].pred].count++) codes[ncodes++] = t->rules[pick[i]].pred;
    qsort(codes, (size_t)ncodes, sizeof *codes, by_code);
    uint32_t at = 0;
    for (int i = 0; i < ncodes; i++) { /* in code order, as the whole table was laid out */
        Dispatch *d = &t->dispatch[codes[i]];
        d->first = at;
        at += d->count;
        d->count = 0;
    }
    for (int i = 0; i < npick; i++) {
        const Rule *r = &t->rules[pick[i]];
        Dispatch *d = &t->dispatch[r->pred];
        t->order[d->first + d->count++] = pick[i];
        if (r->nleft || r->nright) t->has_context = true;
        if (r->nnewleft || r->nnewright) t->has_newctx = true;
        if (r->nleft) t->ctx_left = true;
        /* each rule's right context is matched its own way, whatever the others' are: a
         * branch in one rule does not take the links from the others */
        if (r->right_branches) t->ctx_branches = true;
        else if (r->nright) t->ctx_right = true;
        if (r->nleft > 1 || (r->nright > 1 && !r->right_branches)) t->ctx_index = true;
        for (int k = 0; k < r->nleft; k++)
            if (CODE_ARITY(r->left[k].code)) t->ctx_index = true;
        for (int k = 0; k < r->nright && !r->right_branches; k++)
            if (CODE_ARITY(r->right[k].code)) t->ctx_index = true;
        if (r->nslots) t->emits_params = true;
        if (r->nsucc > t->max_succ) t->max_succ = r->nsucc;
        if (r->nslots > t->max_succ_params) t->max_succ_params = r->nslots;
    }
    for (int i = 0; i < npick; i++) { /* the codes new contexts name: only their links are kept */
        const Rule *r = &t->rules[pick[i]];
        if (r->nnewleft && !t->newleft_code && !(t->newleft_code = arena_alloc_sparse(a, CODE_COUNT * sizeof(bool))))
            return false;
        for (int k = 0; k < r->nnewleft; k++) t->newleft_code[r->newleft[k].code] = true;
        if (r->newright_branches) t->newright_branches = true;
        if (r->nnewright && !t->newright_code && !(t->newright_code = arena_alloc_sparse(a, CODE_COUNT * sizeof(bool))))
            return false;
        for (int k = 0; k < r->nnewright; k++) t->newright_code[r->newright[k].code] = true;
    }
    t->all_plain = true;
    for (int i = 0; i < ncodes; i++) {
        Dispatch *d = &t->dispatch[codes[i]];
        if (d->count > 1) t->all_plain = false;
        if (d->count != 1) continue;
        const Rule *r = &t->rules[t->order[d->first]];
        if (!r->nleft && !r->nright && !r->nnewleft && !r->nnewright && r->cond < 0 && !r->weighted) d->plain = r;
        else t->all_plain = false;
    }
    if (t->all_plain) { /* run_chunk_plain's runs: only it reads stay */
        if (!(t->stay = arena_alloc(a, CODE_COUNT))) return false;
        for (int ar = 0; ar <= CODE_ARITY(CODE_COUNT - 1); ar++) /* codes of one arity are consecutive */
            memset(t->stay + CODE(0, ar), 1 + ar, MAX_SYMBOLS);
        for (int i = 0; i < ncodes; i++) t->stay[codes[i]] = 0;
    }
    for (int i = 0; i < ncodes; i++)
        if (!build_choice(t, &t->dispatch[codes[i]], a)) return false;
    t->light = true;
    for (int i = 0; i < npick; i++) {
        const Rule *r = &t->rules[pick[i]];
        const Dispatch *d = &t->dispatch[r->pred];
        bool fast = r->nleft <= 1 && r->nright <= 1 && !r->nnewleft && !r->nnewright && r->cond < 0 && !r->weighted;
        if (!r->vm_free || !(d->plain || d->choice || fast)) t->light = false;
    }
    t->all_fast = true;
    for (int i = 0; i < ncodes; i++) {
        Dispatch *d = &t->dispatch[codes[i]];
        if (!d->count || d->plain) continue;
        bool fast = true;
        for (uint32_t k = 0; k < d->count && fast; k++) {
            const Rule *r = &t->rules[t->order[d->first + k]];
            fast = r->nleft <= 1 && r->nright <= 1 && !r->nnewleft && !r->nnewright && r->cond < 0 && !r->weighted &&
                   (!r->nleft || !CODE_ARITY(r->left[0].code)) &&
                   (!r->nright || (r->right[0].kind == PAT_MODULE && !CODE_ARITY(r->right[0].code)));
        }
        if (!fast) {
            t->all_fast = false;
            continue;
        }
        FastRule *f = arena_alloc(a, sizeof *f * d->count);
        if (!f) return false;
        for (uint32_t k = 0; k < d->count; k++) {
            const Rule *r = &t->rules[t->order[d->first + k]];
            f[k].left = r->nleft ? r->left[0].code : CODE_ANY;
            f[k].right = r->nright ? r->right[0].code : CODE_ANY;
            f[k].rule = r;
        }
        d->fast = f;
    }
    return build_pick(t, codes, ncodes, a);
}

/* Every rule in file order: what a model without groups derives with, and what the
 * disassembler and the checks read. */
void cc_build_table(Compiler *c, RuleTable *t) {
    if (!t->nrules) return;
    uint16_t *all = arena_alloc(c->tmp, sizeof *all * (size_t)t->nrules);
    for (int i = 0; i < t->nrules; i++) all[i] = (uint16_t)i;
    build(t, all, t->nrules, &c->p->arena);
}

bool lang_table_select(const SylProgram *p, int table, uint64_t active, RuleTable *t, Arena *a) {
    const RuleTable *base = &p->tables[table];
    memset(t, 0, sizeof *t);
    t->rules = base->rules;
    t->maxdepth = base->maxdepth;
    uint16_t *pick = arena_alloc(a, sizeof *pick * (size_t)(base->nrules ? base->nrules : 1));
    if (!pick) return false;
    int n = 0;
    for (int i = 0; i < base->nrules; i++) {
        int g = base->rules[i].group;
        if (g >= 0 && (active >> g & 1)) pick[n++] = (uint16_t)i;
    }
    for (int i = 0; i < base->nrules; i++)
        if (base->rules[i].group < 0) pick[n++] = (uint16_t)i;
    t->nrules = n; /* the rules taking part; their indices stay those of base->rules */
    return !n || build(t, pick, n, a);
}
