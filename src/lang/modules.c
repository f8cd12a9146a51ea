/* Module names: the symbol table, and splitting words into modules (ABOP's convention:
 * a declared name is matched greedily, any other letter or digit is a module of its own). */
#include <ctype.h>
#include <string.h>

#include "lang/compiler.h"

int cc_symbol(Compiler *c, const char *name, SylLoc loc) {
    int id = namemap_get(&c->syms, name, -1);
    if (id >= 0) return id;
    SylProgram *p = c->p;
    if (p->nsyms >= MAX_SYMBOLS - 1) { /* the last id is kept for CODE_ANY */
        diag_error(c->d, loc, "too many different modules (at most %d)", MAX_SYMBOLS - 1);
        return SYM_OPEN;
    }
    Symbol *s = VEC_PUSH(&p->arena, p->syms, p->nsyms, p->symcap);
    s->name = arena_strndup(&p->arena, name, strlen(name));
    s->declared_arity = -1;
    s->turtle = (uint8_t)turtle_command_find(s->name); /* resolved once, here */
    namemap_put(&c->syms, s->name, p->nsyms - 1);
    return p->nsyms - 1;
}

static void add(Compiler *c, Mods *out, const char *name, int len, SylLoc loc) {
    char buf[256];
    if (len >= (int)sizeof buf) len = (int)sizeof buf - 1;
    memcpy(buf, name, (size_t)len);
    buf[len] = 0;
    Mod *m = VEC_PUSH(c->tmp, out->v, out->n, out->cap);
    m->sym = cc_symbol(c, buf, loc);
    m->loc = loc;
}

void cc_split(Compiler *c, const Items *items, Mods *out) {
    memset(out, 0, sizeof *out);
    for (int i = 0; i < items->n; i++) {
        const Item *it = &items->v[i];
        const char *t = it->text;
        int len = (int)strlen(t);
        if (it->kind == IT_SYMBOL) {
            add(c, out, t, len, it->loc);
        } else {
            for (int pos = 0; pos < len;) {
                int take = 0;
                if (it->kind == IT_WORD)
                    for (int l = len - pos < c->max_declared_len ? len - pos : c->max_declared_len; l >= 2; l--)
                        if (namemap_get(&c->declared, t + pos, l) >= 0) {
                            take = l;
                            break;
                        }
                if (!take) {
                    if (!isalnum((unsigned char)t[pos])) {
                        diag_error(c->d, it->loc,
                                   "'%c' in '%s' is not a module: declare the name with `module %s`",
                                   t[pos], t, t);
                        break;
                    }
                    take = 1;
                }
                SylLoc loc = it->loc;
                loc.first_column += pos;
                loc.last_column = loc.first_column + take - 1;
                add(c, out, t + pos, take, loc);
                pos += take;
            }
        }
        if (out->n) { /* parameters belong to the last module of a word */
            out->v[out->n - 1].args = it->args;
            if (it->parens) out->v[out->n - 1].loc.last_column = it->loc.last_column;
        }
    }
}
