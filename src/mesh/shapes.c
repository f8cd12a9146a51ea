/* Organs and polygons. Leaves, petals and polygons are thin: both sides are made, each with
 * its own normals, so they shade right from either side without a double-sided material
 * (for glTF, leaves and petals are made once, their material double-sided: one_sided).
 * Needles and spheres are closed.
 *
 * Organ frame: H along the organ, L across, U = H x L its face. A leaf is a blade of length
 * size along H, a fifth as wide each way along L, with UVs 0..1 over the blade (v along the
 * main vein, u across). A flower is five such petals around H, tilted forward. A needle is a
 * slender three-sided spike. A sphere is a UV sphere of diameter size about H. A disc (cpfg's
 * circle) is a flat fan of diameter size in the H-L plane, facing U, made on both sides. A
 * leaf's material may name its own leaf surface (leaf_outline, leaf_tris, leaf_width:
 * Weber–Penn's named shapes, util/leafoutline.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cglm/cglm.h>

#include "mesh/mesh_internal.h"
#include "util/leafoutline.h"

/* The blade: x along 0..1, y across -1..1; triangles counter-clockwise in (x, y). */
static const float blade_xy[8][2] = {{0, 0},    {0.3f, 0},  {0.7f, 0},     {1, 0},
                                     {0.3f, 1}, {0.7f, 0.75f}, {0.3f, -1}, {0.7f, -0.75f}};
static const uint8_t blade_tri[8][3] = {{0, 6, 1}, {0, 1, 4}, {1, 6, 7}, {1, 7, 2},
                                        {1, 2, 5}, {1, 5, 4}, {2, 7, 3}, {2, 3, 5}};
enum { BLADE_V = 16, BLADE_T = 16, PETALS = 5, NEEDLE_V = 7, NEEDLE_T = 4 };
#define LEAF_WIDTH 0.22f  /* half width / length */
#define PETAL_LENGTH 0.5f /* of the flower's size */
#define PETAL_WIDTH 0.36f /* half width / petal length */
#define PETAL_TILT 0.45f  /* radians towards H */
#define NEEDLE_WIDTH 0.03f

bool mesh_organ_frame(const SylOrgan *o, float h[3], float l[3], float u[3]) {
    if (!(o->size > 0) || !isfinite(o->size) || !isfinite(o->pos[0]) || !isfinite(o->pos[1]) ||
        !isfinite(o->pos[2]))
        return false;
    memcpy(h, o->h, sizeof(vec3));
    memcpy(l, o->l, sizeof(vec3));
    float hn = glm_vec3_norm(h);
    if (!(hn > 1e-6f) || !isfinite(hn)) return false;
    glm_vec3_scale(h, 1.0f / hn, h);
    glm_vec3_muladds(h, -glm_vec3_dot(l, h), l);
    float ln = glm_vec3_norm(l);
    if (!(ln > 1e-6f) || !isfinite(ln)) {
        vec3 a = {1, 0, 0};
        if (fabsf(h[0]) > 0.9f) a[0] = 0, a[1] = 1;
        glm_vec3_cross(h, a, l);
        ln = glm_vec3_norm(l);
    }
    glm_vec3_scale(l, 1.0f / ln, l);
    glm_vec3_cross(h, l, u);
    return true;
}

_Static_assert((int)SYL_LEAF_OUTLINE_OVAL == (int)LEAF_OUTLINE_OVAL && (int)SYL_LEAF_OUTLINE_SQUARE == (int)LEAF_OUTLINE_SQUARE &&
                   (int)SYL_LEAF_OUTLINE_PALM == (int)LEAF_OUTLINE_PALM,
               "the public outline numbers are util/leafoutline.h's");

/* Does the material name its own leaf surface (Weber–Penn's shapes)? Else Sylva's blade. */
bool mesh_own_leaf(const SylMaterial *m) {
    return m->leaf_tris >= 1 && m->leaf_width > 0 && isfinite(m->leaf_width) &&
           leaf_outline_valid(m->leaf_outline, m->leaf_tris);
}

