/* Arena: bump allocation for data that lives and dies together. */
#include "util/arena.h"
#include "util/pages.h"

#include <limits.h>
#include <stdbool.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A big block's data lives apart from its header, in whole 2 MB pages (util/pages.c): a
 * rule table's dispatch is 2 MB, and a deriver builds one per set of active groups. */
struct ArenaBlock {
    ArenaBlock *next;
    size_t size, off;
    unsigned char *data; /* inline, or pages of their own when size >= PAGES_BIG */
    _Alignas(16) unsigned char inline_data[];
};

enum { BLOCK_MIN = 64 * 1024 };

void *arena_fail(Arena *a) {
    if (a->oom) longjmp(*a->oom, 1);
    return NULL;
}

void *arena_alloc(Arena *a, size_t size) {
    /* size + 15 and sizeof *b + bs must not wrap; no object exceeds PTRDIFF_MAX anyway */
    if (size > PTRDIFF_MAX - 16 - sizeof(ArenaBlock)) return arena_fail(a);
    size = (size + 15) & ~(size_t)15;
    ArenaBlock *b = a->head;
    if (!b || b->size - b->off < size) {
        size_t bs = size > BLOCK_MIN ? size : BLOCK_MIN;
        bool big = bs >= PAGES_BIG;
        b = malloc(sizeof *b + (big ? 0 : bs));
        unsigned char *data = !b ? NULL : big ? pages_alloc(bs) : b->inline_data;
        if (!data) {
            free(b);
            return arena_fail(a);
        }
        b->data = data;
        b->size = bs;
        b->off = 0;
        b->next = a->head;
        a->head = b;
    }
    void *p = b->data + b->off;
    b->off += size;
    a->used += size;
    memset(p, 0, size);
    return p;
}

void *arena_grow(Arena *a, void *old, size_t old_size, size_t new_size) {
    void *p = arena_alloc(a, new_size);
    if (!p) return NULL;
    if (old && old_size) memcpy(p, old, old_size < new_size ? old_size : new_size);
    return p;
}

char *arena_strndup(Arena *a, const char *s, size_t n) {
    if (n == SIZE_MAX) return arena_fail(a);
    char *p = arena_alloc(a, n + 1);
    if (!p) return NULL;
    memcpy(p, s, n);
    p[n] = 0;
    return p;
}

char *arena_printf(Arena *a, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0) return arena_fail(a); /* vsnprintf fails only for want of memory here */
    char *p = arena_alloc(a, (size_t)n + 1);
    if (!p) return NULL;
    va_start(ap, fmt);
    vsnprintf(p, (size_t)n + 1, fmt, ap);
    va_end(ap);
    return p;
}

void arena_free(Arena *a) {
    ArenaBlock *b = a->head;
    while (b) {
        ArenaBlock *n = b->next;
        if (b->data != b->inline_data) pages_free(b->data, b->size);
        free(b);
        b = n;
    }
    a->head = NULL;
    a->used = 0;
}

void *arena_vec_grow(Arena *a, void *ptr, int *cap, size_t elem) {
    int c = *cap ? *cap : 2;
    if (c > INT_MAX / 2 || (size_t)c * 2 > PTRDIFF_MAX / (elem ? elem : 1)) return arena_fail(a);
    void *p = arena_grow(a, ptr, (size_t)*cap * elem, (size_t)c * 2 * elem);
    if (p) *cap = c * 2;
    return p;
}
