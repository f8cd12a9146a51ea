/* Texture: procedural bark, leaf, flower and grass textures, and PNG pictures — what the
 * renderer and the mesh exporters both draw on. */
#ifndef SYLVA_TEXTURE_H
#define SYLVA_TEXTURE_H
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "sylva.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Procedural textures after Picek 2015 (bark with cracks along the branch, leaf with veins,
 * grass): size x size RGB, rows top to bottom. Kind is SYL_MATERIAL_*, or -1 for grass.
 * The texture is a pattern times rgb (in linear light); rgb NULL: white (grass: its green).
 * Image x is u: around a branch, across a leaf or petal (main vein at u = 0.5); image y is
 * v (row 0 first, as in glTF): along a branch, from a leaf's base (v = 0) to its tip (1).
 * Every texture tiles. SYL_MATERIAL_PLAIN is flat. False when out of memory: out is then
 * flat, which a writer must not commit as the texture. */
bool syl_texture_draw(int kind, const float rgb[3], int size, uint8_t *out);
/* "bark", "leaf", "flower", "grass" (kind -1); NULL for kinds without a texture. */
const char *syl_texture_name(int kind);

/* Leaf shapes for alpha-tested cards (docs/mesh.md#leaf-cards). A shape fills the card:
 * s runs from the leaf's base (0) to its tip (1), t across (-1..1, main vein at 0). */
enum { SYL_LEAF_OVATE, SYL_LEAF_LINEAR, SYL_LEAF_CORDATE, SYL_LEAF_MAPLE, SYL_LEAF_PALMATE, SYL_LEAF_SHAPES };
extern const char *const syl_leaf_shape_names[SYL_LEAF_SHAPES]; /* "ovate", ... */
int syl_leaf_shape_named(const char *name);                      /* -1: no such shape */
/* shape may also be 128 and above: a skeleton's own outline (Weber–Penn's LeafShape, coded
 * by the mesher as SylMesh.leaf_shape; src/util/leafoutline.h). */
bool syl_leaf_inside(int shape, float s, float t);
/* size x size RGBA: the leaf texture (white-based, as syl_texture_draw) with the shape's
 * coverage in alpha; x is u (across), y is v (base at row 0). False when out of memory. */
bool syl_leaf_draw_card(int shape, int size, uint8_t *rgba);
/* A leaf cluster card (docs/mesh.md#leaf-clusters): size x size RGBA, several leaves of the
 * shape radiating from the centre (SYL_CLUSTER_NEEDLES: a tuft of needles), the leaf texture
 * along each leaf in RGB and their coverage in alpha. False when out of memory. */
enum { SYL_CLUSTER_NEEDLES = SYL_LEAF_SHAPES };
bool syl_leaf_draw_cluster(int shape, int size, uint8_t *rgba);
/* The share of a cluster card an alpha cutoff of 1/2 keeps (measured on a 128 x 128 drawing
 * of the same leaves): what a card must be enlarged by to show a given leaf area. 0: out of
 * memory. */
float syl_leaf_cluster_fill(int shape);

/* Write width x height RGB (rows top to bottom) as a PNG. path "-": standard output;
 * otherwise as the mesh writers (mesh.h). */
int syl_png_write(const char *path, const uint8_t *rgb, int width, int height, const SylSink *sink);
/* The same with an alpha channel: 4 bytes a pixel. */
int syl_png_write_rgba(const char *path, const uint8_t *rgba, int width, int height, const SylSink *sink);

#ifdef __cplusplus
}
#endif

#endif
