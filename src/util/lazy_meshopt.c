/* meshoptimizer's table of functions, loaded on first use (util/lazy_meshopt.h). */
#include "util/lazy_meshopt.h"

LAZY_LIB_GETTER(MeshoptApi, meshopt_api, "libmeshoptimizer.so.2d", "mesh optimization (vertex-cache order, levels of detail)", false, MESHOPT_FUNCS)
