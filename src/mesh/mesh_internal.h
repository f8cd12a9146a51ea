/* The mesher's parts: a plan (tubes, organs and polygons with exact vertex and triangle
 * counts, and where each run of triangles goes in SylMesh.idx), then emission into arrays
 * sized once. Emission of one piece touches only its own ranges, so pieces can be written
 * by any thread in any order and the mesh is the same. */
#ifndef SYL_MESH_INTERNAL_H
#define SYL_MESH_INTERNAL_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "sylva/mesh.h"
#include "util/leafoutline.h"

enum { MESH_MAX_SIDES = 256 };

/* A point on a tube's centre line. */
typedef struct MeshPt {
    float p[3];
    float r;
    uint8_t mat; /* of the segment ending here (the first point: of the first segment) */
    uint8_t lobes;       /* its node's lobed cross-section (0: round) */
    uint16_t lobe_depth; /* as SylNode's */
} MeshPt;

/* Triangles of one material, written from SylMesh.idx[idx] on. */
typedef struct MeshRun {
    size_t idx;
    uint32_t tris;
    uint8_t mat;
} MeshRun;

typedef struct MeshTube {
    size_t vert;           /* first vertex */
    uint32_t first, count; /* points, into MeshPlan.pts */
    uint32_t run;          /* first run; a tube has one run per change of material */
    uint16_t sides;
    float rmax;            /* its largest radius */
    float ref[3];          /* the frame's first normal, perpendicular to the first tangent */
    int32_t node;          /* its last node (SylMesh.node) */
} MeshTube;

/* An organ or a polygon: one run. */
typedef struct MeshItem {
    size_t vert;
    uint32_t index; /* into SylSkeleton.organs or MeshPlan.polys */
    uint32_t run;
    uint32_t verts;
    int32_t node;   /* the node it hangs on (SylMesh.node; -1: none) */
    bool poly;
    bool cluster;   /* index: into MeshPlan.clusters */
} MeshItem;

/* A leaf cluster's card (clusters.c): centre, half extents along and across, its normal. */
typedef struct MeshCluster {
    float c[3], a[3], b[3], n[3];
    int32_t node; /* its first leaf's node */
    uint8_t mat;
} MeshCluster;

/* A polygon after cleaning and triangulation. */
typedef struct MeshPoly {
    uint32_t first, count; /* kept vertices: MeshPlan.pv[first..] index SylSkeleton.poly_verts */
    uint32_t tri, ntris;   /* MeshPlan.ptri[3 * tri ..]: local vertex numbers */
    float n[3], e1[3], e2[3]; /* unit normal and plane axes (e1 x e2 = n) */
    float uv0[2], uvscale;
} MeshPoly;

typedef struct MeshTrig {
    float c[MESH_MAX_SIDES + 1], s[MESH_MAX_SIDES + 1], u[MESH_MAX_SIDES + 1]; /* cos, sin, j / sides */
} MeshTrig;

typedef struct MeshPlan {
    const SylSkeleton *skel;
    int sides, min_sides, sphere_stacks, leaves;
    bool model_sides; /* no sides asked for: its materials' ring_sides, where they give them, win */
    int leaf_shape, cluster_shape; /* clusters: the shape the cards show (SYL_CLUSTER_NEEDLES) */
    float cluster_leaves;          /* clusters: leaves per card */
    MeshCluster *clusters;
    size_t nclusters, clusters_cap;
    bool caps, one_sided; /* one_sided: SylMeshOptions.one_sided */
    MeshPt *pts;
    size_t npts, pts_cap;
    MeshTube *tubes;
    size_t ntubes, tubes_cap;
    MeshRun *runs;
    size_t nruns, runs_cap;
    MeshItem *items;
    size_t nitems, items_cap;
    MeshPoly *polys;
    size_t npolys, polys_cap;
    uint32_t *pv, *ptri;
    size_t npv, pv_cap, nptri, ptri_cap;
    MeshTrig *trig[MESH_MAX_SIDES + 1]; /* by number of sides, as needed */
    size_t nverts;
    float uv_rmin; /* bark v's radius floor: 1/100 of the thickest tube's (mesh.c) */
    LeafPanel *panels[256]; /* by material: its own leaf outline, computed once (NULL: the blade) */
    uint8_t npanels[256];
} MeshPlan;

/* Grow *arr to hold n + more elements; false when out of memory. */
bool mesh_reserve(void **arr, size_t *cap, size_t n, size_t more, size_t elem);
/* Add a run of tris triangles of material mat. */
bool mesh_add_run(MeshPlan *pl, uint8_t mat, uint32_t tris);
const MeshTrig *mesh_trig(MeshPlan *pl, int sides);

/* An organ's unit frame (H along, L across, U = H x L); false when it has none or no size. */
bool mesh_organ_frame(const SylOrgan *o, float h[3], float l[3], float u[3]);
/* The half width of a leaf per unit of length (the blade's or its material's own). */
float mesh_leaf_width(const SylMaterial *m);
/* Does the material name its own leaf surface (leaf_outline, leaf_tris, leaf_width)? */
bool mesh_own_leaf(const SylMaterial *m);

/* Organs and polygons (shapes.c). Planning adds items and runs; emission fills them. */
bool mesh_plan_shapes(MeshPlan *pl);
void mesh_emit_item(const MeshPlan *pl, const MeshItem *it, SylMesh *m);
/* The area one side of an organ shows as the mesher draws it (SYL_LEAVES_MESH): a leaf's
 * blade or oval; half the surface of a closed needle, which shows as much on average. */
float mesh_organ_side_area(const MeshPlan *pl, const SylOrgan *o);

/* Leaf clusters (clusters.c): one card item per group of about per_card leaves and needles
 * (which organ planning then leaves out), and a card's 4 vertices and 2 triangles. */
bool mesh_plan_clusters(MeshPlan *pl, float per_card);
void mesh_emit_cluster(const MeshCluster *k, float *pos, float *nrm, float *uv, uint32_t *idx, uint32_t v0);

/* firstuse.c: a piece's vertices (nv from vert on) in the order its runs' triangles first use
 * them, the triangles renumbered; f is the caller's scratch, kept between pieces */
typedef struct MeshFirstUse {
    uint32_t *id;
    float *tmp;
    size_t cap;
} MeshFirstUse;
void mesh_first_use(MeshFirstUse *f, SylMesh *m, size_t vert, size_t nv, const MeshRun *runs, size_t nruns);
void mesh_first_use_free(MeshFirstUse *f);

#endif
