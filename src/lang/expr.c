/* Expressions: resolve names, fold what is known at compile time, emit bytecode. */
#include <math.h>
#include <string.h>

#include "lang/builtins.h"
#include "lang/compiler.h"
#include "lang/opcodes.h"
#include "lang/vm.h"

static Expr *number(Compiler *c, Expr *like, double v) {
    Expr *e = arena_alloc(c->tmp, sizeof *e);
    e->kind = EX_NUM;
    e->loc = like->loc;
    e->num = v;
    return e;
}

static bool is_num(const Expr *e) { return e->kind == EX_NUM; }

static int binary(int op, double a, double b, double *r) {
    switch (op) {
    case '+': *r = a + b; break;
    case '-': *r = a - b; break;
    case '*': *r = a * b; break;
    case '/':
        if (b == 0) return EVAL_DIV_ZERO;
        *r = a / b;
        break;
    case '%':
        if (b == 0) return EVAL_DIV_ZERO;
        *r = fmod(a, b);
        break;
    case '^': return syl_power(a, b, r);
    case '<': *r = a < b; break;
    case '>': *r = a > b; break;
    case BIN_LE: *r = a <= b; break;
    case BIN_GE: *r = a >= b; break;
    case BIN_EQ: *r = a == b; break;
    case BIN_NE: *r = a != b; break;
    }
    return isfinite(*r) ? EVAL_OK : EVAL_NONFINITE;
}

static Expr *fold_call(Compiler *c, Expr *e, Scope *s, bool *random) { /* through cc_fold */
    bool all_const = true;
    for (int i = 0; i < e->args.n; i++) {
        e->args.v[i] = cc_fold(c, e->args.v[i], s, random);
        all_const &= is_num(e->args.v[i]);
    }
    int id, n = e->args.n;
    if ((id = namemap_get(&c->fns, e->name, -1)) >= 0) {
        Function *f = &c->p->fns[id];
        c->fn_used[id] = true;
        if (n != f->nparams) {
            diag_error(c->d, e->loc, "function '%s' takes %d argument%s, not %d", e->name, f->nparams,
                       f->nparams == 1 ? "" : "s", n);
            return number(c, e, 0);
        }
        cc_function(c, id);
        if (c->fn_random[id]) *random = true;
        if (f->external && !c->extern_called) c->extern_called = f->name;
        /* The body's error was reported where it is; there is no code to run for this call. */
        if (f->state == 3) return number(c, e, 0);
        if (all_const && f->state == 2 && !c->fn_random[id]) {
            double args[MAX_LOCALS], r;
            for (int i = 0; i < n; i++) args[i] = e->args.v[i]->num;
            Rng rng = rng_stream(0, 0, 0, 0);
            VmFault fault;
            if (vm_run(c->p, f->pc, args, &rng, &r, &fault)) {
                diag_error(c->d, e->loc, "in '%s': %s", e->name, syl_eval_error_text(fault.status));
                return number(c, e, 0);
            }
            return number(c, e, r);
        }
        return e;
    }
    if ((id = namemap_get(&c->curves, e->name, -1)) >= 0) {
        c->curve_used[id] = true;
        if (n != 1) {
            diag_error(c->d, e->loc, "curve '%s' takes 1 argument, not %d", e->name, n);
            return number(c, e, 0);
        }
        if (!c->p->curves[id].n) {
            diag_error(c->d, e->loc, "curve '%s' is used before its points are known", e->name);
            return number(c, e, 0);
        }
        return all_const ? number(c, e, curve_eval(&c->p->curves[id], e->args.v[0]->num)) : e;
    }
    if ((id = syl_builtin_find(e->name)) >= 0) {
        const Builtin *b = &syl_builtins[id];
        if (n != b->nargs) {
            diag_error(c->d, e->loc, "'%s' takes %d argument%s, not %d", e->name, b->nargs,
                       b->nargs == 1 ? "" : "s", n);
            return number(c, e, 0);
        }
        if (b->random) *random = true;
        if (all_const && !b->random) {
            double args[3], r;
            for (int i = 0; i < n; i++) args[i] = e->args.v[i]->num;
            int st = syl_builtin_apply(id, args, NULL, &r);
            if (st) {
                diag_error(c->d, e->loc, "%s: %s", e->name, syl_eval_error_text(st));
                return number(c, e, 0);
            }
            return number(c, e, r);
        }
        return e;
    }
    diag_error(c->d, e->loc, "unknown function '%s'", e->name);
    return number(c, e, 0);
}

