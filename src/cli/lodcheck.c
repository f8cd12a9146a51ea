/* How far a level of detail strays from LOD0 where it switches on: both rendered at the
 * size the plant then has on a 1080-line screen, their silhouettes compared pixel by pixel.
 * Here because the renderer and the LOD builder are peers; only the CLI uses both. */
#include <stdlib.h>

#include "cli/lodcheck.h"
#include "sylva/render.h"

enum { SCREEN_LINES = 1080, MIN_PIXELS = 32, MAX_PIXELS = 1024 };

int lod_silhouette(const SylLodChain *c, int k, int threads, LodSilhouette *out) {
    /* The renderer frames the plant in 80% of the picture: the picture is 1/0.8 of it. */
    int size = (int)((double)c->level[k - 1].coverage * SCREEN_LINES / 0.8 + 0.5);
    size = size < MIN_PIXELS ? MIN_PIXELS : size > MAX_PIXELS ? MAX_PIXELS : size;
    size_t n = (size_t)size * (size_t)size;
    uint8_t *rgb = malloc(3 * n), *a0 = malloc(n), *ak = malloc(n);
    int status = rgb && a0 && ak ? SYL_OK : SYL_ELIMIT;
    SylRenderOptions ro = {.width = size, .height = size, .view = SYL_VIEW_AUTO, .samples = 4, .ao_samples = -1,
                           .shadows = -1, .threads = threads, .diag = stderr, .frame = c->level[0].mesh};
    ro.alpha = a0;
    if (!status) status = syl_render(c->level[0].mesh, &ro, rgb);
    ro.alpha = ak;
    if (!status) status = syl_render(c->level[k].mesh, &ro, rgb);
    if (!status) {
        size_t differ = 0, covered = 0;
        for (size_t i = 0; i < n; i++) {
            bool in0 = a0[i] >= 128, ink = ak[i] >= 128;
            covered += in0;
            differ += in0 != ink;
        }
        *out = (LodSilhouette){.pixels = size, .covered = covered, .differ = differ,
                               .percent = covered ? 100.0 * (double)differ / (double)covered : 0};
    }
    free(rgb), free(a0), free(ak);
    return status;
}
