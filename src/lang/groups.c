/* Groups (tables): their declaration and `use` lines compiled, and which are used at a step. */
#include <string.h>

#include "lang/builtins.h"
#include "lang/compiler.h"
#include "lang/groups.h"

int cc_group_of(const SylProgram *p, const char *name) {
    for (int g = 0; name && g < p->ngroups; g++)
        if (!strcmp(p->groups[g].name, name)) return g;
    return -1;
}

/* The group blocks (one per group in each of the body, decompose and interpret) and the
 * `use` lines, whose conditions read `step` as their one bound name. */
void cc_groups(Compiler *c, Stmt **all, int n) {
    SylProgram *p = c->p;
    int first_block[MAX_GROUPS][BLOCK_COUNT] = {{0}};
    int count = 0;
    for (int i = 0; i < n; i++) count += all[i]->kind == ST_GROUP;
    p->groups = arena_alloc(&p->arena, sizeof *p->groups * (size_t)(count < MAX_GROUPS ? count + 1 : MAX_GROUPS));
    for (int i = 0; i < n; i++) {
        const Stmt *s = all[i];
        if (s->kind != ST_GROUP) continue;
        int g = cc_group_of(p, s->name);
        if (g < 0) {
            if (p->ngroups == MAX_GROUPS) {
                diag_error(c->d, s->loc, "a model has at most %d groups", MAX_GROUPS);
                continue;
            }
            g = p->ngroups++;
            p->groups[g].name = arena_strndup(&p->arena, s->name, strlen(s->name));
            p->groups[g].loc = s->loc;
        }
        int *at = &first_block[g][s->block];
        if (*at)
            diag_error(c->d, s->loc, "group '%s' is already declared at line %d%s", s->name, *at,
                       s->block == BLOCK_PRODUCE ? "" : s->block == BLOCK_DECOMPOSE ? " in this decompose block"
                                                                                    : " in this interpret block");
        else *at = s->loc.first_line;
    }
    int nuse[MAX_GROUPS] = {0};
    for (int i = 0; i < n; i++)
        if (all[i]->kind == ST_USE) {
            int g = cc_group_of(p, all[i]->name);
            bool declared = g >= 0; /* or one past the limit, reported already */
            for (int j = 0; j < n && !declared; j++)
                declared = all[j]->kind == ST_GROUP && !strcmp(all[j]->name, all[i]->name);
            if (!declared)
                diag_error(c->d, all[i]->loc, "use of unknown group '%s' (declare it with `group %s { }`)",
                           all[i]->name, all[i]->name);
            if (g >= 0) nuse[g]++;
        }
    for (int g = 0; g < p->ngroups; g++) {
        p->groups[g].when = arena_alloc(&p->arena, sizeof(int32_t) * (size_t)(nuse[g] + 1));
        p->groups[g].when_loc = arena_alloc(&p->arena, sizeof(SylLoc) * (size_t)(nuse[g] + 1));
    }
    for (int i = 0; i < n; i++) {
        const Stmt *s = all[i];
        int g = s->kind == ST_USE ? cc_group_of(p, s->name) : -1;
        if (g < 0) continue;
        Group *gr = &p->groups[g];
        const char *names[1] = {"step"};
        Scope scope = {.names = names, .n = 1};
        int32_t pc = s->value ? cc_expr(c, s->value, &scope, NULL) : -1;
        double v;
        if (cc_code_constant(p, pc, &v) && v != 0) pc = -1; /* always true */
        gr->when_loc[gr->nwhen] = s->value ? s->value->loc : s->loc;
        gr->when[gr->nwhen++] = pc;
    }
}

int lang_groups_active(const SylProgram *p, int step, uint64_t seed, uint64_t *active, VmFault *fault, int *group) {
    *active = 0;
    double locals[1] = {step};
    for (int g = 0; g < p->ngroups; g++)
        for (int k = 0; k < p->groups[g].nwhen; k++) {
            int32_t pc = p->groups[g].when[k];
            double v = 1;
            /* a condition may draw: from a stream of its own per step, group and line */
            Rng rng = rng_stream(seed, (uint64_t)step << 16, TABLE_COUNT + 1, (uint64_t)g << 16 | (uint64_t)k);
            if (pc >= 0 && vm_run(p, (uint32_t)pc, locals, &rng, &v, fault)) {
                *group = g;
                return fault->status ? fault->status : EVAL_NONFINITE;
            }
            if (v != 0) {
                *active |= 1ull << g;
                break;
            }
        }
    return EVAL_OK;
}
