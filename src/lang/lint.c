/* Warnings of `sylva check`: things that are legal but almost certainly not meant. */
#include <string.h>

#include "lang/compiler.h"
#include "util/closest.h"

static const char *plural(int n) { return n == 1 ? "" : "s"; }

static void mark(bool *made, const Rule *r) {
    for (int i = 0; i < r->nsucc; i++) made[r->succ[i]] = true;
}

/* The (symbol, parameter count) codes that some string holds: from the axiom through the
 * successors of every rule whose predecessor is reached, in every table (decomposition and
 * interpretation make modules too). An over-estimate, so that what it calls unreached is:
 * conditions, contexts and weights are not read. */
static bool *reached(Compiler *c) {
    const SylProgram *p = c->p;
    bool *made = arena_alloc(c->tmp, sizeof(bool) * CODE_COUNT);
    mark(made, &p->axiom);
    bool *done[TABLE_COUNT];
    for (int t = 0; t < TABLE_COUNT; t++) done[t] = arena_alloc(c->tmp, sizeof(bool) * (size_t)(p->tables[t].nrules + 1));
    for (bool more = true; more;) {
        more = false;
        for (int t = 0; t < TABLE_COUNT; t++)
            for (int i = 0; i < p->tables[t].nrules; i++) {
                const Rule *r = &p->tables[t].rules[i];
                if (done[t][i] || !made[r->pred]) continue;
                done[t][i] = more = true;
                mark(made, r);
            }
    }
    return made;
}

/* Made by some rule, reached or not. */
static bool *written(Compiler *c) {
    const SylProgram *p = c->p;
    bool *made = arena_alloc(c->tmp, sizeof(bool) * CODE_COUNT);
    mark(made, &p->axiom);
    for (int t = 0; t < TABLE_COUNT; t++)
        for (int i = 0; i < p->tables[t].nrules; i++) mark(made, &p->tables[t].rules[i]);
    return made;
}

/* A rule for X(a, b) when strings hold X only as X(a): the parameter count it is made with. */
static int other_arity(const bool *made, int code) {
    int other = -1;
    for (int a = 0; a <= MAX_ARITY; a++)
        if (made[CODE(CODE_SYM(code), a)]) other = a;
    return other;
}

static void warn_arity(Compiler *c, const Rule *r, int other) {
    diag_warning(c->d, r->loc, "this rule never applies: '%s' is only made with %d parameter%s, not %d",
                 c->p->syms[CODE_SYM(r->pred)].name, other, plural(other), CODE_ARITY(r->pred));
}

static void lint_table(Compiler *c, const RuleTable *t, const bool *made, const bool *any) {
    const SylProgram *p = c->p;
    for (int i = 0; i < t->nrules; i++) {
        const Rule *r = &t->rules[i];
        const Symbol *y = &p->syms[CODE_SYM(r->pred)];
        if (!made[r->pred]) {
            int other = other_arity(made, r->pred);
            if (other >= 0) warn_arity(c, r, other);
            else if (other_arity(any, r->pred) >= 0)
                diag_warning(c->d, r->loc, "this rule never applies: no string holds '%s' (only rules that never "
                             "apply make it)", y->name);
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
            if (q->pred == r->pred && q->group == r->group && !q->nleft && !q->nright && !q->nnewleft &&
                !q->nnewright && q->cond < 0 && !q->weighted) {
                diag_warning(c->d, r->loc, "this rule never applies: the rule at line %d always applies first",
                             q->line);
                break;
            }
        }
        if (r->weighted && r->weight < 0 && r->const_weight == 0)
            diag_warning(c->d, r->loc, "this rule's weight is zero: it is never chosen");
    }
}

/* A group that no `use` line makes take part, or only with a condition that is always false. */
static void lint_groups(Compiler *c) {
    const SylProgram *p = c->p;
    for (int g = 0; g < p->ngroups; g++) {
        const Group *gr = &p->groups[g];
        bool used = false;
        for (int k = 0; k < gr->nwhen && !used; k++) {
            double v;
            used = !cc_code_constant(p, gr->when[k], &v) || v != 0;
        }
        if (!used)
            diag_warning(c->d, gr->loc, gr->nwhen ? "group '%s' is never used: its `use` condition%s always false"
                                                  : "group '%s' is never used: no `use %s when ...` line",
                         gr->name, gr->nwhen ? (gr->nwhen == 1 ? " is" : "s are") : gr->name);
    }
}

void cc_lint(Compiler *c) {
    const SylProgram *p = c->p;
    bool *made = reached(c), *any = written(c);
    for (int t = 0; t < TABLE_COUNT; t++) lint_table(c, &p->tables[t], made, any);
    lint_groups(c);
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

/* ---- the warnings of mistakes: `sylva check`, and every command that derives ---- */

const char *cc_near_module(Compiler *c, const char *word) {
    const SylProgram *p = c->p;
    for (int s = 0; s < p->nsyms; s++)
        if (p->syms[s].declared && strlen(p->syms[s].name) >= 2 && closest_near(word, p->syms[s].name))
            return p->syms[s].name;
    return NULL;
}

/* A word read letter by letter (no declared module in it) although it is close to a
 * declared name: Leef beside `module Leaf`. */
void cc_warn_words(Compiler *c, const Items *items) {
    if (!(c->warn & SYL_WARN_MISTAKES) || c->max_declared_len < 2) return;
    for (int i = 0; i < items->n; i++) {
        const Item *it = &items->v[i];
        int len = (int)strlen(it->text);
        if (it->kind != IT_WORD || len < 2) continue;
        bool has_declared = false;
        for (int pos = 0; pos < len && !has_declared; pos++)
            for (int l = 2; l <= len - pos && l <= c->max_declared_len; l++)
                if (namemap_get(&c->declared, it->text + pos, l) >= 0) has_declared = true;
        const char *near = has_declared ? NULL : cc_near_module(c, it->text);
        if (near)
            diag_warning(c->d, it->loc, "'%s' is not a declared module: it is read as %d modules, one per letter "
                         "(did you mean '%s'?)", it->text, len, near);
    }
}

/* Whether some module that a string may hold draws (a segment, a polygon, an organ); a
 * shoot rule's string (it holds `shoot`) is read by its grow block, not drawn. */
static bool draws(const SylProgram *p, const bool *made) {
    for (int code = 0; code < CODE_COUNT; code++) {
        if (!made[code] || CODE_SYM(code) >= p->nsyms) continue;
        const Symbol *y = &p->syms[CODE_SYM(code)];
        if ((turtle_command_flags(y->turtle) & TF_DRAWS) || !strcmp(y->name, "shoot")) return true;
    }
    return false;
}

void cc_warn(Compiler *c) {
    const SylProgram *p = c->p;
    if (!lang_kind_is(p->kind, KF_RULES)) return;
    bool *made = reached(c);
    if (!c->opt->lint && (c->warn & SYL_WARN_MISTAKES)) /* check's lint says it with the others */
        for (int t = 0; t < TABLE_COUNT; t++)
            for (int i = 0; i < p->tables[t].nrules; i++) {
                const Rule *r = &p->tables[t].rules[i];
                int other = made[r->pred] ? -1 : other_arity(made, r->pred);
                if (other >= 0) warn_arity(c, r, other);
            }
    if ((c->warn & SYL_WARN_DRAWS) && p->axiom.loc.first_line && !draws(p, made))
        diag_warning(c->d, p->axiom.loc, "model '%s' draws nothing: no string it makes holds F, G, a polygon or "
                     "an organ", p->name);
}