float mesh_leaf_width(const SylMaterial *m) { return mesh_own_leaf(m) ? 0.5f * m->leaf_width : LEAF_WIDTH; }

/* A leaf or flower material with an image of its own (SylMaterial.image) is a card, its alpha
 * the outline, as wide as the material's own leaf (Weber–Penn's LeafScaleX, Pafčo's
 * billboards) or else of the image's proportions: the half width per unit of length; 0 when
 * it has no image. */
static float image_leaf(const MeshPlan *pl, int mat) {
    const SylMaterial *m = &pl->skel->materials[mat];
    bool leafy = m->kind == SYL_MATERIAL_LEAF || m->kind == SYL_MATERIAL_FLOWER;
    const SylImage *g = leafy ? syl_material_image(pl->skel->images, m) : NULL;
    return !g ? 0 : mesh_own_leaf(m) ? 0.5f * m->leaf_width : 0.5f * (float)g->width / (float)g->height;
}

/* Vertices and triangles of a material's own leaf, both faces. */
static void own_leaf_counts(const MeshPlan *pl, int mat, uint32_t *verts, uint32_t *tris) {
    *verts = *tris = 0;
    for (int k = 0; k < pl->npanels[mat]; k++)
        *verts += 2 * (uint32_t)pl->panels[mat][k].n, *tris += 2 * (uint32_t)(pl->panels[mat][k].n - 2);
}

static void organ_counts(const MeshPlan *pl, const SylOrgan *o, uint32_t *verts, uint32_t *tris) {
    vec3 h, l, u;
    *verts = *tris = 0;
    if (!mesh_organ_frame(o, h, l, u)) return;
    uint32_t st = (uint32_t)pl->sphere_stacks, sl = (uint32_t)pl->sides;
    switch (o->kind) {
    case SYL_KIND_LEAF:
        if (pl->leaves == SYL_LEAVES_INSTANCED || pl->leaves == SYL_LEAVES_INSTANCED_CARDS ||
            pl->leaves == SYL_LEAVES_CLUSTERS)
            break; /* placed apart */
        if (image_leaf(pl, o->material) > 0) { /* a card, both faces unless one_sided */
            *verts = pl->one_sided ? 4 : 8, *tris = pl->one_sided ? 2 : 4;
            break;
        }
        if (pl->leaves == SYL_LEAVES_CARDS) *verts = 4, *tris = 2;
        else if (pl->npanels[o->material]) own_leaf_counts(pl, o->material, verts, tris);
        else *verts = BLADE_V, *tris = BLADE_T;
        if (pl->one_sided && pl->leaves != SYL_LEAVES_CARDS) *verts /= 2, *tris /= 2;
        break;
    case SYL_KIND_FLOWER:
        if (image_leaf(pl, o->material) > 0) { /* one card of the flower's image */
            *verts = pl->one_sided ? 4 : 8, *tris = pl->one_sided ? 2 : 4;
            break;
        }
        *verts = PETALS * BLADE_V, *tris = PETALS * BLADE_T;
        if (pl->one_sided) *verts /= 2, *tris /= 2;
        break;
    case SYL_KIND_NEEDLE:
        if (pl->leaves != SYL_LEAVES_CLUSTERS) *verts = NEEDLE_V, *tris = NEEDLE_T;
        break;
    case SYL_KIND_SPHERE: *verts = (st + 1) * (sl + 1), *tris = 2 * sl * (st - 1); break;
    case SYL_KIND_DISC: *verts = 2 * (sl + 1), *tris = 2 * sl; break;
    default: break;
    }
}

/* ------------------------------------------------------------------ polygons */

