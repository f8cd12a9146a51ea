/* The expression VM's interpreter: a stack machine over the instructions of lang/opcodes.h. */
#include "lang/vm.h"

#include <math.h>

#include "lang/builtins.h"
#include "lang/opcodes.h"

enum { MAX_CALL_DEPTH = 200 };

static int run(const SylProgram *p, uint32_t pc, const double *locals, Rng *rng, double *out,
               VmFault *fault, int depth) {
    double st[VM_STACK];
    int sp = -1;
    const uint32_t *code = p->code;
    int status;
    for (;;) {
        uint32_t ins = code[pc];
        uint32_t a = INSTR_A(ins);
        switch (INSTR_OP(ins)) {
        case OP_PUSHK: st[++sp] = p->consts[a]; break;
        case OP_LOCAL: st[++sp] = locals[a]; break;
        case OP_ADD: sp--; st[sp] += st[sp + 1]; break;
        case OP_SUB: sp--; st[sp] -= st[sp + 1]; break;
        case OP_MUL: sp--; st[sp] *= st[sp + 1]; break;
        case OP_DIV:
            sp--;
            if (st[sp + 1] == 0) { status = EVAL_DIV_ZERO; goto fail; }
            st[sp] /= st[sp + 1];
            break;
        case OP_MOD:
            sp--;
            if (st[sp + 1] == 0) { status = EVAL_DIV_ZERO; goto fail; }
            st[sp] = fmod(st[sp], st[sp + 1]);
            break;
        case OP_POW:
            sp--;
            status = syl_power(st[sp], st[sp + 1], &st[sp]);
            if (status) goto fail;
            break;
        case OP_ADDK: st[sp] += p->consts[a]; break;
        case OP_SUBK: st[sp] -= p->consts[a]; break;
        case OP_MULK: st[sp] *= p->consts[a]; break;
        case OP_DIVK: st[sp] /= p->consts[a]; break; /* the compiler refuses a zero k */
        case OP_NEG: st[sp] = -st[sp]; break;
        case OP_NOT: st[sp] = st[sp] == 0; break;
        case OP_LT: sp--; st[sp] = st[sp] < st[sp + 1]; break;
        case OP_LE: sp--; st[sp] = st[sp] <= st[sp + 1]; break;
        case OP_GT: sp--; st[sp] = st[sp] > st[sp + 1]; break;
        case OP_GE: sp--; st[sp] = st[sp] >= st[sp + 1]; break;
        case OP_EQ: sp--; st[sp] = st[sp] == st[sp + 1]; break;
        case OP_NE: sp--; st[sp] = st[sp] != st[sp + 1]; break;
        case OP_JMP: pc = a; continue;
        case OP_JFALSE:
            if (st[sp--] == 0) { pc = a; continue; }
            break;
        case OP_ANDJ:
            if (st[sp] == 0) { st[sp] = 0; pc = a; continue; }
            sp--;
            break;
        case OP_ORJ:
            if (st[sp] != 0) { st[sp] = 1; pc = a; continue; }
            sp--;
            break;
        case OP_BOOL: st[sp] = st[sp] != 0; break;
        case OP_CALLB: {
            int n = syl_builtins[a].nargs;
            sp -= n - 1;
            status = syl_builtin_apply((int)a, &st[sp], rng, &st[sp]);
            if (status) goto fail;
            break;
        }
        case OP_CALLF: {
            const Function *f = &p->fns[a];
            if (depth >= MAX_CALL_DEPTH) { status = EVAL_DEPTH; goto fail; }
            sp -= f->nparams - 1;
            if (f->external && (f->bound || !f->has_default)) {
                if (!f->bound) { status = EVAL_UNBOUND; goto fail; }
                double r;
                if (f->bound(f->bound_user, &st[sp], f->nparams, &r)) { status = EVAL_EXTERN; goto fail; }
                if (!isfinite(r)) { status = EVAL_NONFINITE; goto fail; }
                st[sp] = r;
                break;
            }
            double r;
            status = run(p, f->pc, &st[sp], rng, &r, fault, depth + 1);
            if (status) return status; /* fault already points into the callee */
            st[sp] = r;
            break;
        }
        case OP_CURVE: st[sp] = curve_eval(&p->curves[a], st[sp]); break;
        case OP_RET:
            if (!isfinite(st[sp])) { status = EVAL_NONFINITE; goto fail; }
            *out = st[sp];
            return EVAL_OK;
        default: status = EVAL_DOMAIN; goto fail;
        }
        pc++;
    }
fail:
    fault->status = status;
    fault->pc = pc;
    return status;
}

int vm_run(const SylProgram *p, uint32_t pc, const double *locals, Rng *rng, double *out, VmFault *fault) {
    return run(p, pc, locals, rng, out, fault, 0);
}
