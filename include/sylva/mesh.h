/* Mesh: triangles made from a skeleton — generalized cylinders along each axis, organs and
 * polygons — with smooth normals, UVs and one group of triangles per material. */
#ifndef SYLVA_MESH_H
#define SYLVA_MESH_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "skeleton.h"
#include "sylva.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct SylMeshGroup {
    uint32_t first, count; /* a range of SylMesh.idx (a multiple of 3) */
    uint8_t material;
} SylMeshGroup;

typedef struct SylMesh {
    float *pos, *nrm, *uv; /* 3, 3 and 2 floats per vertex; uv as in glTF: v = 0 is the
                              top row of a texture */
    size_t nverts;
    uint32_t *idx;         /* triangles, counter-clockwise seen from outside */
    size_t nidx;
    SylMeshGroup *groups;  /* sorted by material, no two with the same material */
    int ngroups;
    SylMaterial materials[256];
    int nmaterials;
    uint8_t card_shape[256];   /* per material, with SYL_LEAVES_CARDS: 1 + the shape its leaves'
                                  cards draw (their own outline, or SylMeshOptions.leaf_shape:
                                  a scene's plants each keep theirs); 0: leaf_shape */
    uint8_t double_sided[256]; /* per material, with SylMeshOptions.one_sided: 1 when it has
                                  leaves or petals made once, to be drawn from both sides */
    int32_t *node;         /* with SylMeshOptions.vertex_nodes: the skeleton node each vertex
                              was made for: a tube's last node (one of its axis), an organ's or
                              a polygon's node (-1: none); else NULL */
    char name[64];
    uint8_t leaves, leaf_shape; /* SYL_LEAVES_* it was made with; for cards and clusters, the
                                   shape drawn (clusters: SYL_CLUSTER_NEEDLES for needles) */

    SylImages *images;     /* its materials' images (SylMaterial.image), one reference; NULL: none */
    struct SylMeshStore *store; /* the library's own record of a mesh it made (how its arrays are
                                   held, the memory budget they count against); NULL for a mesh
                                   made by hand, whose arrays syl_mesh_free frees one by one */
} SylMesh;

enum { SYL_RADIUS_MODEL, SYL_RADIUS_PIPE };
/* How leaves are made (docs/mesh.md#leaves): copied blades; one alpha-tested card each; left
 * out of the mesh, to be placed as instances of one leaf (syl_instances_build); or leaves and
 * needles grouped into clusters, one alpha-tested card showing several leaves each. */
enum { SYL_LEAVES_MESH, SYL_LEAVES_CARDS, SYL_LEAVES_INSTANCED, SYL_LEAVES_INSTANCED_CARDS, SYL_LEAVES_CLUSTERS,
       SYL_LEAVES_MODES };
extern const char *const syl_leaves_names[SYL_LEAVES_MODES]; /* "mesh", "cards", ... */
enum { SYL_CLUSTER_LEAVES = 8 }; /* clusters: leaves per card by default (Pafčo's clusters hold 5 to 10) */

typedef struct SylMeshOptions {
    int sides;            /* around a cylinder; 0: 8 */
    int min_sides;        /* thin branches get fewer, down to this; 0: 3 */
    int radius;           /* SYL_RADIUS_MODEL: the turtle's widths; SYL_RADIUS_PIPE */
    float pipe_exponent;  /* 0: 2.0 (da Vinci) */
    float tip_radius;     /* pipe model: radius of a tip; 0: the mean of the model's tips */
    int caps;             /* close axis ends (default on: set -1 for off) */
    int leaves;           /* SYL_LEAVES_*: the instanced modes leave leaves out */
    int leaf_shape;       /* cards: SYL_LEAF_* (texture.h) drawn in the card's alpha */
    float cluster_leaves; /* clusters: leaves (and needles) per card on average; 0: SYL_CLUSTER_LEAVES */
    int threads;          /* <= 0: all cores; the mesh never depends on it */
    int vertex_nodes;     /* fill SylMesh.node (for skinning: wind, docs/mesh.md#wind) */
    int one_sided;        /* leaves and petals made once, not once a side, their materials marked
                           * in SylMesh.double_sided: for glTF, whose viewers then draw both sides
                           * (half the leaves' vertices); 0: two faces, for formats that cannot */
    FILE *diag;           /* where problems are reported; NULL: nowhere */
    const SylSink *sink;  /* or as records to this sink instead (sylva.h); NULL: diag */
    /* The mesh's size is estimated before anything is allocated: beyond the memory budget
     * it stops with SYL_ELIMIT and says so. */
    uint64_t max_memory;  /* bytes, when budget is NULL; 0: the default */
    SylBudget *budget;    /* shared memory budget; the mesh counts against it until freed */
    const SylCancel *cancel; /* asked before planning and before writing the mesh (sylva.h) */
} SylMeshOptions;

