/* Skeleton: the common currency of Sylva. The turtle emits it from an L-system string, the
 * growth engine grows it, and the mesher, renderer, exporters and metrics read it; nothing
 * downstream knows which engine made it.
 *
 * Frame convention: Y is up. Every node carries the turtle frame at its position: H heading,
 * L left, U up, with H x L = U. Lengths are model units (1 unit = 1 metre for exporters). */
#ifndef SYLVA_SKELETON_H
#define SYLVA_SKELETON_H
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "sylva.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    SYL_KIND_ROOT,      /* where an axis starts without a parent segment */
    SYL_KIND_INTERNODE, /* the end of a drawn segment (F, G) */
    SYL_KIND_LEAF,      /* organs: ~leaf */
    SYL_KIND_FLOWER,    /* ~petal, flowers */
    SYL_KIND_NEEDLE,    /* ~needle */
    SYL_KIND_SPHERE,    /* @O, @o */
    SYL_KIND_BUD,
    SYL_KIND_DISC,      /* @c: a flat disc in the turtle's H-L plane */
    SYL_KIND_COUNT
} SylKind;

extern const char *const syl_kind_names[SYL_KIND_COUNT]; /* "root", "internode", ... */

enum {
    SYL_NODE_SMOOTH = 1, /* inside @Gc ... @Ge: the mesher smooths the axis through it */
};

/* A node: the root of an axis, or the end of one drawn segment whose start is its parent. */
typedef struct SylNode {
    float pos[3];
    float h[3], l[3], u[3];
    float radius;      /* of the segment ending here (half the turtle's width) */
    int32_t parent;    /* -1 for a root */
    int32_t axis;      /* axes are maximal chains; a lateral branch starts a new one */
    uint16_t order;    /* branch order: 0 trunk, 1 its branches, ... */
    uint8_t kind;      /* SylKind */
    uint8_t material;  /* index into SylSkeleton.materials */
    uint8_t flags;     /* SYL_NODE_* */
    /* A lobed cross-section at this node (0: round): the mesher draws radius x (1 + depth x
     * sin(lobes x a)) at angle a about the axis, depth = lobe_depth / 10000 (Weber & Penn's
     * Lobes and LobeDepth; it sits in the struct's padding). */
    uint8_t lobes;
    uint16_t lobe_depth;
    uint32_t module;   /* index of the module that made it, in the string the turtle read */
} SylNode;

/* An organ placed at a point with a frame: a predefined surface or a sphere. */
typedef struct SylOrgan {
    float pos[3];
    float h[3], l[3], u[3];
    float size;       /* scale of the surface; diameter of a sphere or a disc */
    int32_t node;     /* the node it is attached to (-1: none) */
    uint8_t kind;     /* SYL_KIND_LEAF, _FLOWER, _NEEDLE, _SPHERE or _DISC */
    uint8_t material;
    uint32_t module;
} SylOrgan;

/* A polygon drawn with { . } : vertices in order, outline closed implicitly. */
typedef struct SylPolygon {
    uint32_t first, count; /* into SylSkeleton.poly_verts */
    int32_t node;          /* the node current when it was closed (-1: none) */
    uint8_t material;
    uint32_t module;
} SylPolygon;

enum { SYL_MATERIAL_BARK, SYL_MATERIAL_LEAF, SYL_MATERIAL_FLOWER, SYL_MATERIAL_PLAIN };

enum { SYL_LEAF_OUTLINE_OVAL, SYL_LEAF_OUTLINE_SQUARE, SYL_LEAF_OUTLINE_PALM };

/* A material is a plant's surface: its colour, and what the mesher draws with it, so that each
 * plant of a scene keeps its own (a scene's skeleton gives each plant's materials slots of
 * their own, docs/mesh.md#scenes). */
