/* A chain of levels of detail as one .glb (`sylva mesh --lod`): nodes NAME_LOD0 .. NAME_LODn,
 * each with its level's mesh and instance sets, MSFT_lod on the first; glb.c writes it. */
#include <stdio.h>

#include "io/glb.h"
#include "sylva/lod.h"
#include "sylva/stream.h"
#include "sylva/wind.h"

int syl_lod_write_glb(const SylLodChain *c, const char *path, const SylSink *sink) { return syl_wind_write_glb_lods(c, NULL, NULL, path, sink); }

/* With wind, every level meshed with vertex nodes (of s) is skinned to w's joints; a level
 * without them (the billboards) is not. */
static int write_lods(const SylLodChain *c, const SylSkeleton *s, const SylWind *w, const char *path, FILE *stream,
                      SylTextureCache *tc, const SylSink *sink) {
    GlbPart part[SYL_LOD_MAX + 1];
    char names[SYL_LOD_MAX + 1][80];
    float coverage[SYL_LOD_MAX + 1];
    const char *name = c->level[0].mesh->name[0] ? c->level[0].mesh->name : "plant";
    for (int k = 0; k < c->n; k++) {
        snprintf(names[k], sizeof names[k], "%s_LOD%d", name, k);
        part[k] = (GlbPart){.mesh = c->level[k].mesh, .sets = c->level[k].sets, .nsets = c->level[k].nsets,
                            .name = names[k], .wind = w, .skel = s};
        coverage[k] = c->level[k].coverage;
    }
    bool instanced = false;
    for (int k = 0; k < c->n; k++) instanced |= c->level[k].nsets > 0;
    GlbScene sc = {.quantize = instanced,.part = part, .nparts = c->n, .scene_name = name, .lods = true, .coverage = coverage,
                   .atlas = c->atlas, .atlas_w = c->atlas_w, .atlas_h = c->atlas_h,
                   .atlas_material = c->atlas_material, .extras = c->extras, .stream = stream,
                   .textures = tc};
    return glb_write(&sc, path, sink);
}

int syl_wind_write_glb_lods(const SylLodChain *c, const SylSkeleton *s, const SylWind *w, const char *path, const SylSink *sink) {
    return write_lods(c, s, w, path, NULL, NULL, sink);
}

int syl_wind_write_glb_lods_stream(const SylLodChain *c, const SylSkeleton *s, const SylWind *w, FILE *out, const SylSink *sink) {
    return write_lods(c, s, w, "(stream)", out, NULL, sink);
}

int syl_wind_write_glb_lods_cached(const SylLodChain *c, const SylSkeleton *s, const SylWind *w, SylTextureCache *tc,
                                   FILE *out, const SylSink *sink) {
    return write_lods(c, s, w, "(stream)", out, tc, sink);
}
