/* The LOD chain: truncate the skeleton for each level, mesh it, simplify it. */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sylva/lod.h"
#include "util/leafoutline.h"
#include "util/rng.h"

/* Each level drops one more branch order (never the trunk's children) and thicker twigs;
 * leaves halve down to a quarter, the survivors growing by 1/sqrt(share) (at most 2x, as
 * Weber-Penn's leaf quality does), so the foliage keeps its area; each leaf is drawn with
 * fewer triangles, as large in area; the bark is simplified toward these shares of LOD0's
 * triangles, less the leaves'. */
static const float radius_share[SYL_LOD_MAX + 1] = {0, 0.02f, 0.05f, 0.1f, 0.16f, 0.22f, 0.3f, 0.4f, 0.5f};
static const double tri_share[SYL_LOD_MAX + 1] = {1, 0.45, 0.15, 0.045, 0.02, 0.01, 0.005, 0.0025, 0.00125};
/* Unity's default switch points, then halving; below the last level's, the plant is culled. */
static const float switch_at[SYL_LOD_MAX + 1] = {0.6f, 0.3f, 0.12f, 0.05f, 0.025f, 0.0125f, 0.006f, 0.003f, 0.0015f};

enum { MIN_LEAF_SHARE_LOG2 = 2, BLADE_SIDE_TRIS = 8 };
/* From LOD2 on (where thinning stops at a quarter), a level draws its leaves as clusters when
 * half its triangle share, in cards of 2 triangles, makes at least 4 leaves a card. */
enum { CLUSTER_FROM = 2, CARD_TRIS = 2 };
#define CLUSTER_MIN 4.0f
#define BLADE_AREA 1.225f  /* the mesher's blade, per length x half width (shapes.c) */
#define BLADE_WIDTH 0.22f  /* its half width per length */

/* Area of the mesher's oval of n triangles a side (n + 2 points of an ellipse), per length
 * x full width. */
static float oval_area(int n) { return (float)leaf_outline_area(LEAF_OUTLINE_OVAL, n); }

static bool clustered_kind(int kind) { return kind == SYL_KIND_LEAF || kind == SYL_KIND_NEEDLE; }

static bool thinned_kind(const SylLodLevel *lv, int kind) {
    return kind == SYL_KIND_FLOWER || (clustered_kind(kind) && !(lv->cluster_leaves > 0));
}

/* One uniform per organ or polygon, the same at every level, so a level's leaves are a
 * subset of the level above's. */
static double keep_draw(uint64_t table, size_t i) {
    Rng r = rng_stream(0x10d, table, i, 0);
    return rng_unit(&r);
}

static void scale_about(float p[3], const float c[3], float k) {
    for (int a = 0; a < 3; a++) p[a] = c[a] + k * (p[a] - c[a]);
}

/* A copy of s that borrows nothing: the level's nodes, organs and polygons; back[i]: the
 * node of s that node i of the copy is. */