static float cross2(const float *a, const float *b, const float *c) {
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/* p inside or on triangle abc (counter-clockwise)? */
static bool in_triangle(const float *p, const float *a, const float *b, const float *c) {
    return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
}

/* Triangulate a counter-clockwise polygon of k points (2D): a fan when it is convex, ear
 * clipping otherwise. Writes local vertex triples to tri; returns how many. */
static uint32_t triangulate(const float (*xy)[2], uint32_t k, uint32_t *tri, uint32_t *ring) {
    uint32_t nt = 0;
    bool convex = true;
    for (uint32_t i = 0; i < k && convex; i++)
        if (cross2(xy[(i + k - 1) % k], xy[i], xy[(i + 1) % k]) < 0) convex = false;
    if (convex) {
        for (uint32_t i = 1; i + 1 < k; i++) tri[3 * nt] = 0, tri[3 * nt + 1] = i, tri[3 * nt + 2] = i + 1, nt++;
        return nt;
    }
    for (uint32_t i = 0; i < k; i++) ring[i] = i;
    uint32_t n = k, i = 0, misses = 0;
    while (n > 3) {
        uint32_t a = ring[(i + n - 1) % n], b = ring[i], c = ring[(i + 1) % n];
        float cr = cross2(xy[a], xy[b], xy[c]);
        bool ear = false, drop = cr == 0; /* a straight or folded-back point: nothing to fill */
        if (cr > 0) {
            ear = true;
            for (uint32_t q = 0; q < n && ear; q++) {
                uint32_t p = ring[q];
                if (p == a || p == b || p == c || !memcmp(xy[p], xy[a], sizeof xy[0]) ||
                    !memcmp(xy[p], xy[b], sizeof xy[0]) || !memcmp(xy[p], xy[c], sizeof xy[0]))
                    continue;
                if (in_triangle(xy[p], xy[a], xy[b], xy[c])) ear = false;
            }
        }
        if (!ear && !drop && misses > n) ear = true; /* self-intersecting: clip anyway */
        if (ear || drop) {
            if (ear) tri[3 * nt] = a, tri[3 * nt + 1] = b, tri[3 * nt + 2] = c, nt++;
            memmove(ring + i, ring + i + 1, (n - i - 1) * sizeof *ring);
            n--;
            if (i >= n) i = 0;
            misses = 0;
        } else {
            i = (i + 1) % n;
            misses++;
        }
    }
    if (cross2(xy[ring[0]], xy[ring[1]], xy[ring[2]]) != 0)
        tri[3 * nt] = ring[0], tri[3 * nt + 1] = ring[1], tri[3 * nt + 2] = ring[2], nt++;
    return nt;
}

typedef struct PolyScratch {
    float (*xy)[2];
    uint32_t *ring;
    size_t cap;
} PolyScratch;

static bool plan_polygon(MeshPlan *pl, const SylPolygon *sp, PolyScratch *sc) {
    const SylSkeleton *s = pl->skel;
    if (sp->count < 3 || (size_t)sp->first + sp->count > s->nverts) return true;
    if (!mesh_reserve((void **)&pl->pv, &pl->pv_cap, pl->npv, sp->count, sizeof *pl->pv)) return false;
    uint32_t *kept = pl->pv + pl->npv, k = 0;
    for (uint32_t i = 0; i < sp->count; i++) {
        uint32_t vi = sp->first + i;
        const float *p = s->poly_verts[vi];
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) continue;
        if (k && !memcmp(s->poly_verts[kept[k - 1]], p, sizeof(float[3]))) continue;
        kept[k++] = vi;
    }
    while (k > 1 && !memcmp(s->poly_verts[kept[k - 1]], s->poly_verts[kept[0]], sizeof(float[3]))) k--;
    if (k < 3) return true;
    /* Newell's normal about the centroid */
    vec3 c = {0}, nn = {0};
    for (uint32_t i = 0; i < k; i++) glm_vec3_add(c, (float *)s->poly_verts[kept[i]], c);
    glm_vec3_scale(c, 1.0f / (float)k, c);
    for (uint32_t i = 0; i < k; i++) {
        vec3 a, b, x;
        glm_vec3_sub((float *)s->poly_verts[kept[i]], c, a);
        glm_vec3_sub((float *)s->poly_verts[kept[(i + 1) % k]], c, b);
        glm_vec3_cross(a, b, x);
        glm_vec3_add(nn, x, nn);
    }
    float len = glm_vec3_norm(nn), ext = 0;
    for (uint32_t i = 0; i < k; i++) ext = fmaxf(ext, glm_vec3_distance(c, (float *)s->poly_verts[kept[i]]));
    if (!(len > 1e-10f * ext * ext) || !isfinite(len)) return true; /* no area */
    MeshPoly mp = {.first = (uint32_t)pl->npv, .count = k};
    glm_vec3_scale(nn, 1.0f / len, mp.n);
    vec3 a = {1, 0, 0};
    if (fabsf(mp.n[0]) > 0.9f) a[0] = 0, a[1] = 1;
    glm_vec3_cross(a, mp.n, mp.e1);
    glm_vec3_normalize(mp.e1);
    glm_vec3_cross(mp.n, mp.e1, mp.e2);
    if (k > sc->cap) {
        void *x = realloc(sc->xy, k * sizeof *sc->xy), *r = x ? realloc(sc->ring, k * sizeof *sc->ring) : NULL;
        if (x) sc->xy = x;
        if (r) sc->ring = r;
        if (!x || !r) return false;
        sc->cap = k;
    }
    float lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (uint32_t i = 0; i < k; i++) {
        vec3 d;
        glm_vec3_sub((float *)s->poly_verts[kept[i]], c, d);
        sc->xy[i][0] = glm_vec3_dot(d, mp.e1);
        sc->xy[i][1] = glm_vec3_dot(d, mp.e2);
        for (int q = 0; q < 2; q++) lo[q] = fminf(lo[q], sc->xy[i][q]), hi[q] = fmaxf(hi[q], sc->xy[i][q]);
    }
    float span = fmaxf(hi[0] - lo[0], hi[1] - lo[1]);
    mp.uvscale = span > 0 ? 1.0f / span : 1.0f;
    mp.uv0[0] = lo[0], mp.uv0[1] = lo[1];
    /* the plane offset of the centroid is folded into uv0 */
    float co1 = glm_vec3_dot(c, mp.e1), co2 = glm_vec3_dot(c, mp.e2);
    mp.uv0[0] += co1, mp.uv0[1] += co2;
    if (!mesh_reserve((void **)&pl->ptri, &pl->ptri_cap, pl->nptri, 3 * (size_t)(k - 2), sizeof *pl->ptri))
        return false;
    mp.tri = (uint32_t)(pl->nptri / 3);
    mp.ntris = triangulate((const float(*)[2])sc->xy, k, pl->ptri + pl->nptri, sc->ring);
    if (!mp.ntris) return true;
    pl->nptri += 3 * (size_t)mp.ntris;
    pl->npv += k;
    if (!mesh_reserve((void **)&pl->polys, &pl->polys_cap, pl->npolys, 1, sizeof *pl->polys) ||
        !mesh_reserve((void **)&pl->items, &pl->items_cap, pl->nitems, 1, sizeof *pl->items) ||
        !mesh_add_run(pl, sp->material, 2 * mp.ntris))
        return false;
    pl->items[pl->nitems++] = (MeshItem){.vert = pl->nverts, .index = (uint32_t)pl->npolys,
                                         .run = (uint32_t)pl->nruns - 1, .verts = 2 * k, .node = sp->node,
                                         .poly = true};
    pl->polys[pl->npolys++] = mp;
    pl->nverts += 2 * (size_t)k;
    return true;
}

