/* How far from the origin geometry may lie and still be ray-traced. Embree works in float
 * and documents 1.844e18 as the largest magnitude it takes: primitives beyond it are dropped
 * and rays beyond it fail its checks (an assertion that aborts the process). The renderer's
 * camera and ground stand a few times the model's size away from it, and the environment's
 * rays start at the plant's points, so Sylva keeps six orders of magnitude below that: every
 * coordinate handed to Embree is within COORD_MAX. (A float's spacing there is already 2^16.) */
#ifndef SYL_UTIL_COORD_H
#define SYL_UTIL_COORD_H
#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "sylva/sylva.h"

#define COORD_MAX 1e12

static inline bool coord_ok(double x) { return fabs(x) <= COORD_MAX; } /* false for NaN too */
static inline bool coord_ok3(const float p[3]) { return coord_ok(p[0]) && coord_ok(p[1]) && coord_ok(p[2]); }

/* n points, stride floats apart: true when all lie within COORD_MAX. Otherwise false, and
 * "sylva: error: WHAT reaches 1e+18 units from the origin; Sylva traces at most 1e+12 units"
 * (or "... is not a finite number ...") on sink when it is not NULL. */
bool coord_check(const float *v, size_t n, size_t stride, const char *what, const SylSink *sink);

#endif
