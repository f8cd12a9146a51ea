/* The re-balancing cut: tiles, in their row-major order, are given to ranks in contiguous
 * runs of about equal weight (a tile's plants, plus one so that bare ground is spread too):
 * a tile goes to the rank its weight's midpoint falls in on the prefix sums. The cut depends
 * on the counts only, so every rank computes the same one. */
#include "eco/eco.h"

void eco_balance_cut(const int64_t *plants, int ntiles, int nranks, int *owner) {
    double total = 0;
    for (int t = 0; t < ntiles; t++) total += (double)(plants ? plants[t] : 0) + 1;
    double before = 0;
    for (int t = 0; t < ntiles; t++) {
        double w = (double)(plants ? plants[t] : 0) + 1;
        int r = (int)((before + w / 2) * nranks / total);
        owner[t] = r < 0 ? 0 : r >= nranks ? nranks - 1 : r;
        before += w;
    }
}
