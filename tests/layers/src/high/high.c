/* Fixture: high uses mid (a symbol) and low's types only (a header). */
#include "low/low_types.h"
#include "mid/mid.h"
int high_value(void);
int high_value(void) {
    LowPair p = {mid_value(), 2};
    return p.a + p.b;
}