bool mesh_plan_shapes(MeshPlan *pl) {
    const SylSkeleton *s = pl->skel;
    for (int m = 0; m < 256; m++) /* each material's own leaf outline, once */
        if (mesh_own_leaf(&s->materials[m])) {
            if (!(pl->panels[m] = malloc(LEAF_OUTLINE_MAX_PANELS * sizeof *pl->panels[m]))) return false;
            pl->npanels[m] = (uint8_t)leaf_outline_panels(s->materials[m].leaf_outline, s->materials[m].leaf_tris, pl->panels[m]);
        }
    /* room for every organ at once: no doubling series through fresh pages */
    if (!mesh_reserve((void **)&pl->items, &pl->items_cap, pl->nitems, s->norgans, sizeof *pl->items) ||
        !mesh_reserve((void **)&pl->runs, &pl->runs_cap, pl->nruns, s->norgans, sizeof *pl->runs))
        return false;
    for (size_t i = 0; i < s->norgans; i++) {
        uint32_t nv, nt;
        organ_counts(pl, &s->organs[i], &nv, &nt);
        if (!nt) continue;
        if ((s->organs[i].kind == SYL_KIND_SPHERE || s->organs[i].kind == SYL_KIND_DISC) &&
            !mesh_trig(pl, pl->sides))
            return false;
        if (!mesh_reserve((void **)&pl->items, &pl->items_cap, pl->nitems, 1, sizeof *pl->items) ||
            !mesh_add_run(pl, s->organs[i].material, nt))
            return false;
        pl->items[pl->nitems++] = (MeshItem){.vert = pl->nverts, .index = (uint32_t)i,
                                             .run = (uint32_t)pl->nruns - 1, .verts = nv,
                                             .node = s->organs[i].node};
        pl->nverts += nv;
    }
    if (pl->leaves == SYL_LEAVES_CLUSTERS && !mesh_plan_clusters(pl, pl->cluster_leaves)) return false;
    PolyScratch sc = {0};
    bool ok = true;
    for (size_t i = 0; i < s->npolys && ok; i++) ok = plan_polygon(pl, &s->polys[i], &sc);
    free(sc.xy);
    free(sc.ring);
    return ok;
}