typedef struct SylMaterial {
    float rgb[3];   /* base colour, 0..1 */
    uint8_t kind;   /* SYL_MATERIAL_*: chooses the procedural texture */
    /* The surface of every SYL_KIND_LEAF organ of this material (leaf_tris 0: Sylva's blade):
     * the outline leaf_outline (SYL_LEAF_OUTLINE_OVAL of leaf_tris triangles, Arbaro's
     * disc1..disc9; _SQUARE; _PALM, a folded leaflet), leaf_width wide per unit of length. */
    uint8_t leaf_outline;
    uint16_t leaf_tris;
    float leaf_width;
    /* Jitter of a trunk's surface drawn with it (Weber–Penn's 0ScaleV, as Arbaro draws it):
     * the mesher moves each vertex of an order-0 ring to (1 + u) times its distance from the
     * axis, u uniform in [-trunk_jitter, trunk_jitter], drawn per ring and vertex. 0: none. */
    float trunk_jitter;
    uint8_t translucency; /* light let through, 0..255 (glTF KHR_materials_transmission); 0: opaque */
    /* An image of the model's own instead of the procedural texture (docs/language.md#21-textures-bark-and-leaf-images):
     * 0 none, k the skeleton's images->img[k - 1]. Bark repeats it tile[0] times around a
     * branch and tile[1] times as often along it (0: once); a leaf is a card of the image's
     * proportions, its alpha the outline. */
    uint8_t image;
    /* Points of a ring around a stem drawn with it, of branch order 0, 1, 2, 3 and more, as
     * its model asks (Pafčo's DETAIL, docs/pafco.md; the curve tree's resolutions): the mesher
     * uses them when its caller set no sides. 0: the mesher's own rule (sides falling with
     * the radius). */
    uint8_t ring_sides[4];
    float tile[2];
} SylMaterial;

enum { SYL_IMAGES_MAX = 64 };
/* An image file a model names as a texture: the PNG's bytes as read (a .glb embeds them, an
 * OBJ gets a copy beside its MTL), its size in pixels, its name as written in the model. */
typedef struct SylImage {
    char name[160];
    uint8_t *png;
    size_t len;
    int width, height;
    int alpha; /* the PNG has an alpha channel (or a transparent colour) */
} SylImage;
/* A skeleton's images, shared by the meshes made from it: counted references
 * (syl_images_ref, syl_images_release), never changed once attached. */
typedef struct SylImages {
    int refs;
    int n;
    SylImage img[SYL_IMAGES_MAX];
} SylImages;
SylImages *syl_images_ref(SylImages *im);  /* im (NULL: NULL), one more reference */
/* The image material m names in im; NULL when it names none (or im lacks it). */
const SylImage *syl_material_image(const SylImages *im, const SylMaterial *m);
void syl_images_release(SylImages *im);    /* one reference less; the last frees it */
/* The index + 1 of image g in *into (a copy of it added, *into made when NULL, when none there
 * has its name and bytes); 0 when it does not fit (SYL_IMAGES_MAX) or memory ran out. For
 * one skeleton made of others' (a scene): *into must be only its own (one reference). */
int syl_images_add(SylImages **into, const SylImage *g);
/* What a model's texture lines ask (lang reads them; docs/language.md#21-textures-bark-and-leaf-images): the images,
 * bark's (1 + its index, 0: none) with its tiles, and the leaves' (several: mixed at random). */
typedef struct SylTextureSpec {
    SylImages *images; /* NULL: no texture lines */
    int bark;
    float tile[2];
    uint8_t leaf[SYL_IMAGES_MAX];
    int nleaf;
} SylTextureSpec;

typedef struct SylSkeletonPart {
    size_t first_node; /* a plant's first node */
    int obstacle;      /* 0: a plant; k > 0: the scene's obstacle k - 1 */
    char name[64];
} SylSkeletonPart;

/* Build one with syl_skeleton_new and the syl_skeleton_add_* functions, which keep the arrays'
 * room and the memory budget in store (the library's own). */
