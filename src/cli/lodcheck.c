/* How far a level of detail strays from LOD0 where it switches on: both rendered at the
 * size the plant then has on a 1080-line screen, their silhouettes compared pixel by pixel.
 * Here because the renderer and the LOD builder are peers; only the CLI uses both. */
#include <stdlib.h>
#include <string.h>

#include "cli/lodcheck.h"
#include "sylva/render.h"
#include "sylva/texture.h"

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
        uint64_t soft = 0, total = 0;
        for (size_t i = 0; i < n; i++) {
            bool in0 = a0[i] >= 128, ink = ak[i] >= 128;
            covered += in0;
            differ += in0 != ink;
            soft += (uint64_t)abs(a0[i] - ak[i]);
            total += a0[i];
        }
        *out = (LodSilhouette){.pixels = size, .covered = covered, .differ = differ,
                               .percent = covered ? 100.0 * (double)differ / (double)covered : 0,
                               .soft = total ? 100.0 * (double)soft / (double)total : 0};
    }
    free(rgb), free(a0), free(ak);
    return status;
}

int lod_picture(const SylLodChain *c, const char *path, int size, int threads) {
    size_t row = (size_t)size * (size_t)c->n * 3;
    uint8_t *sheet = malloc(row * (size_t)size), *one = malloc((size_t)size * (size_t)size * 3);
    int status = sheet && one ? SYL_OK : SYL_ELIMIT;
    SylRenderOptions ro = {.width = size, .height = size, .view = SYL_VIEW_AUTO, .threads = threads, .diag = stderr,
                           .frame = c->level[0].mesh};
    for (int k = 0; k < c->n && !status; k++) {
        status = syl_render(c->level[k].mesh, &ro, one);
        for (int y = 0; y < size && !status; y++)
            memcpy(sheet + (size_t)y * row + (size_t)k * (size_t)size * 3, one + (size_t)y * (size_t)size * 3,
                   (size_t)size * 3);
    }
    if (!status) status = syl_write_png(path, sheet, size * c->n, size, stderr);
    free(sheet), free(one);
    return status;
}