/* ------------------------------------------------------------------ emission */

typedef struct Out {
    float *pos, *nrm, *uv;
    uint32_t *ix;
    uint32_t v0, nv; /* first vertex of the item, vertices written so far */
} Out;

static uint32_t put(Out *o, const float *p, const float *n, float u, float v) {
    memcpy(o->pos + 3 * o->nv, p, 3 * sizeof(float));
    memcpy(o->nrm + 3 * o->nv, n, 3 * sizeof(float));
    o->uv[2 * o->nv] = u;
    o->uv[2 * o->nv + 1] = v;
    return o->v0 + o->nv++;
}

static void tri(Out *o, uint32_t a, uint32_t b, uint32_t c) {
    *o->ix++ = a, *o->ix++ = b, *o->ix++ = c;
}

/* A double-sided blade from origin along x (length len) and y (half width w); one-sided: its
 * front only. */
static void blade(Out *o, const float *origin, const vec3 x, const vec3 y, float len, float w, bool one) {
    vec3 n, nb;
    glm_vec3_cross((float *)x, (float *)y, n);
    glm_vec3_normalize(n);
    glm_vec3_negate_to(n, nb);
    uint32_t f[8], b[8];
    float p[8][3];
    for (int i = 0; i < 8; i++)
        for (int q = 0; q < 3; q++) p[i][q] = origin[q] + blade_xy[i][0] * len * x[q] + blade_xy[i][1] * w * y[q];
    for (int i = 0; i < 8; i++) f[i] = put(o, p[i], n, 0.5f + 0.5f * blade_xy[i][1], blade_xy[i][0]);
    for (int t = 0; t < 8; t++) tri(o, f[blade_tri[t][0]], f[blade_tri[t][1]], f[blade_tri[t][2]]);
    if (one) return;
    for (int i = 0; i < 8; i++) b[i] = put(o, p[i], nb, 0.5f + 0.5f * blade_xy[i][1], blade_xy[i][0]);
    for (int t = 0; t < 8; t++) tri(o, b[blade_tri[t][0]], b[blade_tri[t][2]], b[blade_tri[t][1]]);
}