int syl_mesh_build(const SylSkeleton *s, const SylMeshOptions *opt, SylMesh **out);
void syl_mesh_free(SylMesh *m);
/* The shape drawn in the alpha of material's cards (--leaves cards): its own leaf outline when
 * it has one (a scene's plants each keep theirs), else leaf_shape. */
int syl_mesh_card_shape(const SylMesh *m, int material);
/* Add src's vertices and triangles to dst (groups stay one per material, sorted; src's
 * materials replace dst's of the same index). SYL_OK or SYL_ELIMIT. */
int syl_mesh_append(SylMesh *dst, const SylMesh *src);
/* A scene's objects (sk->parts): each plant's triangles of plants and each obstacle's of
 * obstacles (may be NULL) as a mesh of its own, named after it, *n of them in *out (none when
 * sk has no parts, or a mesh was made without SylMeshOptions.vertex_nodes). SYL_OK or
 * SYL_ELIMIT. */
int syl_mesh_split(const SylMesh *plants, const SylMesh *obstacles, const SylSkeleton *sk, SylMesh ***out, int *n);
void syl_mesh_parts_free(SylMesh **parts, int n);
/* The radius the mesher gives the segment ending at each node (s->nnodes floats): the
 * model's, or the pipe model's. SYL_EMODEL when a parent does not precede its child. */
int syl_mesh_radii(const SylSkeleton *s, const SylMeshOptions *opt, float *radius);
/* meshoptimizer: triangles without area (two corners at the same point) dropped, those of
 * each group reordered for the vertex cache, then vertices in first-use order (unused ones
 * dropped). SYL_OK or SYL_ELIMIT. */
int syl_mesh_optimize(SylMesh *m);
/* Simplify each group toward ratio of its triangles (meshopt_simplify; the sloppy simplifier
 * when many small parts keep it far above), moving the surface by at most max_error relative
 * to the mesh's size; then syl_mesh_optimize. *error (may be NULL): the error reached, in
 * model units. */
int syl_mesh_simplify(SylMesh *m, double ratio, float max_error, float *error);
/* The same for the groups whose material is of that kind (SYL_MATERIAL_*; -1: every group),
 * the others kept as they are. */
int syl_mesh_simplify_kind(SylMesh *m, int kind, double ratio, float max_error, float *error);

/* Copies of one prototype mesh placed by translation, rotation (unit quaternion x, y, z, w)
 * and scale, as glTF's EXT_mesh_gpu_instancing wants them: a vertex p of the prototype is at
 * T + R (S p). For leaves, and for anything else written many times (a forest's trees). */
typedef struct SylInstances {
    SylMesh *proto;
    size_t count;
    float *t, *r, *s; /* 3, 4 and 3 floats per instance */
    int32_t *node;    /* with SylMeshOptions.vertex_nodes: each instance's skeleton node (the
                         leaf's organ node, -1: none), for wind; else NULL */
    char name[64];
} SylInstances;

/* The leaves of s as instances: one set per leaf material, the prototype a leaf of size 1
 * at the origin along +x, across +y, facing +z (a blade for SYL_LEAVES_INSTANCED, a card for
 * SYL_LEAVES_INSTANCED_CARDS; opt->leaves picks). *n sets in *out, in material order; a leaf
 * the mesher would drop (no size, no frame) is left out too. SYL_OK or SYL_ELIMIT. */
int syl_instances_build(const SylSkeleton *s, const SylMeshOptions *opt, SylInstances **out, int *n);
void syl_instances_free(SylInstances *sets, int n);

/* Files (docs/mesh.md). Each writes to a temporary file and renames it, so a failure leaves
 * nothing; a symlink is followed, a FIFO or device written through (docs/cli.md#output-files).
 * OBJ writes its textures (PNG) beside the file; GLB embeds them. */
