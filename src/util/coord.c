/* Geometry Embree can trace: see coord.h. */
#include "util/coord.h"
#include "util/diag.h"

bool coord_check(const float *v, size_t n, size_t stride, const char *what, const SylSink *sink) {
    double reach = 0;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            double x = fabs(v[i * stride + (size_t)k]);
            if (!isfinite(x)) {
                sink_error(sink, "%s has a coordinate that is not a finite number", what);
                return false;
            }
            if (x > reach) reach = x;
        }
    if (coord_ok(reach)) return true;
    if (sink)
        sink_error(sink, "%s reaches %.3g units from the origin; Sylva traces at most %g units", what,
                reach, COORD_MAX);
    return false;
}