/* A double-sided (one: front only) panel of a named leaf outline (a fan over its points, util/leafoutline.h),
 * len long along x and w wide across: in the plane of x and cos(fold) y + sin(fold) z. */
static void panel(Out *o, const LeafPanel *pn, const float *origin, const vec3 x, const vec3 y, const vec3 z,
                  float len, float w, bool one) {
    vec3 e, nf, nb;
    if (pn->fold == 0) glm_vec3_copy((float *)y, e);
    else for (int q = 0; q < 3; q++) e[q] = cosf(pn->fold) * y[q] + sinf(pn->fold) * z[q];
    glm_vec3_cross((float *)x, e, nf);
    glm_vec3_normalize(nf);
    glm_vec3_negate_to(nf, nb);
    uint32_t f[LEAF_OUTLINE_MAX_POINTS], b[LEAF_OUTLINE_MAX_POINTS];
    for (int i = 0; i < pn->n; i++) {
        float u = pn->st[i][0], v = 0.5f * pn->st[i][1], p[3]; /* along, 0..1; across, -1/2..1/2 */
        for (int q = 0; q < 3; q++) p[q] = origin[q] + u * len * x[q] + v * w * e[q];
        f[i] = put(o, p, nf, 0.5f + v, u);
        if (!one) b[i] = put(o, p, nb, 0.5f + v, u);
    }
    for (int i = 1; i + 1 < pn->n; i++) {
        tri(o, f[0], f[i], f[i + 1]);
        if (!one) tri(o, b[0], b[i + 1], b[i]);
    }
}

/* A card over the leaf's rectangle, one face: its material is double-sided (two faces would
 * fight for the same depth), and the texture's alpha draws the leaf. upright: a leaf of its
 * own image, drawn as people draw leaves, tip up (row 0 at the tip); back: its other face
 * too, for formats without double-sided materials. */
static void card(Out *o, const float *origin, const vec3 x, const vec3 y, float len, float w, bool upright, bool back) {
    vec3 nf, nb;
    glm_vec3_cross((float *)x, (float *)y, nf);
    glm_vec3_normalize(nf);
    glm_vec3_negate_to(nf, nb);
    static const float corner[4][2] = {{0, -1}, {1, -1}, {1, 1}, {0, 1}}; /* along, across */
    uint32_t f[4], b[4];
    for (int i = 0; i < 4; i++) {
        float p[3];
        for (int q = 0; q < 3; q++) p[q] = origin[q] + corner[i][0] * len * x[q] + corner[i][1] * w * y[q];
        float v = upright ? 1 - corner[i][0] : corner[i][0];
        f[i] = put(o, p, nf, 0.5f + 0.5f * corner[i][1], v);
        if (back) b[i] = put(o, p, nb, 0.5f + 0.5f * corner[i][1], v);
    }
    tri(o, f[0], f[1], f[2]), tri(o, f[0], f[2], f[3]);
    if (back) tri(o, b[0], b[2], b[1]), tri(o, b[0], b[3], b[2]);
}