static Expr *fold(Compiler *c, Expr *e, Scope *s, bool *random) {
    switch (e->kind) {
    case EX_NUM:
    case EX_LOCAL: return e;
    case EX_NAME: {
        for (int i = s ? s->n - 1 : -1; i >= 0; i--)
            if (!strcmp(s->names[i], e->name)) {
                if (s->used) s->used[i] = true;
                e->kind = EX_LOCAL;
                e->op = i;
                return e;
            }
        int id = namemap_get(&c->values, e->name, -1);
        if (id >= 0) {
            Value *v = &c->vals[id];
            v->used = true;
            if (!v->known) {
                diag_error(c->d, e->loc, "'%s' is used before its value is known", e->name);
                return number(c, e, 0);
            }
            return number(c, e, v->v);
        }
        if (namemap_get(&c->fns, e->name, -1) >= 0 || namemap_get(&c->curves, e->name, -1) >= 0 ||
            syl_builtin_find(e->name) >= 0)
            diag_error(c->d, e->loc, "'%s' is a function: call it as %s(...)", e->name, e->name);
        else if (!strcmp(e->name, "step")) /* the step number is a `use` line's (docs/language.md §20) */
            diag_error(c->d, e->loc, "unknown name 'step' (the step number is read in `use NAME when ...` "
                                     "lines: put the rule in a group)");
        else
            diag_error(c->d, e->loc, "unknown name '%s'", e->name);
        return number(c, e, 0);
    }
    case EX_UNARY:
        e->a = cc_fold(c, e->a, s, random);
        if (is_num(e->a)) return number(c, e, e->op == '-' ? -e->a->num : e->a->num == 0);
        return e;
    case EX_BINARY: {
        e->a = cc_fold(c, e->a, s, random);
        e->b = cc_fold(c, e->b, s, random);
        if ((e->op == '/' || e->op == '%') && is_num(e->b) && e->b->num == 0) {
            diag_error(c->d, e->loc, "division by zero");
            return number(c, e, 0);
        }
        if (is_num(e->a) && is_num(e->b)) {
            double r = 0;
            int st = binary(e->op, e->a->num, e->b->num, &r);
            if (st) diag_error(c->d, e->loc, "%s", syl_eval_error_text(st));
            return number(c, e, r);
        }
        return e;
    }
    case EX_AND:
    case EX_OR: {
        e->a = cc_fold(c, e->a, s, random);
        e->b = cc_fold(c, e->b, s, random);
        if (is_num(e->a)) {
            bool a = e->a->num != 0;
            if (e->kind == EX_AND && !a) return number(c, e, 0);
            if (e->kind == EX_OR && a) return number(c, e, 1);
            if (is_num(e->b)) return number(c, e, e->b->num != 0);
        }
        return e;
    }
    case EX_COND:
        e->a = cc_fold(c, e->a, s, random);
        e->b = cc_fold(c, e->b, s, random);
        e->c = cc_fold(c, e->c, s, random);
        if (is_num(e->a)) return e->a->num != 0 ? e->b : e->c;
        return e;
    case EX_CALL: return fold_call(c, e, s, random);
    }
    return e;
}

/* fold, with the C stack bounded: an expression deeper than CC_MAX_DEPTH is an error. */
Expr *cc_fold(Compiler *c, Expr *e, Scope *s, bool *random) {
    if (c->depth >= CC_MAX_DEPTH) {
        if (!c->too_deep)
            diag_error(c->d, e->loc, "expression is too deeply nested (at most %d operations inside one another)",
                       CC_MAX_DEPTH);
        c->too_deep = true;
        return number(c, e, 0);
    }
    c->depth++;
    e = fold(c, e, s, random);
    c->depth--;
    return e;
}

bool cc_const(Compiler *c, Expr *e, double *out) {
    bool random = false;
    int before = c->d->errors;
    c->extern_called = NULL;
    e = cc_fold(c, e, NULL, &random);
    if (c->d->errors != before) return false;
    if (c->extern_called) {
        diag_error(c->d, e->loc, "a value known at compile time cannot call extern function '%s'", c->extern_called);
        return false;
    }
    if (random) {
        diag_error(c->d, e->loc, "a value known at compile time cannot be random");
        return false;
    }
    if (!is_num(e)) { /* a call to a recursive function still being compiled */
        diag_error(c->d, e->loc, "this value is not known at compile time");
        return false;
    }
    *out = e->num;
    return true;
}

/* ---- code generation ---- */

static uint32_t constant(Compiler *c, double v) {
    SylProgram *p = c->p;
    for (int i = 0; i < p->nconsts; i++)
        if (!memcmp(&p->consts[i], &v, sizeof v)) return (uint32_t)i;
    *VEC_PUSH(&p->arena, p->consts, p->nconsts, p->constcap) = v;
    return (uint32_t)p->nconsts - 1;
}

static int emit(Compiler *c, Emitter *em, Opcode op, uint32_t a, SylLoc loc) {
    int effect = syl_op_effects[op];
    if (op == OP_CALLB) effect = 1 - syl_builtins[a].nargs;
    if (op == OP_CALLF) effect = 1 - c->p->fns[a].nparams;
    em->depth += effect;
    if (em->depth > em->maxdepth) em->maxdepth = em->depth;
    int cap = em->cap;
    *VEC_PUSH(c->tmp, em->code, em->n, em->cap) = INSTR(op, a);
    em->n--;
    *VEC_PUSH(c->tmp, em->loc, em->n, cap) = loc;
    return em->n - 1;
}

