/* Loading a heavy library on first use (util/lazylib.h). */
#include "util/lazylib.h"

#include <dlfcn.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "sylva/sylva.h"

/* The program's handler: process-wide, as the libraries it is about are. */
static _Atomic(SylMissingLibrary *) on_missing;

void syl_missing_library_set(SylMissingLibrary *handler) { atomic_store(&on_missing, handler); }

static _Noreturn void missing(const LazyLib *lib, const char *why) {
    SylMissingLibrary *f = atomic_load(&on_missing);
    if (f) f(lib->soname, lib->what, why ? why : "unknown error");
    abort();
}

void lazy_lib_load(const LazyLib *lib, void *table) {
    /* A program linked against the library (an embedder, the Python extension) has it loaded
     * already: take its functions from there rather than load a second copy. */
    void *h = dlopen(lib->soname, RTLD_NOW | RTLD_NOLOAD | (lib->global ? RTLD_GLOBAL : RTLD_LOCAL));
    if (!h) h = dlopen(lib->soname, RTLD_NOW | (lib->global ? RTLD_GLOBAL : RTLD_LOCAL));
    const char *why = h ? NULL : dlerror();
    for (size_t i = 0; h && i < lib->n; i++) {
        void *f = dlsym(h, lib->names[i]);
        if (!f) {
            why = dlerror();
            break;
        }
        memcpy((char *)table + i * sizeof f, &f, sizeof f);
    }
    if (!why) return;
    missing(lib, why);
}

void *lazy_lib_sym(const LazyLib *lib, const char *name) {
    void *h = dlopen(lib->soname, RTLD_NOW | RTLD_NOLOAD), *v = h ? dlsym(h, name) : NULL;
    if (!v) missing(lib, h ? dlerror() : "not loaded");
    dlclose(h); /* the reference this call took: the library stays loaded */
    return v;
}
