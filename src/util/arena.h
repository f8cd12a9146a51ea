/* Arena: bump allocation for data that lives and dies together (an AST, a program).
 * Nothing is freed one by one; arena_free releases every block at once, which is also
 * what keeps error paths leak-free.
 *
 * Out of memory (or a size that does not fit in size_t) never aborts: with oom NULL every
 * allocator returns NULL; with oom set, it longjmps there instead, so that code with many
 * allocations (the parser, the compiler) unwinds once, the way Lua's allocator does. */
#ifndef SYL_ARENA_H
#define SYL_ARENA_H
#include <setjmp.h>
#include <stdbool.h>
#include <stddef.h>

typedef struct ArenaBlock ArenaBlock;
typedef struct Arena {
    ArenaBlock *head;
    size_t used;  /* bytes handed out, for statistics */
    jmp_buf *oom; /* where out of memory unwinds to; NULL: return NULL */
    bool fixed;   /* arena_fix's: one block, never another */
} Arena;

void *arena_alloc(Arena *a, size_t size);            /* zeroed, 16-byte aligned */
/* Zeroed too; from SPARSE_MIN bytes on, in small pages that exist only once written (a big
 * table of which a few entries are used costs those pages, not its size). */
void *arena_alloc_sparse(Arena *a, size_t size);
void *arena_grow(Arena *a, void *old, size_t old_size, size_t new_size);
char *arena_strndup(Arena *a, const char *s, size_t n);
char *arena_printf(Arena *a, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void arena_free(Arena *a);
/* A fixed arena, for a generator's scratch arrays that grow: one block of `bytes` (at least
 * 2 MB) in whole 2 MB pages that exist once written, so it may be sized from an estimate and
 * costs the pages its arrays reach; never another block (full: the calls below return NULL
 * and the caller puts the array elsewhere). False when refused. On an empty arena; then
 * only arena_take, arena_resize and arena_pop (and arena_free). */
bool arena_fix(Arena *a, size_t bytes);
/* Arrays: not zeroed (a fixed arena's fresh pages are), 64-byte aligned in a fixed arena. */
void *arena_take(Arena *a, size_t size);
/* p (old_size bytes, or NULL) grown to size: in place when it is the last thing in its block
 * and that has room, else moved (what it leaves is not reused); NULL when there is no
 * room (p unchanged). */
void *arena_resize(Arena *a, void *p, size_t old_size, size_t size);
/* Give p back, or its bytes past size, when it is the last thing in its block (else nothing). */
void arena_pop(Arena *a, void *p, size_t size);
void arena_trim(Arena *a, void *p, size_t old_size, size_t size);
bool arena_holds(const Arena *a, const void *p);
/* A fixed arena's block given up to the caller, the bytes from `from` to what was taken: the
 * whole 2 MB pages outside them unmapped. Returns where the kept pages start (NULL: not a fixed
 * arena, or nothing taken past from) and their length in *bytes, for pages_free; the arena is
 * then empty. */
void *arena_detach(Arena *a, const void *from, size_t *bytes);
/* Report out of memory: longjmp to a->oom, or return NULL when it is not set. */
void *arena_fail(Arena *a);

/* Growable array in an arena: VEC_PUSH(arena, ptr, n, cap) returns a pointer to a new
 * zeroed slot at the end (n and cap are ints). Out of memory with a->oom unset: NULL, and
 * ptr is NULL too (n and cap unchanged; the arena still owns the old array). */
void *arena_vec_grow(Arena *a, void *ptr, int *cap, size_t elem);
#define VEC_PUSH(ar, ptr, n, cap)                                                              \
    ((n) == (cap) ? (void)((ptr) = arena_vec_grow((ar), (ptr), &(cap), sizeof *(ptr))) : (void)0, \
     (ptr) ? &(ptr)[(n)++] : NULL)

#endif
