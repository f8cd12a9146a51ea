/* Box-Muller normals over the counter-based streams of rng.h. */
#include "util/rng.h"

#include <math.h>

double rng_normal(Rng *r) {
    double u1 = rng_unit(r), u2 = rng_unit(r);
    if (u1 < 0x1.0p-60) u1 = 0x1.0p-60; /* log(0) guard */
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}
