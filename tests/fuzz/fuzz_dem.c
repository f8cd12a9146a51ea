/* libFuzzer harness: the DEM readers (a PNG when the input starts with PNG's signature, else
 * the same text as an ESRI ASCII grid and as Zamuda's DMR list) on arbitrary bytes, then every
 * factor of what they read, with checks on the factors' ranges. Small limits keep each input
 * fast: 64 MB, grids of at most 4096 cells computed, two days of four suns. (OBJ terrains are
 * read by fuzz_obj's reader.) */
#include <math.h>

#include "fuzz.h"
#include "sylva/sylva.h"
#include "terrain/terrain.h"

/* What a reader gave: nothing when it failed, else factors within their ranges. */
static void check(int st, Terrain *t, SylTerrainOptions *o) {
    if (st != SYL_OK) {
        if (t) abort(); /* a failed read leaves nothing */
        return;
    }
    if ((size_t)t->nx * (size_t)t->nz <= 4096) {
        o->wind_distance = 10 * t->cell;
        if (syl_terrain_compute(t, o) == SYL_OK) {
            size_t n = (size_t)t->nx * (size_t)t->nz;
            for (size_t c = 0; c < n; c++) {
                float s = t->factor[SYL_TERRAIN_SLOPE][c], a = t->factor[SYL_TERRAIN_ASPECT][c];
                float f = t->factor[SYL_TERRAIN_FLOW][c], in = t->factor[SYL_TERRAIN_INSOLATION][c];
                float w = t->factor[SYL_TERRAIN_WIND][c];
                if (!(s >= 0 && s <= 90) || !(a == -1 || (a >= 0 && a < 360)) || !(f >= 1 && f <= n) ||
                    !(in >= 0 && isfinite(in)) || !(w >= -90 && w <= 90) || isnan(t->factor[SYL_TERRAIN_WETNESS][c]))
                    abort();
            }
            double x = t->x0 + t->nx * t->cell / 3, z = t->z0 + t->nz * t->cell / 2;
            for (int f = 0; f < SYL_TERRAIN_FACTORS; f++) /* every factor made: GIS's and Zamuda's */
                if (t->factor[f] && isnan(syl_terrain_factor_at(t, (SylTerrainFactor)f, x, z))) abort();
        }
    }
    syl_terrain_free(t);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    FILE *diag = fuzz_diag();
    SylTerrainOptions o = {.cell = 2, .height_lo = -5, .height_hi = 50, .threads = 1, .max_memory = 64u << 20,
                           .diag = diag, .sun_days = 2, .sun_minutes = 360, .measures = SYL_TERRAIN_BOTH};
    Terrain *t = NULL;
    if (size >= 8 && !memcmp(data, "\x89PNG\r\n\x1a\n", 8)) {
        int st = terrain_read_png("fuzz.png", data, size, &o, &t); /* before check() reads t: C leaves */
        check(st, t, &o);                                            /* the order of arguments open */
        return 0;
    }
    char *text = fuzz_text(data, size);
    int st = terrain_read_asc("fuzz.asc", text, size, &o, &t);
    check(st, t, &o);
    t = NULL;
    st = terrain_read_dmr("fuzz.dmr", text, size, &o, &t);
    check(st, t, &o);
    free(text);
    return 0;
}
