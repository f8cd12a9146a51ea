/* Writers into an open stream rather than a path: the same bytes `sylva mesh` and
 * `sylva render` write into files, for a program that keeps them in memory (open_memstream)
 * or sends them on (`sylva view` serves them to the browser). Each returns SYL_OK or a SYL_*
 * status reported on diag (SYL_EIO when a write to out failed); out is flushed, not closed. */
#ifndef SYLVA_STREAM_H
#define SYLVA_STREAM_H
#include <stdint.h>
#include <stdio.h>

#include "lod.h"
#include "mesh.h"
#include "skeleton.h"
#include "wind.h"

#ifdef __cplusplus
extern "C" {
#endif

/* syl_mesh_write_glb_instanced (mesh.h): a .glb of m and its instance sets (n may be 0). */
int syl_mesh_write_glb_instanced_stream(const SylMesh *m, const SylInstances *sets, int n, FILE *out, const SylSink *sink);
/* syl_wind_write_glb_lods (wind.h): a chain of levels (MSFT_lod), skinned when w is not NULL. */
int syl_wind_write_glb_lods_stream(const SylLodChain *c, const SylSkeleton *s, const SylWind *w, FILE *out,
                                   const SylSink *sink);
/* syl_wind_write_glb (wind.h): a skinned mesh swaying in a looping animation. */
int syl_wind_write_glb_stream(const SylMesh *m, const SylInstances *sets, int n, const SylSkeleton *s,
                              const SylWind *w, FILE *out, const SylSink *sink);
/* The procedural textures' PNG bytes (bark, leaf, flower, leaf cards and clusters), kept by
 * their owner across .glb writes (sylva view's server keeps one: every save writes the same
 * textures). The _cached writers below take them from it, made and kept there the first
 * time; their bytes are the writers' above. Not shared between threads at once. */
typedef struct SylTextureCache SylTextureCache;
SylTextureCache *syl_texture_cache_new(void);
void syl_texture_cache_free(SylTextureCache *c);
int syl_mesh_write_glb_instanced_cached(const SylMesh *m, const SylInstances *sets, int n, SylTextureCache *tc,
                                        FILE *out, const SylSink *sink);
int syl_wind_write_glb_lods_cached(const SylLodChain *c, const SylSkeleton *s, const SylWind *w, SylTextureCache *tc,
                                   FILE *out, const SylSink *sink);
int syl_wind_write_glb_cached(const SylMesh *m, const SylInstances *sets, int n, const SylSkeleton *s,
                              const SylWind *w, SylTextureCache *tc, FILE *out, const SylSink *sink);
/* syl_png_write (texture.h): width x height RGB as a PNG. */
int syl_png_write_stream(FILE *out, const uint8_t *rgb, int width, int height, const SylSink *sink);
/* syl_png_write_rgba (texture.h): width x height RGBA as a PNG. */
int syl_png_write_rgba_stream(FILE *out, const uint8_t *rgba, int width, int height, const SylSink *sink);

#ifdef __cplusplus
}
#endif
#endif
