/* meshoptimizer, bound on first use (util/lazylib.h): include this instead of its headers. */
#ifndef SYL_UTIL_LAZY_MESHOPT_H
#define SYL_UTIL_LAZY_MESHOPT_H

#include <meshoptimizer.h>

#include "util/lazylib.h"

#define MESHOPT_FUNCS(X) \
    X(meshopt_optimizeVertexCache) \
    X(meshopt_optimizeVertexFetchRemap) \
    X(meshopt_remapIndexBuffer) \
    X(meshopt_remapVertexBuffer) \
    X(meshopt_simplify) \
    X(meshopt_simplifyScale) \
    X(meshopt_simplifySloppy) \
    X(meshopt_stripify) \
    X(meshopt_stripifyBound)

typedef struct MeshoptApi {
    MESHOPT_FUNCS(LAZY_LIB_FIELD)
} MeshoptApi;
const MeshoptApi *meshopt_api(void);

/* Each call goes through the table; a function missing here is an undefined symbol at link. */
#define meshopt_optimizeVertexCache(...) meshopt_api()->meshopt_optimizeVertexCache(__VA_ARGS__)
#define meshopt_optimizeVertexFetchRemap(...) meshopt_api()->meshopt_optimizeVertexFetchRemap(__VA_ARGS__)
#define meshopt_remapIndexBuffer(...) meshopt_api()->meshopt_remapIndexBuffer(__VA_ARGS__)
#define meshopt_remapVertexBuffer(...) meshopt_api()->meshopt_remapVertexBuffer(__VA_ARGS__)
#define meshopt_simplify(...) meshopt_api()->meshopt_simplify(__VA_ARGS__)
#define meshopt_simplifyScale(...) meshopt_api()->meshopt_simplifyScale(__VA_ARGS__)
#define meshopt_simplifySloppy(...) meshopt_api()->meshopt_simplifySloppy(__VA_ARGS__)
#define meshopt_stripify(...) meshopt_api()->meshopt_stripify(__VA_ARGS__)
#define meshopt_stripifyBound(...) meshopt_api()->meshopt_stripifyBound(__VA_ARGS__)

#endif
