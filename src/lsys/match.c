/* Branch-aware context matching of rules' left and right contexts (see match.h). */
#include "lsys/match.h"

#include <string.h>

/* Skip modules ignored in contexts (never brackets). */
static size_t skip_ignored(const View *v, size_t pos) {
    while (pos < v->n && v->skip[CODE_SYM(v->code[pos])]) pos++;
    return pos;
}

/* Match pattern elements [j, end) from pos on, inside the current branch. */
static bool match_seq(const View *v, const PatElem *pat, int j, int end, size_t pos, double *locals) {
    while (j < end) {
        const PatElem *pe = &pat[j];
        if (pe->kind == PAT_OPEN) {
            /* a branch written in the context: try the side branches that start here */
            for (pos = skip_ignored(v, pos); pos < v->n && CODE_SYM(v->code[pos]) == SYM_OPEN;
                 pos = skip_ignored(v, (size_t)v->pair[pos] + 1))
                if (match_seq(v, pat, j + 1, pe->match, pos + 1, locals)) break;
            if (pos >= v->n || CODE_SYM(v->code[pos]) != SYM_OPEN) return false;
            pos = (size_t)v->pair[pos] + 1; /* the rest of that branch is skipped */
            j = pe->match + 1;
            continue;
        }
        for (;;) { /* next module along this axis, skipping side branches */
            if (pos >= v->n) return false;
            int s = CODE_SYM(v->code[pos]);
            if (s == SYM_OPEN) pos = (size_t)v->pair[pos] + 1;
            else if (s == SYM_CLOSE) return false; /* the branch ends */
            else if (v->skip[s]) pos++;
            else break;
        }
        if (v->code[pos] != pe->code) return false;
        match_bind(v, pos, pe, locals);
        pos++;
        j++;
    }
    return true;
}

bool match_branches(const View *v, size_t i, const Rule *r, double *locals) {
    return match_seq(v, r->right, 0, r->nright, i + 1, locals);
}

bool match_right_pat(const View *v, size_t i, const PatElem *pat, int n, bool branches, double *locals) {
    if (branches) return match_seq(v, pat, 0, n, i + 1, locals);
    if (v->rcode[i] != pat[0].code) return false;
    int32_t pos = (int32_t)i;
    for (int j = 0; j < n; j++) {
        pos = v->right[pos];
        if (pos < 0 || v->code[pos] != pat[j].code) return false;
        match_bind(v, (size_t)pos, &pat[j], locals);
    }
    return true;
}

void match_link_left(const uint16_t *code, size_t n, const bool *skip, int32_t *left, uint16_t *lcode,
                     int32_t *stack) {
    /* the stack keeps (index, code) pairs so that no neighbour is looked up far away */
    int32_t last = -1;
    uint16_t lastcode = CODE_NONE;
    size_t sp = 0;
    for (size_t i = 0; i < n; i++) {
        uint16_t c = code[i];
        int s = CODE_SYM(c);
        if (left) left[i] = last;
        lcode[i] = lastcode;
        if (s == SYM_OPEN) { /* a branch starts from its parent's module */
            stack[sp++] = last;
            stack[sp++] = lastcode;
        } else if (s == SYM_CLOSE) {
            lastcode = sp ? (uint16_t)stack[--sp] : CODE_NONE;
            last = sp ? stack[--sp] : -1;
        } else if (!skip[s]) {
            last = (int32_t)i;
            lastcode = c;
        }
    }
}

void match_link_right(const uint16_t *code, size_t n, const bool *skip, int32_t *right, uint16_t *rcode,
                      int32_t *stack) {
    int32_t next = -1;
    uint16_t nextcode = CODE_NONE;
    size_t sp = 0;
    for (size_t i = n; i-- > 0;) {
        uint16_t c = code[i];
        int s = CODE_SYM(c);
        if (right) right[i] = next;
        rcode[i] = nextcode;
        if (s == SYM_CLOSE) { /* entering a branch from its end: nothing follows its last module */
            stack[sp++] = next;
            stack[sp++] = nextcode;
            next = -1;
            nextcode = CODE_NONE;
        } else if (s == SYM_OPEN) {
            nextcode = sp ? (uint16_t)stack[--sp] : CODE_NONE;
            next = sp ? stack[--sp] : -1;
        } else if (!skip[s]) {
            next = (int32_t)i;
            nextcode = c;
        }
    }
}

void match_class_actions(const uint8_t *cls, const bool *skip, uint8_t *act) {
    for (int c = 0; c < CODE_COUNT; c++) {
        int s = CODE_SYM(c);
        act[c] = s == SYM_OPEN ? ACT_OPEN : s == SYM_CLOSE ? ACT_CLOSE : skip[s] ? ACT_SKIP : cls[c];
    }
}

void match_class_right(const uint16_t *code, size_t n, const uint8_t *act, uint8_t none, uint8_t *rclass,
                       uint8_t *stack) {
    uint8_t next = none;
    size_t sp = 0;
    for (size_t i = n; i-- > 0;) {
        uint8_t a = act[code[i]];
        rclass[i] = next;
        if (a < ACT_SKIP) next = a;
        else if (a == ACT_CLOSE) {
            stack[sp++] = next;
            next = none;
        } else if (a == ACT_OPEN) next = sp ? stack[--sp] : none;
    }
}

void match_pairs(const uint16_t *code, size_t n, int32_t *pair) {
    /* pair[] doubles as the stack of open brackets: each '[' links to the enclosing one
     * until its ']' is found. */
    int32_t top = -1;
    for (size_t i = 0; i < n; i++) {
        int s = CODE_SYM(code[i]);
        if (s == SYM_OPEN) {
            pair[i] = top;
            top = (int32_t)i;
        } else if (s == SYM_CLOSE && top >= 0) {
            int32_t open = top;
            top = pair[open];
            pair[open] = (int32_t)i;
            pair[i] = open;
        }
    }
}
