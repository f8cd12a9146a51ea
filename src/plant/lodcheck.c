/* How far a level of detail strays from LOD0 where it switches on: both rendered at the
 * size the plant then has on a 1080-line screen, their silhouettes compared pixel by pixel.
 * Here, in plant, because the renderer and the LOD builder are peers (sylva/lod.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sylva/lod.h"
#include "sylva/render.h"

enum { SCREEN_LINES = 1080, MIN_PIXELS = 32, MAX_PIXELS = 1024 };

/* The view the levels are compared in: from 35 degrees up (iso), or the front for a plant
 * drawn in a plane, as the silhouette bounds of tests/run-lod were set in; not the eye-level
 * view pictures now default to. */
static SylView lod_view(const SylMesh *m) {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, size = 0;
    for (size_t i = 0; i < m->nverts; i++)
        for (int k = 0; k < 3; k++) lo[k] = fminf(lo[k], m->pos[3 * i + k]), hi[k] = fmaxf(hi[k], m->pos[3 * i + k]);
    for (int k = 0; k < 3; k++) size = fmaxf(size, hi[k] - lo[k]);
    return hi[2] - lo[2] < 0.05f * size ? SYL_VIEW_FRONT : SYL_VIEW_ISO; /* camera.c's rule for auto */
}

int syl_lod_check_silhouette(const SylLodChain *c, int k, const SylLodCheckOptions *o, SylLodSilhouette *out) {
    if (k < 1 || k >= c->n) return SYL_EUSAGE;
    /* The renderer frames the plant in 80% of the picture: the picture is 1/0.8 of it. */
    int size = (int)((double)c->level[k - 1].coverage * SCREEN_LINES / 0.8 + 0.5);
    size = size < MIN_PIXELS ? MIN_PIXELS : size > MAX_PIXELS ? MAX_PIXELS : size;
    size_t n = (size_t)size * (size_t)size;
    uint8_t *rgb = malloc(3 * n), *a0 = malloc(n), *ak = malloc(n);
    int status = rgb && a0 && ak ? SYL_OK : SYL_ELIMIT;
    SylRenderOptions ro = {.width = size, .height = size, .view = lod_view(c->level[0].mesh), .samples = 4, .ao_samples = -1,
                           .shadows = -1, .threads = o ? o->threads : 0, .diag = o ? o->diag : NULL,
                           .sink = o ? o->sink : NULL, .frame = c->level[0].mesh};
    ro.alpha = a0;
    if (!status) status = syl_render_draw_mesh(c->level[0].mesh, &ro, rgb);
    ro.alpha = ak;
    if (!status) status = syl_render_draw_mesh(c->level[k].mesh, &ro, rgb);
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
        *out = (SylLodSilhouette){.pixels = size, .covered = covered, .differ = differ,
                               .percent = covered ? 100.0 * (double)differ / (double)covered : 0,
                               .soft = total ? 100.0 * (double)soft / (double)total : 0};
    }
    free(rgb), free(a0), free(ak);
    return status;
}

int syl_lod_draw_levels(const SylLodChain *c, const SylLodCheckOptions *o, SylPicture *out) {
    *out = (SylPicture){0};
    int size = o && o->size > 0 ? o->size : 256;
    size_t row = (size_t)size * (size_t)c->n * 3;
    uint8_t *sheet = malloc(row * (size_t)size), *one = malloc((size_t)size * (size_t)size * 3);
    int status = sheet && one ? SYL_OK : SYL_ELIMIT;
    SylRenderOptions ro = {.width = size, .height = size, .view = lod_view(c->level[0].mesh),
                           .threads = o ? o->threads : 0, .diag = o ? o->diag : NULL, .sink = o ? o->sink : NULL,
                           .frame = c->level[0].mesh};
    for (int k = 0; k < c->n && !status; k++) {
        status = syl_render_draw_mesh(c->level[k].mesh, &ro, one);
        for (int y = 0; y < size && !status; y++)
            memcpy(sheet + (size_t)y * row + (size_t)k * (size_t)size * 3, one + (size_t)y * (size_t)size * 3,
                   (size_t)size * 3);
    }
    free(one);
    if (status) free(sheet);
    else *out = (SylPicture){sheet, size * c->n, size};
    return status;
}