int syl_mesh_write_obj(const SylMesh *m, const char *path, const SylSink *sink); /* and NAME.mtl */
/* m (its materials and textures) written as the objects parts[0..n), `o NAME` each */
int syl_mesh_write_obj_parts(const SylMesh *m, SylMesh *const *parts, int n, const char *path, const SylSink *sink);
/* parts[0..n) as one node each, named after them, in the scene */
int syl_mesh_write_glb_parts(SylMesh *const *parts, int n, const char *name, const char *path, const SylSink *sink);
int syl_mesh_write_ply(const SylMesh *m, const char *path, const SylSink *sink); /* binary little endian */
int syl_mesh_write_glb(const SylMesh *m, const char *path, const SylSink *sink); /* glTF 2.0 binary */
/* m and n sets of instances in one .glb: each set a node with EXT_mesh_gpu_instancing (in
 * extensionsUsed only: a viewer without it shows the prototype once, at the origin). */
int syl_mesh_write_glb_instanced(const SylMesh *m, const SylInstances *sets, int n, const char *path, const SylSink *sink);
/* The mesh formats, one table by extension (src/io/formats.def: .glb, .obj, .ply, any case),
 * with what each can hold. */
enum {
    SYL_FORMAT_PARTS = 1,        /* a scene's objects, one each */
    SYL_FORMAT_INSTANCES = 2,    /* instance sets (--leaves instanced) */
    SYL_FORMAT_LEVELS = 4,       /* levels of detail and impostors */
    SYL_FORMAT_WIND = 8,         /* a skinned, animated mesh */
    SYL_FORMAT_DOUBLE_SIDED = 16 /* materials drawn from both sides: a leaf is written once */
};
typedef struct SylMeshFormat {
    const char *ext;  /* ".glb" */
    const char *name; /* "glTF 2.0 binary" */
    int can;          /* SYL_FORMAT_* */
} SylMeshFormat;
/* The format of a file by its name's extension; NULL when it names none, said to diag (NULL:
 * silently) as "cannot tell the format of PATH: name it *.glb, *.obj or *.ply". */
const SylMeshFormat *syl_mesh_format(const char *path, const SylSink *sink);
int syl_mesh_write(const SylMesh *m, const char *path, const SylSink *sink); /* by the extension */
/* A scene (m: all of it) as its objects, parts[0..n): one `o NAME` each in an OBJ, one node each
 * in a .glb; a PLY has no objects, so it is m whole. */
int syl_mesh_write_parts(const SylMesh *m, SylMesh *const *parts, int n, const char *path, const SylSink *sink);
/* A plant's mesh for one file and what goes with it, written in the format of the file's
 * extension by the writer what it holds asks for (the one place that chooses): levels of
 * detail (MSFT_lod; skinned too with wind), else a skinned mesh swaying in the wind, else the
 * leaves as instance sets, else the mesh with a scene's parts (syl_mesh_write_parts). What
 * the format cannot hold (SylMeshFormat.can) is refused, SYL_EUSAGE said on diag; else the
 * writer's status. */
typedef struct SylMeshOutput {
    const SylMesh *mesh;                 /* the whole plant */
    SylMesh *const *parts;               /* a scene's objects, parts[0 .. nparts) */
    int nparts;
    bool instanced;                      /* the leaves as instance sets[0 .. nsets) (maybe none) */
    const SylInstances *sets;
    int nsets;
    const struct SylLodChain *lods;      /* levels of detail (sylva/lod.h); NULL: none */
    const SylSkeleton *skeleton;         /* the plant the wind's joints are of */
    const struct SylWind *wind;          /* sylva/wind.h; NULL: not skinned */
} SylMeshOutput;
int syl_mesh_write_output(const SylMeshOutput *o, const char *path, const SylSink *sink);

enum { SYL_TEXTURE_SIZE = 512 };
/* For exporters: write PREFIX_bark.png, PREFIX_leaf.png and PREFIX_flower.png, each only if
 * a material group of m has that kind (m NULL: all of them and PREFIX_grass.png), as
 * SYL_TEXTURE_SIZE squares (syl_texture_draw, texture.h). They are white-based patterns: the
 * material's colour goes in the material (glTF baseColorFactor, MTL Kd), which multiplies
 * them — as the renderer does. Each file is written through a temporary file. Returns
 * SYL_OK, SYL_EIO or SYL_ELIMIT. */
int syl_mesh_write_textures(const SylMesh *m, const char *prefix, const SylSink *sink);

#ifdef __cplusplus
}
#endif

#endif
