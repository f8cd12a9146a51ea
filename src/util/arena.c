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
    bool sparse;         /* data from pages_alloc_sparse */
    unsigned char *data; /* inline, or pages of their own when size >= PAGES_BIG (or sparse) */
    _Alignas(16) unsigned char inline_data[];
};

enum { BLOCK_MIN = 64 * 1024 };

void *arena_fail(Arena *a) {
    if (a->oom) longjmp(*a->oom, 1);
    return NULL;
}

/* A new block for `size` bytes at least; big ones in pages of their own, which come zeroed
 * (sparse: pages_alloc_sparse's, from SPARSE_MIN bytes on). */
static ArenaBlock *new_block(Arena *a, size_t size, bool sparse) {
    size_t bs = size > BLOCK_MIN ? size : BLOCK_MIN;
    bool big = sparse || bs >= PAGES_BIG;
    ArenaBlock *b = malloc(sizeof *b + (big ? 0 : bs));
    unsigned char *data = !b ? NULL : !big ? b->inline_data : sparse ? pages_alloc_sparse(bs) : pages_alloc(bs);
    if (!data) {
        free(b);
        return arena_fail(a);
    }
    b->data = data;
    b->size = bs;
    b->off = 0;
    b->sparse = sparse;
    b->next = a->head;
    a->head = b;
    return b;
}

void *arena_alloc(Arena *a, size_t size) {
    /* size + 15 and sizeof *b + bs must not wrap; no object exceeds PTRDIFF_MAX anyway */
    if (size > PTRDIFF_MAX - 16 - sizeof(ArenaBlock)) return arena_fail(a);
    size = (size + 15) & ~(size_t)15;
    ArenaBlock *b = a->head;
    bool fresh = false; /* a big block's pages, never written yet */
    if (!b || b->size - b->off < size) {
        if (!(b = new_block(a, size, false))) return NULL;
        fresh = b->size >= PAGES_BIG;
    }
    void *p = b->data + b->off;
    b->off += size;
    a->used += size;
    if (!fresh) memset(p, 0, size);
    return p;
}

void *arena_alloc_sparse(Arena *a, size_t size) {
    if (size < SPARSE_MIN) return arena_alloc(a, size);
    if (size > PTRDIFF_MAX - 16 - sizeof(ArenaBlock)) return arena_fail(a);
    size = (size + 15) & ~(size_t)15;
    /* a block of its own, put second so that the head block keeps serving small ones */
    ArenaBlock *head = a->head, *b = new_block(a, size, true);
    if (!b) return NULL;
    if (head) {
        a->head = head;
        b->next = head->next;
        head->next = b;
    }
    b->off = size;
    a->used += size;
    return b->data;
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
        if (b->sparse) pages_free_sparse(b->data, b->size);
        else if (b->data != b->inline_data) pages_free(b->data, b->size);
        free(b);
        b = n;
    }
    a->head = NULL;
    a->used = 0;
    a->fixed = false;
}

bool arena_fix(Arena *a, size_t bytes) {
    if (a->head || bytes > PTRDIFF_MAX / 2) return false;
    bytes = bytes < PAGES_HUGE ? PAGES_HUGE : (bytes + PAGES_HUGE - 1) & ~(size_t)(PAGES_HUGE - 1);
    jmp_buf *oom = a->oom;
    a->oom = NULL; /* a fixed arena is an option: refused, the caller does without */
    ArenaBlock *b = new_block(a, bytes, false);
    a->oom = oom;
    a->fixed = b != NULL;
    return a->fixed;
}

bool arena_holds(const Arena *a, const void *p) {
    for (const ArenaBlock *b = a->head; b; b = b->next)
        if ((const unsigned char *)p >= b->data && (const unsigned char *)p < b->data + b->size) return true;
    return false;
}

void *arena_detach(Arena *a, const void *from, size_t *bytes) {
    ArenaBlock *b = a->head;
    *bytes = 0;
    if (!a->fixed || !b || b->size < PAGES_BIG || (const unsigned char *)from < b->data ||
        (const unsigned char *)from >= b->data + b->off)
        return NULL;
    size_t lo = (size_t)((const unsigned char *)from - b->data) & ~(size_t)(PAGES_HUGE - 1);
    size_t hi = (b->off + PAGES_HUGE - 1) & ~(size_t)(PAGES_HUGE - 1);
    if (lo) pages_free(b->data, lo);
    if (hi < b->size) pages_free(b->data + hi, b->size - hi);
    void *p = b->data + lo;
    *bytes = hi - lo;
    free(b);
    a->head = NULL;
    a->used = 0;
    a->fixed = false;
    return p;
}

static size_t array_bytes(const Arena *a, size_t size) { return a->fixed ? (size + 63) & ~(size_t)63 : (size + 15) & ~(size_t)15; }

void *arena_resize(Arena *a, void *p, size_t old_size, size_t size) {
    if (size > PTRDIFF_MAX - 64 - sizeof(ArenaBlock)) return a->fixed ? NULL : arena_fail(a);
    size_t bytes = array_bytes(a, size);
    ArenaBlock *b = a->head;
    size_t at = p && b ? (size_t)((uintptr_t)p - (uintptr_t)b->data) : 0; /* (huge when p is not in b) */
    if (p && b && (uintptr_t)p >= (uintptr_t)b->data && at + array_bytes(a, old_size) == b->off && at + bytes <= b->size) {
        a->used += at + bytes - b->off; /* in place: the last array of its block (it may shrink) */
        b->off = at + bytes;
        return p;
    }
    if (!b || b->size - b->off < bytes) {
        if (a->fixed) return NULL;
        if (!(b = new_block(a, bytes, false))) return NULL;
    }
    unsigned char *q = b->data + b->off;
    b->off += bytes;
    a->used += bytes;
    if (p && old_size) memcpy(q, p, old_size < size ? old_size : size);
    return q;
}

void *arena_take(Arena *a, size_t size) { return arena_resize(a, NULL, 0, size); }

void arena_trim(Arena *a, void *p, size_t old_size, size_t size) {
    ArenaBlock *b = a->head;
    size_t bytes = array_bytes(a, old_size), keep = array_bytes(a, size < old_size ? size : old_size);
    if (!p || !b || (uintptr_t)p < (uintptr_t)b->data || (uintptr_t)p - (uintptr_t)b->data + bytes != b->off) return;
    b->off -= bytes - keep;
    a->used -= bytes - keep;
}

void arena_pop(Arena *a, void *p, size_t size) { arena_trim(a, p, size, 0); }

void *arena_vec_grow(Arena *a, void *ptr, int *cap, size_t elem) {
    int c = *cap ? *cap : 2;
    if (c > INT_MAX / 2 || (size_t)c * 2 > PTRDIFF_MAX / (elem ? elem : 1)) return arena_fail(a);
    void *p = arena_grow(a, ptr, (size_t)*cap * elem, (size_t)c * 2 * elem);
    if (p) *cap = c * 2;
    return p;
}