static void emit_organ(const MeshPlan *pl, const SylOrgan *og, Out *o) {
    vec3 h, l, u;
    mesh_organ_frame(og, h, l, u);
    const float *c = og->pos, size = og->size;
    switch (og->kind) {
    case SYL_KIND_LEAF:
        if (image_leaf(pl, og->material) > 0) card(o, c, h, l, size, image_leaf(pl, og->material) * size, true, !pl->one_sided);
        else if (pl->leaves == SYL_LEAVES_CARDS) card(o, c, h, l, size, mesh_leaf_width(&pl->skel->materials[og->material]) * size, false, false);
        else if (pl->npanels[og->material])
            for (int k = 0; k < pl->npanels[og->material]; k++)
                panel(o, &pl->panels[og->material][k], c, h, l, u, size, pl->skel->materials[og->material].leaf_width * size,
                      pl->one_sided);
        else blade(o, c, h, l, size, LEAF_WIDTH * size, pl->one_sided);
        break;
    case SYL_KIND_FLOWER:
        if (image_leaf(pl, og->material) > 0) {
            card(o, c, h, l, size, image_leaf(pl, og->material) * size, true, !pl->one_sided);
            break;
        }
        for (int k = 0; k < PETALS; k++) {
            float a = 6.28318530718f * (float)k / PETALS, ca = cosf(a), sa = sinf(a);
            vec3 radial, across, x;
            for (int q = 0; q < 3; q++) {
                radial[q] = ca * l[q] + sa * u[q];
                across[q] = -sa * l[q] + ca * u[q];
                x[q] = cosf(PETAL_TILT) * radial[q] + sinf(PETAL_TILT) * h[q];
            }
            float len = PETAL_LENGTH * size;
            blade(o, c, x, across, len, PETAL_WIDTH * len, pl->one_sided);
        }
        break;
    case SYL_KIND_NEEDLE: {
        float r = NEEDLE_WIDTH * size, tip[3], p[3][3], nb[3];
        uint32_t base[3], cap[3];
        for (int j = 0; j < 3; j++) {
            float a = 6.28318530718f * (float)j / 3, w[3];
            for (int q = 0; q < 3; q++) {
                w[q] = cosf(a) * l[q] + sinf(a) * u[q];
                p[j][q] = c[q] + r * w[q];
            }
            base[j] = put(o, p[j], w, (float)j / 3, 0);
        }
        for (int q = 0; q < 3; q++) tip[q] = c[q] + size * h[q], nb[q] = -h[q];
        uint32_t t = put(o, tip, h, 0.5f, 1);
        for (int j = 0; j < 3; j++) cap[j] = put(o, p[j], nb, (float)j / 3, 0);
        for (int j = 0; j < 3; j++) tri(o, base[j], base[(j + 1) % 3], t);
        tri(o, cap[0], cap[2], cap[1]);
        break;
    }
    case SYL_KIND_SPHERE: {
        const int st = pl->sphere_stacks, sl = pl->sides;
        const MeshTrig *tr = pl->trig[sl];
        const float rad = 0.5f * size;
        for (int i = 0; i <= st; i++) {
            float phi = 3.14159265359f * (float)i / (float)st, cp = -cosf(phi), sp = sinf(phi);
            if (i == 0 || i == st) sp = 0;
            for (int j = 0; j <= sl; j++) {
                float n[3], p[3];
                for (int q = 0; q < 3; q++) {
                    n[q] = cp * h[q] + sp * (tr->c[j] * l[q] + tr->s[j] * u[q]);
                    p[q] = c[q] + rad * n[q];
                }
                glm_vec3_normalize(n);
                put(o, p, n, (float)j / (float)sl, (float)i / (float)st);
            }
        }
        for (int i = 0; i < st; i++) {
            uint32_t a = o->v0 + (uint32_t)(i * (sl + 1)), b = a + (uint32_t)(sl + 1);
            for (uint32_t j = 0; j < (uint32_t)sl; j++) {
                if (i > 0) tri(o, a + j, a + j + 1, b + j);
                if (i + 1 < st) tri(o, a + j + 1, b + j + 1, b + j);
            }
        }
        break;
    }
    case SYL_KIND_DISC: { /* per side: the centre, then the rim */
        const int sl = pl->sides;
        const MeshTrig *tr = pl->trig[sl];
        const float rad = 0.5f * size;
        for (int side = 0; side < 2; side++) {
            float n[3];
            for (int q = 0; q < 3; q++) n[q] = side ? -u[q] : u[q];
            uint32_t centre = put(o, c, n, 0.5f, 0.5f);
            for (int j = 0; j < sl; j++) {
                float p[3];
                for (int q = 0; q < 3; q++) p[q] = c[q] + rad * (tr->c[j] * h[q] + tr->s[j] * l[q]);
                put(o, p, n, 0.5f + 0.5f * tr->c[j], 0.5f + 0.5f * tr->s[j]);
            }
            for (uint32_t j = 0; j < (uint32_t)sl; j++) {
                uint32_t a = centre + 1 + j, b = centre + 1 + (j + 1) % (uint32_t)sl;
                if (side) tri(o, centre, b, a);
                else tri(o, centre, a, b);
            }
        }
        break;
    }
    default: break;
    }
}

