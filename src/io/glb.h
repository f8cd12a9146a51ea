/* The glTF binary writer (glb.c) and its parts (glb_parts.c), which other writers of .glb
 * (a forest's) may share. */
#ifndef SYLVA_IO_GLB_H
#define SYLVA_IO_GLB_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "io/io_internal.h"

enum { GLB_MAGIC = 0x46546C67, GLB_JSON = 0x4E4F534A, GLB_BIN = 0x004E4942 };
enum { ARRAY_BUFFER = 34962, ELEMENT_ARRAY_BUFFER = 34963, FLOAT = 5126, UNSIGNED_INT = 5125,
       UNSIGNED_SHORT = 5123, UNSIGNED_BYTE = 5121, SHORT = 5122, BYTE = 5120 };

/* A slice of the BIN chunk. */
typedef struct View {
    size_t offset, length;
    int target; /* 0: none */
    int stride; /* byteStride (0: packed) */
} View;

float glb_linear(float srgb);                          /* glTF's colours are linear */
void glb_u32(IoBuf *b, uint32_t u);                    /* little-endian */
void glb_words(IoBuf *b, const void *x, size_t n);     /* n 32-bit words, little-endian */
void glb_pad(IoBuf *b, uint8_t with);                  /* to a multiple of 4 bytes */
void glb_min_max(IoBuf *j, const float *x, size_t n, int k); /* ,"min":[..],"max":[..] */
/* ,"bufferViews":[..],"buffers":[..] */
void glb_buffer_views(IoBuf *js, const View *views, int n, size_t bin_len);
/* The GLB container: header, JSON chunk and (with geometry) BIN chunk, through a temporary
 * file. SYL_OK, SYL_ELIMIT or SYL_EIO, reported. */
int glb_container(const char *path, const IoBuf *js, const IoBuf *bin, bool geometry, const SylSink *sink);
/* The same into stream when it is not NULL (SYL_EIO when a write to it failed). */
int glb_container_to(const char *path, FILE *stream, const IoBuf *js, const IoBuf *bin, bool geometry, const SylSink *sink);

#include "sylva/mesh.h"
#include "sylva/stream.h"
#include "sylva/wind.h"

/* A top-level node: its mesh (may be NULL or empty) and its instance sets (child nodes). */
typedef struct GlbPart {
    const SylMesh *mesh;
    const SylInstances *sets;
    int nsets;
    const char *name;
    const SylWind *wind;       /* with wind (the first part only): skinned, mesh->node set */
    const SylSkeleton *skel;   /* the skeleton mesh->node refers to */
} GlbPart;

/* What glb_write writes: parts, the first in the scene; with lods, the others are its
 * MSFT_lod levels (coverage: each one's MSFT_screencoverage). The last part's material
 * atlas_material is drawn with atlas (atlas_w x atlas_h RGBA, alpha-tested) when atlas is
 * set; extras (JSON object text, may be NULL) goes in the last part's node. */
typedef struct GlbScene {
    const GlbPart *part;
    int nparts;
    const char *scene_name;
    bool lods;
    const float *coverage;
    const uint8_t *atlas;
    int atlas_w, atlas_h, atlas_material;
    const char *extras;
    /* KHR_mesh_quantization: each part's own mesh has 16-bit positions (its node's
     * translation and uniform scale bring them back), 8-bit normals, 16-bit UVs (the
     * materials' KHR_texture_transform brings them back; floats when that is coarser than a
     * texel) and triangle strips, its instances 16-bit translations and rotations. Not for a
     * skinned part (a skinned node's transform is not used). */
    bool quantize;
    FILE *stream; /* set: the file is written here (path only names it in messages) */
    SylTextureCache *textures; /* set: the procedural textures' PNGs from it (glb_texcache.c) */
} GlbScene;

int glb_write(const GlbScene *sc, const char *path, const SylSink *sink);
/* A ground mesh (may be NULL) and n sets of instances (each a node with
 * EXT_mesh_gpu_instancing, extras[i] — JSON object text, or NULL — in its node's extras);
 * sets with the same proto pointer share one mesh: a forest split into cells, for
 * syl_forest_write_glb (sylva/forest.h), the one public name of the operation. The procedural
 * textures' PNGs come from tc, a run's cache (may be NULL: made here). */
