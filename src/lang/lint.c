/* Warnings of `sylva check`: things that are legal but almost certainly not meant. */
#include <string.h>

#include "lang/compiler.h"

static const char *plural(int n) { return n == 1 ? "" : "s"; }

static void mark(bool *made, const Rule *r) {
    for (int i = 0; i < r->nsucc; i++) made[r->succ[i]] = true;
}

static void lint_table(Compiler *c, const RuleTable *t, const bool *made) {
    const SylProgram *p = c->p;
    for (int i = 0; i < t->nrules; i++) {
        const Rule *r = &t->rules[i];
        const Symbol *y = &p->syms[CODE_SYM(r->pred)];
        int ar = CODE_ARITY(r->pred);
        if (!made[r->pred]) {
            int other = -1;
            for (int a = 0; a <= MAX_ARITY; a++)
                if (made[CODE(CODE_SYM(r->pred), a)]) other = a;
            if (other >= 0)
                diag_warning(c->d, r->loc,
                             "this rule never applies: '%s' is only made with %d parameter%s, not %d",
                             y->name, other, plural(other), ar);
            else
                diag_warning(c->d, r->loc, "this rule never applies: neither the axiom nor any rule makes '%s'",
                             y->name);
            continue;
        }
        double v;
        if (cc_code_constant(p, r->cond, &v) && v == 0) {
            diag_warning(c->d, r->loc, "this rule never applies: its condition is always false");
            continue;
        }
        /* a new context of a direction the model never derives in (docs/language.md §9.7) */
        bool always = p->direction_when < 0;
        if (always && r->nnewright && !p->backward) {
            diag_warning(c->d, r->loc, "this rule never applies: a new right context (`>>`) is matched only in "
                                       "backward steps (see `direction`)");
            continue;
        }
        if (always && r->nnewleft && p->backward) {
            diag_warning(c->d, r->loc, "this rule never applies: a new left context (`<<`) is matched only in "
                                       "forward steps, and the model says `direction backward`");
            continue;
        }
        /* a rule after an unconditional, context-free, unweighted one for the same module */
        for (int j = 0; j < i; j++) {
            const Rule *q = &t->rules[j];
            if (q->pred == r->pred && !q->nleft && !q->nright && !q->nnewleft && !q->nnewright && q->cond < 0 &&
                !q->weighted) {
                diag_warning(c->d, r->loc, "this rule never applies: the rule at line %d always applies first",
                             q->line);
                break;
            }
        }
        if (r->weighted && r->weight < 0 && r->const_weight == 0)
            diag_warning(c->d, r->loc, "this rule's weight is zero: it is never chosen");
    }
}

void cc_lint(Compiler *c) {
    const SylProgram *p = c->p;
    bool *made = arena_alloc(c->tmp, sizeof(bool) * CODE_COUNT);
    mark(made, &p->axiom);
    for (int t = 0; t < TABLE_COUNT; t++)
        for (int i = 0; i < p->tables[t].nrules; i++) mark(made, &p->tables[t].rules[i]);
    for (int t = 0; t < TABLE_COUNT; t++) lint_table(c, &p->tables[t], made);
    for (int s = 0; s < p->nsyms; s++)
        if (p->syms[s].declared && !c->sym_used[s])
            diag_warning(c->d, p->syms[s].decl_loc, "module '%s' is declared but never used", p->syms[s].name);
    for (int i = 0; i < c->nvals; i++)
        if (!c->vals[i].used && !c->vals[i].top)
            diag_warning(c->d, c->vals[i].loc, "%s '%s' is never used", c->vals[i].is_param ? "param" : "const",
                         c->vals[i].name);
    for (int i = 0; i < p->nfns; i++)
        if (!c->fn_used[i]) diag_warning(c->d, p->fns[i].loc, "function '%s' is never used", p->fns[i].name);
    for (int i = 0; i < p->ncurves; i++)
        if (!c->curve_used[i]) diag_warning(c->d, p->curves[i].loc, "curve '%s' is never used", p->curves[i].name);
}