static void emit_polygon(const MeshPlan *pl, const MeshPoly *mp, Out *o) {
    const SylSkeleton *s = pl->skel;
    float nb[3] = {-mp->n[0], -mp->n[1], -mp->n[2]};
    for (int side = 0; side < 2; side++)
        for (uint32_t i = 0; i < mp->count; i++) {
            const float *p = s->poly_verts[pl->pv[mp->first + i]];
            float u = (glm_vec3_dot((float *)p, (float *)mp->e1) - mp->uv0[0]) * mp->uvscale;
            float v = (glm_vec3_dot((float *)p, (float *)mp->e2) - mp->uv0[1]) * mp->uvscale;
            put(o, p, side ? nb : mp->n, u, v);
        }
    const uint32_t *t = pl->ptri + 3 * (size_t)mp->tri, k = mp->count;
    for (uint32_t i = 0; i < mp->ntris; i++) tri(o, o->v0 + t[3 * i], o->v0 + t[3 * i + 1], o->v0 + t[3 * i + 2]);
    for (uint32_t i = 0; i < mp->ntris; i++)
        tri(o, o->v0 + k + t[3 * i], o->v0 + k + t[3 * i + 2], o->v0 + k + t[3 * i + 1]);
}

void mesh_emit_item(const MeshPlan *pl, const MeshItem *it, SylMesh *m) {
    Out o = {m->pos + 3 * it->vert, m->nrm + 3 * it->vert, m->uv + 2 * it->vert, m->idx + pl->runs[it->run].idx,
             (uint32_t)it->vert, 0};
    if (it->cluster) mesh_emit_cluster(&pl->clusters[it->index], o.pos, o.nrm, o.uv, o.ix, o.v0);
    else if (it->poly) emit_polygon(pl, &pl->polys[it->index], &o);
    else emit_organ(pl, &pl->skel->organs[it->index], &o);
}

float mesh_organ_side_area(const MeshPlan *pl, const SylOrgan *o) {
    float size = o->size;
    if (o->kind == SYL_KIND_NEEDLE) {
        float r = NEEDLE_WIDTH * size, edge = r * sqrtf(3.0f);
        float sides = 3 * 0.5f * edge * sqrtf(size * size + 0.25f * r * r), cap = 0.25f * sqrtf(3.0f) * edge * edge;
        return 0.5f * (sides + cap);
    }
    const SylMaterial *m = &pl->skel->materials[o->material];
    if (image_leaf(pl, o->material) > 0) return 2 * image_leaf(pl, o->material) * size * size;
    if (pl->npanels[o->material]) return (float)leaf_outline_area(m->leaf_outline, m->leaf_tris) * size * m->leaf_width * size;
    float a = 0;
    for (int t = 0; t < 8; t++) {
        const float(*p[3]) = {blade_xy[blade_tri[t][0]], blade_xy[blade_tri[t][1]], blade_xy[blade_tri[t][2]]};
        a += 0.5f * fabsf((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]));
    }
    return a * size * LEAF_WIDTH * size;
}