int glb_write_forest(const SylMesh *ground, const SylInstances *sets, const char *const *extras, int n,
                     SylTextureCache *tc, const char *path, const SylSink *sink);

/* Texture slots of a material (glb.c): its kind's tiled picture (bark, leaf, flower), a leaf
 * card (RGBA), an impostor's atlas, a leaf cluster (RGBA); -1: none. */
enum { GLB_BARK, GLB_LEAF, GLB_FLOWER, GLB_CARD, GLB_ATLAS, GLB_CLUSTER, GLB_SLOTS };
int glb_slot(const SylMesh *m, int material); /* never GLB_ATLAS */
/* A write's pictures' scratch: img, SYL_TEXTURE_SIZE² RGBA; leaf, the leaf pattern (RGB),
 * made at its first need and shared by the leaf's slot, its cards and its clusters (one
 * pattern, not one per picture). Start as {0}; glb_pixels_free at the end. */
typedef struct GlbPixels {
    uint8_t *img, *leaf;
} GlbPixels;
void glb_pixels_free(GlbPixels *px);
/* Slot k's picture (not the atlas) as PNG bytes into b. shape: the leaf shape of cards and
 * clusters. False when it failed (also out of memory). */
bool glb_slot_png(IoBuf *b, int k, int shape, GlbPixels *px);
/* The same bytes, from c when it has them (made and kept there when not); c NULL: none. */
bool glb_slot_png_cached(SylTextureCache *c, IoBuf *b, int k, int shape, GlbPixels *px);
const char *glb_slot_name(int k); /* the image's name: "bark", "leafcard", ... */

/* A primitive (glb_prims.c): count indices of the mesh from first, of group group, using
 * vertices lo .. lo + nv - 1 (its indices are written less lo). */
typedef struct GlbPrim {
    uint32_t first, count;
    size_t lo, nv;
    int group;
} GlbPrim;
/* split: the mesh has more than 65,535 vertices and its groups are cut into primitives of
 * 16-bit indices, each with attribute accessors of its own window; wide: that failed (a
 * triangle spans more), one primitive a group with 32-bit indices. */
typedef struct GlbPrims {
    GlbPrim *prim;
    size_t n;
    bool split, wide;
} GlbPrims;
bool glb_primitives(const SylMesh *m, GlbPrims *out); /* false: out of memory */

/* The skin of a part with wind (glb_skin.c): its five vertex views; the inverse bind
 * matrices', key times' and rotations' views (strided: with byteStride, as several windows'
 * accessors share them); their accessors (of vertices lo .. lo + nv - 1); the primitive's attributes;
 * the root joints (child ids); the joint nodes (or a copy of them); "skins" and
 * "animations". */
void glb_skin_vertices(const GlbPart *p, IoBuf *bin, View *views, int *nviews, bool strided);
void glb_skin_animation(const SylWind *w, IoBuf *bin, View *views, int *nviews);
void glb_skin_vertex_accessors(IoBuf *js, const GlbPart *p, int view, size_t lo, size_t nv);
void glb_skin_anim_accessors(IoBuf *js, const SylWind *w, int anim);
void glb_skin_attributes(IoBuf *js, int acc);
void glb_skin_roots(IoBuf *js, const SylWind *w, int first_node, bool comma);
void glb_skin_nodes(IoBuf *js, const SylWind *w, int first_node, const char *prefix, const int *start, const int *extra);
void glb_skin_json(IoBuf *js, const SylWind *w, int first_node, int anim_acc, const int *copies, int ncopies);
/* A skinned part's instance sets split by the joint each instance follows (the heavier of
 * its place's blend), translations from that joint's base: *n sets, *joint[k] the joint of
 * set k; the prototypes are borrowed. False when out of memory. */
bool glb_skin_split(const GlbPart *p, SylInstances **out, int **joint, int *n);
void glb_skin_split_free(SylInstances *sets, int n);

#endif