static int truncate_skeleton(const SylSkeleton *s, const float *radius, const SylLodLevel *lv, SylSkeleton *t,
                             int32_t *back) {
    *t = *s;
    t->store = NULL; /* the mesher's copy: nothing is added to it, it is not freed as a skeleton */
    /* Coarser leaves of the same area, material by material: an oval of fewer triangles in
     * place of the blade or of LOD0's oval; shape: the linear factor that keeps each leaf's area. */
    float shape[256];
    for (int m = 0; m < 256; m++) {
        const SylMaterial *ms = &s->materials[m];
        bool own = ms->leaf_tris >= 1 && ms->leaf_width > 0 && isfinite(ms->leaf_width) &&
                   leaf_outline_valid(ms->leaf_outline, ms->leaf_tris);
        bool oval0 = own && ms->leaf_outline == LEAF_OUTLINE_OVAL;
        int n0 = oval0 ? ms->leaf_tris : BLADE_SIDE_TRIS, nk = n0 >> lv->level;
        if (nk < 1) nk = 1;
        if (own && !oval0) nk = n0; /* a square or a palm leaflet keeps its outline */
        float width = oval0 ? ms->leaf_width : 2 * BLADE_WIDTH;
        float area0 = oval0 ? oval_area(n0) * width : BLADE_AREA * BLADE_WIDTH;
        shape[m] = nk < n0 ? sqrtf(area0 / (oval_area(nk) * width)) : 1;
        if (nk < n0 && !(lv->cluster_leaves > 0)) /* clusters: LOD0's leaves' area */
            t->materials[m].leaf_tris = (uint16_t)nk, t->materials[m].leaf_width = width;
    }
    t->nodes = malloc((s->nnodes + 1) * sizeof *t->nodes);
    t->organs = malloc((s->norgans + 1) * sizeof *t->organs);
    t->polys = malloc((s->npolys + 1) * sizeof *t->polys);
    t->poly_verts = malloc((s->nverts + 1) * sizeof *t->poly_verts);
    int32_t *map = malloc((s->nnodes + 1) * sizeof *map);
    if (!t->nodes || !t->organs || !t->polys || !t->poly_verts || !map) {
        free(map);
        return SYL_ELIMIT;
    }
    size_t nn = 0;
    for (size_t i = 0; i < s->nnodes; i++) {
        const SylNode *n = &s->nodes[i];
        bool keep = n->parent < 0 || (n->parent < (int32_t)i && map[n->parent] >= 0);
        if (keep && n->order > 0 && (n->order > lv->max_order || radius[i] < lv->min_radius)) keep = false;
        map[i] = keep ? (int32_t)nn : -1;
        if (!keep) continue;
        t->nodes[nn] = *n;
        t->nodes[nn].parent = n->parent < 0 ? -1 : map[n->parent];
        t->nodes[nn].radius = radius[i]; /* the pipe model's radii of the whole tree, kept */
        back[nn++] = (int32_t)i;
    }
    t->nnodes = nn;
    size_t no = 0;
    for (size_t i = 0; i < s->norgans; i++) {
        SylOrgan o = s->organs[i];
        if (thinned_kind(lv, o.kind)) {
            if (keep_draw(1, i) >= lv->leaf_keep) continue;
            o.size *= lv->leaf_scale * (o.kind == SYL_KIND_LEAF ? shape[o.material] : 1);
        }
        o.node = o.node >= 0 && (size_t)o.node < s->nnodes ? map[o.node] : -1;
        t->organs[no++] = o;
    }
    t->norgans = no;
    size_t np = 0, nv = 0;
    for (size_t i = 0; i < s->npolys; i++) {
        SylPolygon p = s->polys[i];
        bool leafy = s->materials[p.material].kind != SYL_MATERIAL_BARK;
        if (leafy && keep_draw(2, i) >= lv->leaf_keep) continue;
        float c[3] = {0, 0, 0};
        for (uint32_t k = 0; k < p.count; k++)
            for (int a = 0; a < 3; a++) c[a] += s->poly_verts[p.first + k][a] / (float)p.count;
        for (uint32_t k = 0; k < p.count; k++) {
            memcpy(t->poly_verts[nv + k], s->poly_verts[p.first + k], sizeof *t->poly_verts);
            if (leafy) scale_about(t->poly_verts[nv + k], c, lv->leaf_scale);
        }
        p.first = (uint32_t)nv;
        p.node = p.node >= 0 && (size_t)p.node < s->nnodes ? map[p.node] : -1;
        nv += p.count;
        t->polys[np++] = p;
    }
    t->npolys = np;
    t->nverts = nv;
    free(map);
    return SYL_OK;
}

/* A level's vertex (or instance) nodes (SylMeshOptions.vertex_nodes) as nodes of the whole
 * skeleton, so that every level is skinned to the same joints. */
static void nodes_back(int32_t *node, size_t count, const int32_t *back, size_t n) {
    for (size_t v = 0; node && v < count; v++) node[v] = node[v] >= 0 && (size_t)node[v] < n ? back[node[v]] : -1;
}

static void free_copy(SylSkeleton *t) {
    free(t->nodes), free(t->organs), free(t->polys), free(t->poly_verts);
}

static int by_radius_down(const void *a, const void *b) {
    float x = *(const float *)a, y = *(const float *)b;
    return (x < y) - (x > y);
}

/* What level k keeps, from the skeleton's deepest order and thickest stem; down holds the
 * stems' radii, thickest first: a level never cuts more twigs than its triangle share asks
 * (a plant of countless thin twigs would lose its crown). */
/* Leaves per cluster card at level k (0: no clusters): half the level's triangles for the cards;
 * with --leaves clusters (per0: LOD0's), at least twice the level above's, as thinning halves. */
static float cluster_leaves(int k, size_t leaves, size_t tris0, int mode, float per0) {
    if (mode == SYL_LEAVES_INSTANCED || mode == SYL_LEAVES_INSTANCED_CARDS || !leaves) return 0;
    double cards = 0.5 * tri_share[k] * (double)tris0 / CARD_TRIS;
    float per = (float)((double)leaves / (cards > 1 ? cards : 1));
    if (mode == SYL_LEAVES_CLUSTERS) return fmaxf(per, per0 * powf(2, (float)k));
    return k >= CLUSTER_FROM && per >= CLUSTER_MIN ? per : 0;
}

static void plan_level(SylLodLevel *lv, int k, int levels, int top_order, float rmax, const float *down, size_t n) {
    lv->level = k;
    lv->max_order = top_order - k > 1 ? top_order - k : top_order < 1 ? top_order : 1;
    lv->min_radius = radius_share[k] * rmax;
    size_t keep = (size_t)(0.5 * tri_share[k] * (double)n);
    if (keep < n && down[keep] < lv->min_radius) lv->min_radius = down[keep];
    lv->leaf_keep = powf(0.5f, (float)(k < MIN_LEAF_SHARE_LOG2 ? k : MIN_LEAF_SHARE_LOG2));
    lv->leaf_scale = fminf(2.0f, 1 / sqrtf(lv->leaf_keep));
    if (lv->cluster_leaves > 0) lv->leaf_keep = 1, lv->leaf_scale = 1; /* flowers are still thinned */
    lv->coverage = syl_lod_coverage(k, levels);
}

