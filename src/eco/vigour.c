/* A species' vigour at a site: each terrain factor's suitability from its tolerance curve,
 * combined as the block's `vigour` says (Zamuda 2006, eq. 4.20–4.25). */
#include <math.h>

#include "eco/eco.h"

/* 1 within range of the optimum, then falling linearly to 0 over falloff (Zamuda's
 * 1 − min{1, |x − x_o| f}, with the tolerance band kept flat). */
double eco_suitability(const SylEcoSpecies *s, int f, double x) {
    double d = fabs(x - s->optimum[f]);
    if (f == SYL_TERRAIN_ASPECT) {
        if (x < 0) return 1; /* flat ground faces nowhere: any aspect suits it */
        d = fmod(d, 360);
        if (d > 180) d = 360 - d;
    }
    if (d <= s->range[f]) return 1;
    double v = 1 - (d - s->range[f]) / s->falloff[f];
    return v > 0 ? v : 0;
}

double syl_ecosystem_vigour(const SylEcoModel *m, int species, const SylTerrain *t, double x, double z) {
    const SylEcoSpecies *s = &m->species[species];
    double sum = 0, prod = 1, min = 1;
    int n = 0;
    for (int f = 0; f < SYL_TERRAIN_FACTORS; f++) {
        if (!s->set[f]) continue;
        double v = eco_suitability(s, f, syl_terrain_factor_at(t, (SylTerrainFactor)f, x, z));
        sum += v;
        prod *= v;
        if (v < min) min = v;
        n++;
    }
    if (!n) return 1;
    return m->combine == SYL_ECO_PRODUCT ? prod : m->combine == SYL_ECO_MINIMUM ? min : sum / n;
}
