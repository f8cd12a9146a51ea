/* Declarations: the names of modules, values, functions and curves, and the values' evaluation. */
#include <string.h>

#include "lang/compiler.h"

static bool defined_elsewhere(Compiler *c, const char *name, SylLoc loc) {
    if (namemap_get(&c->values, name, -1) >= 0 || namemap_get(&c->fns, name, -1) >= 0 ||
        namemap_get(&c->curves, name, -1) >= 0) {
        diag_error(c->d, loc, "'%s' is already defined", name);
        return true;
    }
    return false;
}

void cc_declare(Compiler *c, Stmt *s, bool top) {
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
        f->external = s->external;
        f->has_default = s->value != NULL;
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

/* Values, in the order written: a const may use the ones before it. */
void cc_evaluate(Compiler *c, Stmt *s) {
    SylProgram *p = c->p;
    if (s->kind == ST_CONST || s->kind == ST_PARAM) {
        int id = namemap_get(&c->values, s->name, -1);
        if (id < 0 || c->vals[id].loc.first_line != s->loc.first_line ||
            c->vals[id].loc.first_column != s->loc.first_column)
            return; /* a duplicate, already reported */
        Value *v = &c->vals[id];
        const SylOverride *o = s->kind == ST_PARAM ? cc_find_override(c, s->name) : NULL;
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