static void patch(Emitter *em, int at, int target) {
    em->code[at] = INSTR(INSTR_OP(em->code[at]), (uint32_t)target);
}

static void gen(Compiler *c, Emitter *em, Expr *e) {
    switch (e->kind) {
    case EX_NUM: emit(c, em, OP_PUSHK, constant(c, e->num), e->loc); break;
    case EX_LOCAL: emit(c, em, OP_LOCAL, (uint32_t)e->op, e->loc); break;
    case EX_NAME: emit(c, em, OP_PUSHK, constant(c, 0), e->loc); break; /* reported by fold */
    case EX_UNARY:
        gen(c, em, e->a);
        emit(c, em, e->op == '-' ? OP_NEG : OP_NOT, 0, e->loc);
        break;
    case EX_BINARY: {
        static const struct { int op; Opcode code, kcode; } ops[] = {
            {'+', OP_ADD, OP_ADDK}, {'-', OP_SUB, OP_SUBK}, {'*', OP_MUL, OP_MULK},
            {'/', OP_DIV, OP_DIVK}, {'%', OP_MOD, OP_MOD},  {'^', OP_POW, OP_POW},
            {'<', OP_LT, OP_LT},    {'>', OP_GT, OP_GT},    {BIN_LE, OP_LE, OP_LE},
            {BIN_GE, OP_GE, OP_GE},  {BIN_EQ, OP_EQ, OP_EQ},  {BIN_NE, OP_NE, OP_NE},
        };
        int i = 0;
        while (ops[i].op != e->op) i++;
        gen(c, em, e->a);
        if (is_num(e->b) && ops[i].kcode != ops[i].code) {
            emit(c, em, ops[i].kcode, constant(c, e->b->num), e->loc);
        } else {
            gen(c, em, e->b);
            emit(c, em, ops[i].code, 0, e->loc);
        }
        break;
    }
    case EX_AND:
    case EX_OR: {
        gen(c, em, e->a);
        int j = emit(c, em, e->kind == EX_AND ? OP_ANDJ : OP_ORJ, 0, e->loc);
        em->depth--; /* the branch taken pops */
        gen(c, em, e->b);
        emit(c, em, OP_BOOL, 0, e->loc);
        patch(em, j, em->n);
        break;
    }
    case EX_COND: {
        gen(c, em, e->a);
        int jf = emit(c, em, OP_JFALSE, 0, e->loc);
        gen(c, em, e->b);
        int je = emit(c, em, OP_JMP, 0, e->loc);
        em->depth--; /* only one side's value is on the stack */
        patch(em, jf, em->n);
        gen(c, em, e->c);
        patch(em, je, em->n);
        break;
    }
    case EX_CALL: {
        for (int i = 0; i < e->args.n; i++) gen(c, em, e->args.v[i]);
        int id;
        if ((id = namemap_get(&c->fns, e->name, -1)) >= 0)
            emit(c, em, OP_CALLF, (uint32_t)id, e->loc);
        else if ((id = namemap_get(&c->curves, e->name, -1)) >= 0)
            emit(c, em, OP_CURVE, (uint32_t)id, e->loc);
        else
            emit(c, em, OP_CALLB, (uint32_t)syl_builtin_find(e->name), e->loc);
        break;
    }
    }
}

int32_t cc_expr(Compiler *c, Expr *e, Scope *s, bool *random) {
    bool r = false;
    int before = c->d->errors;
    e = cc_fold(c, e, s, &r);
    if (random) *random = r;
    if (c->d->errors != before) return -1;
    Emitter em = {0};
    gen(c, &em, e);
    emit(c, &em, OP_RET, 0, e->loc);
    if (em.maxdepth > VM_STACK) {
        diag_error(c->d, e->loc, "expression is too deeply nested");
        return -1;
    }
    SylProgram *p = c->p;
    int32_t base = p->ncode;
    for (int i = 0; i < em.n; i++) {
        uint32_t ins = em.code[i];
        if (syl_op_kinds[INSTR_OP(ins)] == 'J') ins = INSTR(INSTR_OP(ins), INSTR_A(ins) + (uint32_t)base);
        int cap = p->codecap;
        *VEC_PUSH(&p->arena, p->code, p->ncode, p->codecap) = ins;
        p->ncode--;
        *VEC_PUSH(&p->arena, p->code_loc, p->ncode, cap) = em.loc[i];
    }
    return base;
}

void cc_function(Compiler *c, int id) {
    Function *f = &c->p->fns[id];
    if (f->state) return;
    f->state = 1;
    Stmt *st = c->fn_stmts[id];
    Scope s = {.names = st->params.v, .n = st->params.n};
    bool random = false;
    int32_t pc = st->value ? cc_expr(c, st->value, &s, &random) : 0; /* an extern without a default: no code */
    f->pc = pc < 0 ? 0 : (uint32_t)pc;
    c->fn_random[id] = random || f->external; /* what an extern gives is known only when it runs */
    f->state = pc < 0 ? 3 : 2;
}
