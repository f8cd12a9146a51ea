/* Embree's table of functions, loaded on first use (util/lazy_embree.h). */
#include "util/lazy_embree.h"

LAZY_LIB_GETTER(EmbreeApi, embree_api, "libembree3.so.3", "ray tracing (pictures, obstacles, shadows, light)", false,
                EMBREE_FUNCS)
