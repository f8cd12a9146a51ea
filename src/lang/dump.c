/* The disassembler behind `sylva compile --dump`: what each rule became. */
#include <stdio.h>

#include "lang/builtins.h"
#include "lang/opcodes.h"
#include "lang/program.h"
#include "sylva/sylva.h"

static void module(FILE *out, const SylProgram *p, uint16_t code) {
    int ar = CODE_ARITY(code);
    fprintf(out, "%s", p->syms[CODE_SYM(code)].name);
    if (ar) fprintf(out, "/%d", ar);
}

/* Print the expression at pc up to its RET (jumps only go forward). */
static void expression(FILE *out, const SylProgram *p, uint32_t pc, const char **names, const char *indent) {
    uint32_t end = pc;
    for (uint32_t i = pc;; i++) {
        Opcode op = INSTR_OP(p->code[i]);
        if (syl_op_kinds[op] == 'J' && INSTR_A(p->code[i]) > end) end = INSTR_A(p->code[i]);
        if (op == OP_RET && i >= end) {
            end = i;
            break;
        }
    }
    for (uint32_t i = pc; i <= end; i++) {
        uint32_t ins = p->code[i], a = INSTR_A(ins);
        Opcode op = INSTR_OP(ins);
        fprintf(out, "%s%04u  %-6s", indent, i, syl_op_names[op]);
        switch (syl_op_kinds[op]) {
        case 'K': fprintf(out, " %g", p->consts[a]); break;
        case 'L': fprintf(out, " %s", names ? names[a] : "?"); break;
        case 'J': fprintf(out, " -> %04u", a); break;
        case 'B': fprintf(out, " %s/%d", syl_builtins[a].name, syl_builtins[a].nargs); break;
        case 'F': fprintf(out, " %s/%d", p->fns[a].name, p->fns[a].nparams); break;
        case 'C': fprintf(out, " %s", p->curves[a].name); break;
        }
        fputc('\n', out);
    }
}

static void pattern(FILE *out, const SylProgram *p, const PatElem *pe, int n, const char **names) {
    for (int i = 0; i < n; i++) {
        if (i) fputc(' ', out);
        module(out, p, pe[i].code);
        int ar = CODE_ARITY(pe[i].code);
        if (pe[i].kind == PAT_MODULE && ar) {
            fputc('(', out);
            for (int k = 0; k < ar; k++) fprintf(out, "%s%s", k ? "," : "", names[pe[i].local + k]);
            fputc(')', out);
        }
    }
}

static void rule(FILE *out, const SylProgram *p, const Rule *r, int index) {
    if (index >= 0) {
        fprintf(out, "  rule %d, line %d", index + 1, r->line);
        if (r->group >= 0) fprintf(out, ", group %s", p->groups[r->group].name);
        fprintf(out, ": ");
        if (r->nleft) {
            pattern(out, p, r->left, r->nleft, r->names);
            fprintf(out, " < ");
        }
        if (r->nnewleft) {
            pattern(out, p, r->newleft, r->nnewleft, r->names);
            fprintf(out, " << ");
        }
        module(out, p, r->pred);
        if (r->pred_arity) {
            fputc('(', out);
            for (int k = 0; k < r->pred_arity; k++) fprintf(out, "%s%s", k ? "," : "", r->names[k]);
            fputc(')', out);
        }
        if (r->nright) {
            fprintf(out, " > ");
            pattern(out, p, r->right, r->nright, r->names);
        }
        if (r->nnewright) {
            fprintf(out, " >> ");
            pattern(out, p, r->newright, r->nnewright, r->names);
        }
        if (r->nnewleft) fprintf(out, "  (new context: forward steps only)");
        if (r->nnewright) fprintf(out, "  (new context: backward steps only)");
        fputc('\n', out);
        if (r->cond >= 0) {
            fprintf(out, "    condition:\n");
            expression(out, p, (uint32_t)r->cond, r->names, "      ");
        }
        if (r->weighted && r->weight < 0) fprintf(out, "    weight: %g\n", r->const_weight);
        if (r->weight >= 0) {
            fprintf(out, "    weight:\n");
            expression(out, p, (uint32_t)r->weight, r->names, "      ");
        }
    }
    fprintf(out, "    successor (%d module%s):", r->nsucc, r->nsucc == 1 ? "" : "s");
    for (int i = 0; i < r->nsucc; i++) {
        fputc(' ', out);
        module(out, p, r->succ[i]);
    }
    fputc('\n', out);
    for (int k = 0; k < r->nslots; k++) {
        const Slot *s = &r->slots[k];
        fprintf(out, "      parameter %d: ", k + 1);
        if (s->kind == SLOT_CONST) fprintf(out, "constant %g\n", s->k);
        else if (s->kind == SLOT_LOCAL) fprintf(out, "copy %s\n", r->names[s->local]);
        else if (s->kind == SLOT_CODE) {
            fprintf(out, "code\n");
            expression(out, p, s->pc, r->names, "        ");
        } else { /* x op k: run without the VM; its code (from LOCAL x) reports errors */
            fprintf(out, "%s %c %g, code\n", r->names[s->local], "+-*/"[s->kind - SLOT_ADDK], s->k);
            expression(out, p, s->pc - 1, r->names, "        ");
        }
    }
}

