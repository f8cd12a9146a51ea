#include "match.h"

#include <stdlib.h>
#include <string.h>

static void bind(const View *v, size_t pos, const PatElem *pe, double *locals) {
    int ar = CODE_ARITY(pe->code);
    if (ar) memcpy(locals + pe->local, v->par + v->poff[pos], sizeof(double) * (size_t)ar);
}

bool match_left(const View *v, size_t i, const Rule *r, double *locals) {
    size_t pos = i;
    for (int j = r->nleft - 1; j >= 0; j--) {
        for (;;) { /* step back to the previous module on the path to the root */
            if (pos == 0) return false;
            int s = CODE_SYM(v->code[--pos]);
            if (s == SYM_CLOSE) pos = (size_t)v->pair[pos]; /* skip a whole side branch */
            else if (s != SYM_OPEN && !v->skip[s]) break;  /* '[': go on into the parent */
        }
        if (v->code[pos] != r->left[j].code) return false;
        bind(v, pos, &r->left[j], locals);
    }
    return true;
}

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
        bind(v, pos, pe, locals);
        pos++;
        j++;
    }
    return true;
}

bool match_right(const View *v, size_t i, const Rule *r, double *locals) {
    return match_seq(v, r->right, 0, r->nright, i + 1, locals);
}

bool match_pairs(const uint16_t *code, size_t n, int32_t *pair) {
    /* pair[] doubles as the stack of open brackets: each '[' links to the enclosing one
     * until its ']' is found. */
    int32_t top = -1;
    for (size_t i = 0; i < n; i++) {
        int s = CODE_SYM(code[i]);
        if (s == SYM_OPEN) {
            pair[i] = top;
            top = (int32_t)i;
        } else if (s == SYM_CLOSE) {
            if (top < 0) return false;
            int32_t open = top;
            top = pair[open];
            pair[open] = (int32_t)i;
            pair[i] = open;
        }
    }
    return top < 0;
}
