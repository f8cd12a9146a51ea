/* The plan of the class pass (see classes.h). */
#include "lsys/classes.h"

#include <stdlib.h>
#include <string.h>

#include "lsys/match.h"

/* Entry e for rule r (NULL: the module stays). Its template follows the successor as the
 * pass follows the string: each module not ignored gives its class to the one before it on
 * its axis, a ']' gives none. False when the pass could not follow it (too long, or its
 * brackets do not balance). */
static bool set_succ(ClassSucc *e, const Rule *r, const uint8_t *act, uint8_t none) {
    memset(e, 0, sizeof *e);
    e->rule = r;
    if (!r) return true;
    e->n = (uint32_t)r->nsucc;
    memcpy(e->code, r->succ, sizeof e->code); /* successors are padded to SUCC_PAD */
    if (r->nsucc > SUCC_PAD) return false;
    int pend[SUCC_PAD + 1], depth = 0; /* per depth, the module whose right class is not known */
    pend[0] = -1;
    for (int q = 0; q < r->nsucc; q++) {
        uint8_t a = act[r->succ[q]];
        if (a < ACT_SKIP) {
            if (depth == 0 && !e->has_base) {
                e->has_base = 1;
                e->first = a;
            } else if (pend[depth] >= 0) e->rt[pend[depth]] = a;
            pend[depth] = q;
            if (depth == 0) e->last = (uint8_t)q;
        } else if (a == ACT_OPEN) pend[++depth] = -1;
        else if (a == ACT_CLOSE) {
            if (depth == 0) return false;
            if (pend[depth] >= 0) e->rt[pend[depth]] = none;
            depth--;
        }
    }
    return depth == 0;
}

bool class_plan_build(ClassPlan *cp, const RuleTable *t, const bool *skip) {
    class_plan_free(cp);
    const uint32_t nn = (uint32_t)(t->nclass * t->nclass);
    uint8_t *act = cp->act = malloc(CODE_COUNT);
    cp->code = malloc(sizeof *cp->code * CODE_COUNT);
    /* the entry of modules that stay, and one block per predecessor code: t->order lists the
     * rules taking part (in a table of groups not all of t->rules) grouped by code */
    size_t n = 1;
    for (uint32_t j = 0; j < (uint32_t)t->nrules; j++) {
        const Dispatch *d = &t->dispatch[t->rules[t->order[j]].pred];
        if (d->first == j) n += d->plain ? 1 : nn;
    }
    cp->succ = malloc(sizeof *cp->succ * n);
    if (!act || !cp->code || !cp->succ) {
        class_plan_free(cp);
        return false;
    }
    match_class_actions(t->ctx_class, skip, act);
    for (int c = 0; c < CODE_COUNT; c++)
        cp->code[c] = (ClassCode){.act = act[c], .row = (uint8_t)(act[c] < ACT_SKIP ? act[c] * t->nclass : 0)};
    cp->none = t->ctx_class[CODE_NONE];
    cp->writes_right = true;
    set_succ(&cp->succ[0], NULL, act, cp->none);
    uint32_t at = 1;
    for (uint32_t j = 0; j < (uint32_t)t->nrules; j++) {
        uint16_t c = t->rules[t->order[j]].pred;
        const Dispatch *d = &t->dispatch[c];
        if (d->first != j) continue; /* not the first rule of its code */
        cp->code[c].base = at;
        if (d->plain) {
            cp->writes_right &= set_succ(&cp->succ[at++], d->plain, act, cp->none);
            continue;
        }
        cp->code[c].mask = 0xff;
        cp->writes_right &= act[c] < ACT_SKIP;
        for (uint32_t j = 0; j < nn; j++) cp->writes_right &= set_succ(&cp->succ[at++], d->pick[j], act, cp->none);
    }
    return true;
}

void class_plan_free(ClassPlan *cp) {
    free(cp->code);
    free(cp->act);
    free(cp->succ);
    cp->code = NULL;
    cp->act = NULL;
    cp->succ = NULL;
}