/* Each group and the `use` conditions that make it take part (in the rule lines: its rules). */
static void groups(FILE *out, const SylProgram *p) {
    static const char *step[] = {"step"};
    for (int g = 0; g < p->ngroups; g++) {
        const Group *gr = &p->groups[g];
        fprintf(out, "group %s, line %d: ", gr->name, gr->loc.first_line);
        bool always = false;
        for (int k = 0; k < gr->nwhen; k++) always |= gr->when[k] < 0;
        if (always) fprintf(out, "used at every step\n");
        else if (!gr->nwhen) fprintf(out, "never used\n");
        else if (gr->nwhen == 1) fprintf(out, "used when its condition holds\n");
        else fprintf(out, "used when one of its %d conditions holds\n", gr->nwhen);
        for (int k = 0; k < gr->nwhen && !always; k++) {
            fprintf(out, "    condition (line %d):\n", gr->when_loc[k].first_line);
            expression(out, p, (uint32_t)gr->when[k], step, "      ");
        }
    }
}

/* A directive line with its values evaluated, as the engine that owns it reads them. */
static void directive(FILE *out, const SylDirective *d) {
    fprintf(out, "    %s", d->name);
    for (int a = 0; a < d->nargs; a++) {
        const SylDirArg *g = &d->args[a];
        if (g->kind == SYL_DARG_NUMBER) fprintf(out, " %.17g", g->num);
        else if (g->kind == SYL_DARG_STRING) fprintf(out, " \"%s\"", g->text);
        else fprintf(out, " %s", g->kind == SYL_DARG_TUPLE ? "" : g->text);
        if (g->kind == SYL_DARG_TUPLE || (g->kind == SYL_DARG_SYMBOL && g->nvalues))
            for (int k = 0; k < g->nvalues; k++) fprintf(out, "%s%.17g%s", k ? ", " : "(", g->values[k], k + 1 == g->nvalues ? ")" : "");
    }
    fputc('\n', out);
}

/* grow, weber and strands blocks: their parameters and directive lines */
static void dump_directives(const SylProgram *p, FILE *out) {
    fprintf(out, "%s %s\n", lang_kind_keyword(p->kind), p->name);
    for (int i = 0; i < p->nparams; i++)
        fprintf(out, "param %s = %g%s\n", p->params[i].name, p->params[i].value,
                p->params[i].overridden ? " (set on the command line)" : "");
    fprintf(out, "directives (%d):\n", p->ndirectives);
    for (int i = 0; i < p->ndirectives; i++) directive(out, &p->directives[i]);
}

void syl_program_dump(const SylProgram *p, FILE *out) {
    if (syl_kind_has_directives(p->kind)) {
        dump_directives(p, out);
        return;
    }
    fprintf(out, "lsystem %s\n", p->name);
    fprintf(out, "settings: derive %d, angle %g, step %g, width %g, seed %llu\n", p->derive, p->angle, p->step,
            p->width, (unsigned long long)p->seed);
    if (p->backward || p->direction_when >= 0) {
        fprintf(out, "direction: %s%s\n", p->backward ? "backward" : "forward", p->direction_when >= 0 ? " when" : "");
        if (p->direction_when >= 0) {
            const char *step[1] = {"step"};
            expression(out, p, (uint32_t)p->direction_when, step, "    ");
        }
    }
    fprintf(out, "modules (%d):", p->nsyms);
    for (int i = 0; i < p->nsyms; i++) fprintf(out, " %s%s", p->syms[i].name, p->skip[i] ? "(ignored)" : "");
    fputc('\n', out);
    for (int i = 0; i < p->nparams; i++)
        fprintf(out, "param %s = %g%s\n", p->params[i].name, p->params[i].value,
                p->params[i].overridden ? " (set on the command line)" : "");
    groups(out, p);
    fprintf(out, "axiom:\n");
    rule(out, p, &p->axiom, -1);
    static const char *const table_names[TABLE_COUNT] = {"productions", "decomposition", "interpretation"};
    for (int t = 0; t < TABLE_COUNT; t++) {
        const RuleTable *tb = &p->tables[t];
        if (!tb->nrules) continue;
        fprintf(out, "%s (%d rule%s", table_names[t], tb->nrules, tb->nrules == 1 ? "" : "s");
        if (t != TABLE_PRODUCE) fprintf(out, ", maxdepth %d", tb->maxdepth);
        fprintf(out, "):\n");
        for (int i = 0; i < tb->nrules; i++) rule(out, p, &tb->rules[i], i);
    }
    for (int i = 0; i < p->nfns; i++) {
        const Function *f = &p->fns[i];
        fprintf(out, "%s %s/%d:%s\n", f->external ? "extern" : "fn", f->name, f->nparams,
                f->external && !f->has_default ? " (no default)" : "");
        if (!f->external || f->has_default) expression(out, p, f->pc, f->names, "    ");
    }
    for (int i = 0; i < p->ncurves; i++) {
        fprintf(out, "curve %s:", p->curves[i].name);
        for (int k = 0; k < p->curves[i].n; k++) fprintf(out, " (%g, %g)", p->curves[i].x[k], p->curves[i].y[k]);
        fputc('\n', out);
    }
}
