/* ShapeRatio(shape, r): the crown shapes of Weber & Penn's table (r from the tip, 0..1).
 * Arbaro's conical shape is r itself (for larch and fir); the paper's is 0.2 + 0.8 r. The
 * envelope (8) below its peak: see the comment there. */
#include "weber/internal.h"

double weber_shape_ratio(const WeberParams *w, int shape, double r) {
    switch (shape) {
    case 0: return w->convention == WEBER_PAPER ? 0.2 + 0.8 * r : r;
    case 1: return 0.2 + 0.8 * sin(M_PI * r);
    case 2: return 0.2 + 0.8 * sin(0.5 * M_PI * r);
    case 3: return 1.0;
    case 4: return 0.5 + 0.5 * r;
    case 5: return r <= 0.7 ? r / 0.7 : (1 - r) / 0.3;
    case 6: return 1 - 0.8 * r;
    case 7: return r <= 0.7 ? 0.5 + 0.5 * r / 0.7 : 0.5 + 0.5 * (1 - r) / 0.3;
    case 8: { /* the pruning envelope */
        double peak = w->PruneWidthPeak;
        if (r < 0 || r > 1) return 0;
        if (r < 1 - peak) return w->PrunePowerHigh == 0.5 ? sqrt(r / (1 - peak)) : pow(r / (1 - peak), w->PrunePowerHigh);
        /* Arbaro divides by 1 - peak here too (a jump at the peak unless it is 0.5) */
        double d = w->convention == WEBER_PAPER ? peak : 1 - peak;
        return d > 0 ? pow((1 - r) / d, w->PrunePowerLow) : 0;
    }
    default: return 0;
    }
}
