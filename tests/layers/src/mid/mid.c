/* Fixture: mid uses low (a symbol and a header). */
#include "low/low.h"
#include "mid/mid.h"
int mid_value(void) { return low_value() + 1; }