int syl_lod_build(const SylSkeleton *s, const SylMeshOptions *mo, SylMesh *lod0, int levels, SylLodChain *out) {
    memset(out, 0, sizeof *out);
    if (levels < 0 || levels > SYL_LOD_MAX) return SYL_EUSAGE;
    float *radius = malloc((s->nnodes + 1) * sizeof *radius);
    if (!radius) return SYL_ELIMIT;
    int status = syl_mesh_radii(s, mo, radius);
    int top = 0;
    float rmax = 0;
    for (size_t i = 0; i < s->nnodes; i++) {
        if (s->nodes[i].kind != SYL_KIND_INTERNODE) continue;
        if (s->nodes[i].order > top) top = s->nodes[i].order;
        if (radius[i] > rmax) rmax = radius[i];
    }
    float *down = malloc((s->nnodes + 1) * sizeof *down);
    int32_t *back = malloc((s->nnodes + 1) * sizeof *back);
    size_t nstems = 0;
    for (size_t i = 0; down && i < s->nnodes; i++)
        if (s->nodes[i].kind == SYL_KIND_INTERNODE) down[nstems++] = radius[i];
    if (!down || !back) status = SYL_ELIMIT;
    else qsort(down, nstems, sizeof *down, by_radius_down);
    if (!status) status = syl_mesh_optimize(lod0);
    size_t leaves = 0;
    for (size_t i = 0; i < s->norgans; i++) leaves += clustered_kind(s->organs[i].kind) && s->organs[i].size > 0;
    float per0 = mo->cluster_leaves > 0 ? mo->cluster_leaves : SYL_CLUSTER_LEAVES;
    out->level[0] = (SylLodLevel){.mesh = lod0, .max_order = top, .leaf_keep = 1, .leaf_scale = 1,
                                  .coverage = syl_lod_coverage(0, levels),
                                  .cluster_leaves = mo->leaves == SYL_LEAVES_CLUSTERS ? per0 : 0};
    out->n = 1;
    size_t tris0 = lod0->nidx / 3;
    int sides = mo->sides > 0 ? mo->sides : 8;
    for (int k = 1; k <= levels && !status; k++) {
        SylLodLevel *lv = &out->level[k];
        lv->cluster_leaves = cluster_leaves(k, leaves, tris0, mo->leaves, per0);
        plan_level(lv, k, levels, top, rmax, down, nstems);
        SylSkeleton t;
        status = truncate_skeleton(s, radius, lv, &t, back);
        SylMeshOptions o = *mo;
        o.sides = (int)lroundf((float)sides * powf(0.75f, (float)k));
        if (o.sides < 3) o.sides = 3;
        o.min_sides = 3;
        o.radius = SYL_RADIUS_MODEL;
        if (lv->cluster_leaves > 0) o.leaves = SYL_LEAVES_CLUSTERS, o.cluster_leaves = lv->cluster_leaves;
        if (!status) status = syl_mesh_build(&t, &o, &lv->mesh);
        if (lv->mesh) out->n = k + 1;
        if (!status && (mo->leaves == SYL_LEAVES_INSTANCED || mo->leaves == SYL_LEAVES_INSTANCED_CARDS))
            status = syl_instances_build(&t, &o, &lv->sets, &lv->nsets);
        size_t kept = t.nnodes;
        free_copy(&t);
        if (status) break;
        size_t bark = 0;
        for (int g = 0; g < lv->mesh->ngroups; g++)
            if (lv->mesh->materials[lv->mesh->groups[g].material].kind == SYL_MATERIAL_BARK)
                bark += lv->mesh->groups[g].count / 3;
        /* the leaves are kept whole (thinning made them few): the bark takes the budget's rest,
         * a tenth of it at least */
        double want = (double)tris0 * tri_share[k] - (double)(lv->mesh->nidx / 3 - bark);
        double ratio = bark ? fmax(want, 0.1 * (double)bark) / (double)bark : 1;
        status = syl_mesh_simplify_kind(lv->mesh, SYL_MATERIAL_BARK, ratio, 0.004f * powf(3, (float)(k - 1)),
                                        &lv->error);
        nodes_back(lv->mesh->node, lv->mesh->nverts, back, kept);
        for (int i = 0; i < lv->nsets; i++) nodes_back(lv->sets[i].node, lv->sets[i].count, back, kept);
        snprintf(lv->mesh->name, sizeof lv->mesh->name, "%s", lod0->name);
    }
    free(radius), free(down), free(back);
    if (status) syl_lod_free(out);
    return status;
}

float syl_lod_coverage(int k, int levels) {
    if (k < 0 || k > SYL_LOD_MAX) return 0;
    return k == levels ? fminf(0.01f, switch_at[k]) : switch_at[k];
}

void syl_lod_free(SylLodChain *c) {
    for (int k = 1; k < c->n; k++) {
        syl_mesh_free(c->level[k].mesh);
        syl_instances_free(c->level[k].sets, c->level[k].nsets);
    }
    memset(c, 0, sizeof *c);
}
