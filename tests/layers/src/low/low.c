/* Fixture: low uses nothing. */
#include "low/low.h"
int low_value(void) { return 1; }