typedef struct SylSkeleton {
    SylNode *nodes;
    size_t nnodes;
    SylOrgan *organs;
    size_t norgans;
    SylPolygon *polys;
    size_t npolys;
    float (*poly_verts)[3];
    size_t nverts;
    SylMaterial materials[256];
    int nmaterials;  /* indices below this are in use */
    char name[64];
    /* A scene's objects, each written as an object or node of its own (docs/mesh.md#scenes):
     * its plants, in order, each from its first node to the next one's, then its obstacles,
     * whose meshes (SylMesh.node) number them from 0. Unique names. */
    SylSkeletonPart *parts;
    int nparts;
    struct SylSkeletonStore *store;
    SylImages *images; /* the images its materials name (SylMaterial.image); NULL: none */
} SylSkeleton;

SylSkeleton *syl_skeleton_new(const char *name); /* default palette: bark, leaf, flower, ... */
void syl_skeleton_free(SylSkeleton *s);
/* A scene's next object (plant: from the next node on; obstacle: k > 0, its k - 1), named name
 * or, when an object has that name already, name_2, name_3 …; -1: out of memory. */
int syl_skeleton_add_part(SylSkeleton *s, const char *name, int obstacle);
int32_t syl_skeleton_add_node(SylSkeleton *s, const SylNode *n);   /* returns its index; -1 out of memory */
int32_t syl_skeleton_add_organ(SylSkeleton *s, const SylOrgan *o);
int32_t syl_skeleton_add_polygon(SylSkeleton *s, const float (*verts)[3], uint32_t n, int32_t node,
                                 uint8_t material, uint32_t module);
/* Give sk the textures of spec (its images move to sk; spec->images becomes NULL): every bark
 * material bark's image and tiles; every leaf material used by a leaf organ the first leaf
 * image, copied into a material per further image, and each leaf organ one of those, chosen
 * at random by seed and its index (the same for the same seed, whatever the threads).
 * SYL_OK, or SYL_ELIMIT when the leaves' copies do not fit in 256 materials. */
int syl_skeleton_apply_textures(SylSkeleton *sk, SylTextureSpec *spec, uint64_t seed);
/* Axis-aligned bounds of nodes, organs and polygons. */
void syl_skeleton_bounds(const SylSkeleton *s, float lo[3], float hi[3]);
/* id,parent,x,y,z,radius,order,kind — nodes, then organs (parent: their node). */
int syl_skeleton_write_csv(const SylSkeleton *s, FILE *out);
int syl_skeleton_write_json(const SylSkeleton *s, FILE *out);

typedef struct SylTurtleOptions {
    FILE *diag;
    /* The skeleton's nodes are counted before they are allocated: beyond the memory budget
     * the turtle stops with SYL_ELIMIT. */
    uint64_t max_memory;  /* bytes, when budget is NULL; 0: the default */
    SylBudget *budget;    /* shared memory budget; the skeleton counts against it until freed */
    /* The seed of the leaves' choice among several leaf_texture images: seed when use_seed
     * is set (the derivation's --seed), else the model's. */
    int use_seed;
    uint64_t seed;
    const SylCancel *cancel; /* asked every 65,536 modules (sylva.h); NULL: never */
} SylTurtleOptions;

/* Interpret a derived string (after `interpret` rules, see syl_interpret) with the 3D
 * turtle of docs/turtle.md and return its skeleton. */
int syl_turtle_draw(const SylProgram *p, const SylString *s, const SylTurtleOptions *opt, SylSkeleton **out);

/* The turtle's query pass, for a query environment of your own (SylQueryOps.fill): fill the
 * query modules ?P(x,y,z), ?H, ?L and ?U of s in place with the turtle's position and frame
 * where each one stands (docs/language.md, "Query modules"); nothing else changes. With env,
 * also collect every segment end and every ?E module (position, heading, where its parameters
 * are in syl_string_params) into env, emptied first; without, ?E modules are not looked at.
 * SYL_OK, or SYL_ELIMIT when out of memory. env starts as {0} and may be filled again (its
 * arrays are reused); free it with syl_env_fill_free. */
int syl_turtle_query(const SylProgram *p, SylString *s, SylEnvFill *env);
/* Free env's arrays and record and empty it (env may be NULL). */
void syl_env_fill_free(SylEnvFill *env);

#ifdef __cplusplus
}
#endif

#endif
