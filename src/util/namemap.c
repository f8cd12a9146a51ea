/* NameMap: string to int by FNV-1a and open addressing. */
#include "util/namemap.h"

#include <string.h>

static unsigned hash(const char *s, int len) {
    unsigned h = 2166136261u;
    for (int i = 0; i < len; i++) h = (h ^ (unsigned char)s[i]) * 16777619u;
    return h;
}

void namemap_init(NameMap *m, Arena *a) {
    memset(m, 0, sizeof *m);
    m->arena = a;
}

int namemap_get(const NameMap *m, const char *key, int len) {
    if (len < 0) len = (int)strlen(key);
    if (!m->cap) return -1;
    for (unsigned i = hash(key, len) & (unsigned)(m->cap - 1);; i = (i + 1) & (unsigned)(m->cap - 1)) {
        const char *k = m->keys[i];
        if (!k) return -1;
        if ((int)strlen(k) == len && !memcmp(k, key, (size_t)len)) return m->vals[i];
    }
}

static void insert(NameMap *m, const char *key, int val) {
    int len = (int)strlen(key);
    for (unsigned i = hash(key, len) & (unsigned)(m->cap - 1);; i = (i + 1) & (unsigned)(m->cap - 1)) {
        if (!m->keys[i] || !strcmp(m->keys[i], key)) {
            if (!m->keys[i]) m->n++;
            m->keys[i] = key;
            m->vals[i] = val;
            return;
        }
    }
}

void namemap_put(NameMap *m, const char *key, int val) {
    if ((m->n + 1) * 2 > m->cap) {
        NameMap old = *m;
        m->cap = m->cap ? m->cap * 2 : 64;
        m->n = 0;
        m->keys = arena_alloc(m->arena, sizeof *m->keys * (size_t)m->cap);
        m->vals = arena_alloc(m->arena, sizeof *m->vals * (size_t)m->cap);
        for (int i = 0; i < old.cap; i++)
            if (old.keys[i]) insert(m, old.keys[i], old.vals[i]);
    }
    insert(m, key, val);
}
