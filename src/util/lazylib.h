/* Heavy shared libraries bound on first use (dlopen), not at start-up (docs/architecture.md,
 * "Start-up"). Each such library has a header util/lazy_NAME.h: the list of the functions
 * Sylva calls (an X-macro), a table of pointers typed from the library's own prototypes, and a
 * macro per function that calls through the table, so the code that uses the library reads as
 * before. The binary then records no dependency on the library: `sylva --version` and
 * `sylva derive` never load Embree, libxml2, meshoptimizer, OpenMPI or libmicrohttpd. */
#ifndef SYL_UTIL_LAZYLIB_H
#define SYL_UTIL_LAZYLIB_H

#include <pthread.h>
#include <stdbool.h>
#include <stddef.h>

typedef struct LazyLib {
    const char *soname;        /* the library's file as the linker would record it */
    const char *what;          /* what needs it, for the message when it cannot be loaded */
    const char *const *names;  /* its functions, in the order of the table */
    size_t n;
    bool global;               /* RTLD_GLOBAL: OpenMPI's own components look up libmpi's symbols */
} LazyLib;

/* Fill TABLE (LIB->n function pointers) from the library: from the process when the program
 * was linked against it (an embedder), else from dlopen of LIB->soname. When it cannot be
 * loaded, the handler of syl_missing_library_set (sylva.h) is called, and the process aborts
 * if it returns. Call it once per library (pthread_once, in the library's lazy_*.c). */
void lazy_lib_load(const LazyLib *lib, void *table);

/* A variable of a loaded library, by name (OpenMPI's predefined handles, libxml2's xmlFree);
 * a missing one is reported as a missing library. */
void *lazy_lib_sym(const LazyLib *lib, const char *name);

/* The body of a library's table getter: fn() loads it once and returns it; fn##_lib says
 * which library it is. */
#define LAZY_LIB_GETTER(type, fn, soname, what, global, list)                                  \
    static const char *const fn##_names[] = {list(LAZY_LIB_NAME)};                             \
    static const LazyLib fn##_lib = {soname, what, fn##_names,                                 \
                                     sizeof fn##_names / sizeof *fn##_names, global};          \
    _Static_assert(sizeof(type) == sizeof fn##_names / sizeof *fn##_names * sizeof(void *),    \
                   "one pointer per listed function");                                         \
    static type fn##_table;                                                                    \
    static pthread_once_t fn##_once = PTHREAD_ONCE_INIT;                                       \
    static void fn##_load(void) { lazy_lib_load(&fn##_lib, &fn##_table); }                     \
    const type *fn(void) {                                                                     \
        pthread_once(&fn##_once, fn##_load);                                                   \
        return &fn##_table;                                                                    \
    }
#define LAZY_LIB_NAME(f) #f,
#define LAZY_LIB_FIELD(f) __typeof__(&f) f;

#endif
