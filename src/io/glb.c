/* The one glTF 2.0 binary writer (.glb): any set of top-level nodes (one plant; a chain of
 * levels of detail NAME_LOD0 .. with MSFT_lod on the first), each with its mesh and its
 * instance sets (child nodes with EXT_mesh_gpu_instancing), in any leaf mode.
 *
 * Each mesh has one primitive per material group; POSITION, NORMAL and TEXCOORD_0 are shared
 * by its primitives, each with its own range of 16-bit indices. Above 65,535 vertices a group
 * is several primitives, each with its own window of the attributes (glb_prims.c). Materials are metallic-roughness with the material's colour (converted to linear, as
 * glTF wants) and, for bark, leaf and flower kinds, the procedural texture; leaf cards and an
 * impostor's billboards are alpha-tested (PNGs embedded in the BIN chunk). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/lazy_meshopt.h"

#include "io/glb.h"
#include "sylva/lod.h"
#include "sylva/stream.h"
#include "sylva/texture.h"
#include "texture/texture.h"

enum { KINDS = GLB_SLOTS, CARD = GLB_CARD, ATLAS = GLB_ATLAS, CLUSTER = GLB_CLUSTER }; /* texture slots (glb.h) */
/* then one slot per image of the model's own (SylMaterial.image), its PNG embedded as read */
enum { IMAGE0 = KINDS, SLOTS = KINDS + SYL_IMAGES_MAX };
/* and the cards' further shapes (a scene's plants each draw their own outline): textures after
 * all the slots', so a file with one card shape is as before */
enum { SHAPES = 256, TEXTURES = SLOTS + SHAPES };

/* A mesh written: the part it belongs to and which of its sets (-1: the part's own). */
typedef struct MeshRef {
    const SylMesh *m;
    int part, set;
    int view, accessor, material; /* its first buffer view, accessor and material */
    GlbPrims pr;                  /* its primitives (glb_prims.c) */
    const SylMesh *proto;         /* a set's: the prototype, m its copy scaled by fold when fold > 0 */
    float fold;                   /* the one size of its sets' instances, over their part's scale
                                     when quantized: m is proto scaled by it (0: sizes differ) */
    bool skinned;                 /* its part's wind: five more vertex accessors */
    float uvq[4];                 /* quantized UVs: offset and scale of KHR_texture_transform (scale 0: floats) */
    bool strips;                  /* quantized: each primitive a triangle strip (pr's first, count: the strip's) */
} MeshRef;

/* What goes in the file, numbered before the JSON refers to it. */
typedef struct Layout {
    const GlbScene *sc;
    IoBuf bin;
    View *views;
    int nviews;
    MeshRef *mesh;
    int nmeshes;
    int *set_view, *set_accessor, *part_mesh, *part_node, *set_node; /* -1: none */
    int nsets, nnodes;
    int tex_of_kind[SLOTS], ntex, image_view[TEXTURES], image_kind[TEXTURES];
    int card_tex[SHAPES], card_shape; /* the texture of cards of each shape (-1: none); the shape
                                         of the cards that draw their mesh's leaf_shape */
    const SylImages *images;      /* the first mesh's images (the others share them: levels, parts) */
    bool image_leaf[SYL_IMAGES_MAX]; /* an image some leaf wears: clamped, not repeated */
    float (*quant)[4];            /* each part's dequantization: translation, scale (0: none) */
    const SylWind *wind;          /* the parts' one skin, when they are skinned */
    int anim_view, anim_accessor, joint_node; /* its first view, accessor and joint node */
    /* Instanced leaves of skinned parts follow a joint each: set i's joint (-1: a child of its
     * part), and per part its copy of the joints that carry them (-1: none; one plant's sets
     * hang from the joints themselves) */
    const int *set_joint;
    int *set_mesh, *anchor_node;
} Layout;

static const int kinds[] = {SYL_MATERIAL_BARK, SYL_MATERIAL_LEAF, SYL_MATERIAL_FLOWER};

static bool has_geometry(const SylMesh *m) { return m && m->nverts > 0 && m->nidx > 0 && m->ngroups > 0; }
/* Shared attributes then one index accessor a primitive; split, each primitive its own
 * attributes and indices (and skin attributes). */
static int skin_accessors(const MeshRef *r) { return r->skinned ? 5 : 0; }
static int accessors_of(const MeshRef *r) {
    return r->pr.split ? (int)r->pr.n * (4 + skin_accessors(r)) : 3 + (int)r->pr.n + skin_accessors(r);
}

/* KHR_mesh_quantization: x of a box centred on t of half-size k, as a normalized short. */
static int16_t q16(float x, float t, float k) {
    float v = (x - t) / k;
    v = v < -1 ? -1 : v > 1 ? 1 : v;
    return (int16_t)lrintf(v * 32767);
}
static int8_t q8(float x) { return (int8_t)lrintf((x < -1 ? -1 : x > 1 ? 1 : x) * 127); }
static inline void le16(uint8_t *p, uint16_t v) { /* little-endian, as glTF's buffers */
    p[0] = (uint8_t)(v & 0xff), p[1] = (uint8_t)(v >> 8);
}
/* n 16-bit values appended, written in place (no call per value); NULL when out of memory */
static uint8_t *room16(IoBuf *b, size_t n) { return io_room(b, 2 * n); }

/* n vectors of k floats as normalized shorts (t, s: the box), with pad: each padded to 4
 * bytes (a vertex attribute's elements must be aligned so; instance attributes need not). */
static void put_q16(IoBuf *b, const float *x, size_t n, int k, const float *t, float s, bool pad) {
    size_t per = (size_t)k + (k == 3 && pad);
    uint8_t *o = room16(b, per * n);
    for (size_t i = 0; o && i < n; i++) {
        for (int c = 0; c < k; c++, o += 2) le16(o, (uint16_t)q16(x[(size_t)k * i + (size_t)c], t ? t[c] : 0, s));
        if (per > (size_t)k) le16(o, 0), o += 2;
    }
    glb_pad(b, 0);
}

/* ,"min":[..],"max":[..] of put_q16's values (the integers, as glTF wants). */
static void min_max_q16(IoBuf *j, const float *x, size_t n, const float *t, float s) {
    int lo[3] = {32767, 32767, 32767}, hi[3] = {-32767, -32767, -32767};
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            int v = q16(x[3 * i + (size_t)c], t[c], s);
            if (v < lo[c]) lo[c] = v;
            if (v > hi[c]) hi[c] = v;
        }
    for (int w = 0; w < 2; w++) {
        io_printf(j, ",\"%s\":[", w ? "max" : "min");
        for (int c = 0; c < 3; c++) io_printf(j, "%s%d", c ? "," : "", w ? hi[c] : lo[c]);
        io_put(j, "]", 1);
    }
}
static bool cards(const SylMesh *m) { return m->leaves == SYL_LEAVES_CARDS || m->leaves == SYL_LEAVES_INSTANCED_CARDS; }

int glb_slot(const SylMesh *m, int i) {
    int kind = m->materials[i].kind;
    if (kind == SYL_MATERIAL_LEAF && cards(m)) return CARD;
    if (kind == SYL_MATERIAL_LEAF && m->leaves == SYL_LEAVES_CLUSTERS) return CLUSTER;
    for (int k = 0; k < 3; k++)
        if (kind == kinds[k]) return k;
    return -1;
}

/* The texture slot material i of mesh r uses (-1: none). */
static int slot_of(const Layout *l, const MeshRef *r, int i) {
    const GlbScene *sc = l->sc;
    if (sc->atlas && r->part == sc->nparts - 1 && r->set < 0 && i == sc->atlas_material) return ATLAS;
    if (r->m->images == l->images && io_image(r->m, i)) return IMAGE0 + r->m->materials[i].image - 1;
    return glb_slot(r->m, i);
}

void glb_pixels_free(GlbPixels *px) {
    free(px->img), free(px->leaf);
    *px = (GlbPixels){0};
}

/* The leaf pattern, syl_texture_draw's bytes as the leaf's slot, syl_leaf_draw_card and
 * syl_leaf_draw_cluster make them; NULL when out of memory. */
static const uint8_t *leaf_pattern(GlbPixels *px) {
    enum { N = SYL_TEXTURE_SIZE };
    if (!px->leaf) {
        uint8_t *rgb = malloc((size_t)N * N * 3);
        if (!rgb || !syl_texture_draw(SYL_MATERIAL_LEAF, NULL, N, rgb)) return free(rgb), NULL;
        px->leaf = rgb;
    }
    return px->leaf;
}

bool glb_slot_png(IoBuf *b, int k, int shape, GlbPixels *px) {
    enum { N = SYL_TEXTURE_SIZE };
    if (!px->img && !(px->img = malloc((size_t)N * N * 4))) return false;
    uint8_t *img = px->img;
    const uint8_t *leaf = k == CARD || k == CLUSTER || (k < 3 && kinds[k] == SYL_MATERIAL_LEAF) ? leaf_pattern(px) : NULL;
    return k == CARD      ? leaf && (leaf_card_of(leaf, shape, N, img), io_png_rgba(b, img, N, N))
           : k == CLUSTER ? leaf && leaf_cluster_of(leaf, shape, N, img) && io_png_rgba(b, img, N, N)
           : leaf         ? io_png(b, leaf, N)
           : k < 3        ? syl_texture_draw(kinds[k], NULL, N, img) && io_png(b, img, N)
                          : false;
}

const char *glb_slot_name(int k) {
    return k == CARD ? "leafcard" : k == ATLAS ? "impostor" : k == CLUSTER ? "leafcluster" : syl_texture_name(kinds[k]);
}

/* A quantized mesh's UVs as normalized unsigned shorts over their box, which
 * KHR_texture_transform's offset and scale give back (KHR_mesh_quantization's way): when a
 * step of that is at most one texel of a texture tile (an error of half a texel at most);
 * floats otherwise (uvq[2] = 0). */
static void plan_uvs(const SylMesh *m, float uvq[4]) {
    float lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t i = 0; i < m->nverts; i++)
        for (int c = 0; c < 2; c++) lo[c] = fminf(lo[c], m->uv[2 * i + c]), hi[c] = fmaxf(hi[c], m->uv[2 * i + c]);
    uvq[2] = uvq[3] = 0;
    for (int c = 0; c < 2; c++)
        if (!isfinite(lo[c]) || !isfinite(hi[c]) || (hi[c] - lo[c]) * SYL_TEXTURE_SIZE > 65535) return;
    for (int c = 0; c < 2; c++) uvq[c] = lo[c], uvq[2 + c] = hi[c] > lo[c] ? hi[c] - lo[c] : 1;
}
static void put_uv16(IoBuf *b, const float *uv, size_t n, const float uvq[4]) {
    uint8_t *o = room16(b, 2 * n);
    for (size_t i = 0; o && i < n; i++)
        for (int c = 0; c < 2; c++, o += 2) {
            float x = (uv[2 * i + c] - uvq[c]) / uvq[2 + c];
            le16(o, (uint16_t)lrintf((x < 0 ? 0 : x > 1 ? 1 : x) * 65535));
        }
}

/* A quantized mesh's primitives as triangle strips, the same triangles in the same order
 * and winding joined by triangles without area (meshoptimizer's stripify; every reader
 * drops those): about 0.6 of a list's indices on tubes, whose bands are strips already.
 * Each primitive's first and count become its strip's; the view is set by the caller's. */
static void layout_strips(Layout *l, MeshRef *r) {
    const SylMesh *m = r->m;
    size_t at = 0, most = 0;
    for (size_t k = 0; k < r->pr.n; k++) most = r->pr.prim[k].count > most ? r->pr.prim[k].count : most;
    unsigned *src = malloc((most + 1) * sizeof *src), *dst = malloc((meshopt_stripifyBound(most) + 1) * sizeof *dst);
    if (!src || !dst) {
        l->bin.failed = true;
        free(src), free(dst);
        return;
    }
    for (size_t k = 0; k < r->pr.n; k++) {
        GlbPrim *pr = &r->pr.prim[k];
        for (uint32_t i = 0; i < pr->count; i++) src[i] = m->idx[pr->first + i] - (uint32_t)pr->lo;
        size_t n = meshopt_stripify(dst, src, pr->count, pr->nv, 0);
        uint8_t *o = room16(&l->bin, n);
        for (size_t i = 0; o && i < n; i++) le16(o + 2 * i, (uint16_t)dst[i]);
        pr->first = (uint32_t)at, pr->count = (uint32_t)n;
        at += n;
    }
    free(src), free(dst);
}

/* At least the bytes layout_attributes copies into the buffer for r (floats: arrays too small
 * to go by reference; strips: at most 5/3 of the indices; skin: joints and weights): reserved
 * at once, so that the buffer is not grown by doubling and copying. */
static size_t attribute_bytes(const MeshRef *r) {
    size_t nv = r->m->nverts, ni = r->m->nidx;
    return 32 * nv + 4 * ni + (r->skinned ? 12 * nv : 0) + 16 * r->pr.n + 64;
}

/* POSITION, NORMAL and TEXCOORD_0, then the indices, the smallest type that holds them. */
static void layout_attributes(Layout *l, MeshRef *r) {
    const SylMesh *m = r->m;
    const size_t nv = m->nverts;
    const float *q = r->set < 0 ? l->quant[r->part] : NULL;
    const bool split = r->pr.split; /* accessors of several windows share each view: strided */
    r->view = l->nviews;
    if (q && q[3] > 0) { /* 16-bit positions and 8-bit normals, each padded to 4 bytes */
        l->views[l->nviews++] = (View){l->bin.len, 8 * nv, ARRAY_BUFFER, 8};
        put_q16(&l->bin, m->pos, nv, 3, q, q[3], true);
        l->views[l->nviews++] = (View){l->bin.len, 4 * nv, ARRAY_BUFFER, 4};
        uint8_t *o = io_room(&l->bin, 4 * nv);
        for (size_t i = 0; o && i < nv; i++, o += 4)
            o[0] = (uint8_t)q8(m->nrm[3 * i]), o[1] = (uint8_t)q8(m->nrm[3 * i + 1]), o[2] = (uint8_t)q8(m->nrm[3 * i + 2]), o[3] = 0;
    } else {
        l->views[l->nviews++] = (View){l->bin.len, 12 * nv, ARRAY_BUFFER, split ? 12 : 0};
        glb_words(&l->bin, m->pos, 3 * nv);
        l->views[l->nviews++] = (View){l->bin.len, 12 * nv, ARRAY_BUFFER, split ? 12 : 0};
        glb_words(&l->bin, m->nrm, 3 * nv);
    }
    const bool atlas = l->sc->atlas && r->part == l->sc->nparts - 1; /* its texture may be finer than a tile */
    if (q && q[3] > 0 && !atlas) plan_uvs(m, r->uvq);
    if (r->uvq[2] > 0) {
        l->views[l->nviews++] = (View){l->bin.len, 4 * nv, ARRAY_BUFFER, split ? 4 : 0};
        put_uv16(&l->bin, m->uv, nv, r->uvq);
    } else {
        l->views[l->nviews++] = (View){l->bin.len, 8 * nv, ARRAY_BUFFER, split ? 8 : 0};
        glb_words(&l->bin, m->uv, 2 * nv);
    }
    /* 16-bit indices, less each primitive's first vertex; 32-bit only when a triangle spans
     * more than 65,535 vertices (glb_prims.c) */
    const bool wide = r->pr.wide;
    const size_t at = l->bin.len;
    View *iv = &l->views[l->nviews++];
    *iv = (View){at, (wide ? 4 : 2) * m->nidx, ELEMENT_ARRAY_BUFFER, 0};
    if (wide) {
        glb_words(&l->bin, m->idx, m->nidx);
    } else if (q && q[3] > 0 && !r->skinned) {
        r->strips = true;
        layout_strips(l, r);
        iv->length = l->bin.len - at;
        glb_pad(&l->bin, 0);
    } else {
        for (size_t k = 0; k < r->pr.n; k++) {
            const GlbPrim *pr = &r->pr.prim[k];
            uint8_t *o = room16(&l->bin, pr->count);
            for (size_t i = 0; o && i < pr->count; i++) le16(o + 2 * i, (uint16_t)(m->idx[pr->first + i] - (uint32_t)pr->lo));
        }
        glb_pad(&l->bin, 0);
    }
    if (r->skinned) glb_skin_vertices(&l->sc->part[r->part], &l->bin, l->views, &l->nviews, split);
}

/* Each set's translations, rotations and scales: three views. Quantized: translations in
 * the part's box, rotations, and scales over the part's scale (which the node's transform
 * applies again: a leaf is far smaller than its plant), all as normalized shorts. */
static void layout_instances(Layout *l, const SylInstances *set, int i, const float *q) {
    size_t n = set->count;
    bool scale = !(l->mesh[l->set_mesh[i]].fold > 0); /* else in the prototype */
    l->set_view[i] = l->nviews;
    if (q[3] > 0) {
        l->views[l->nviews++] = (View){l->bin.len, 6 * n, 0, 0}; /* VEC3s packed */
        put_q16(&l->bin, set->t, n, 3, q, q[3], false);
        l->views[l->nviews++] = (View){l->bin.len, 8 * n, 0, 0};
        put_q16(&l->bin, set->r, n, 4, NULL, 1, false);
        if (scale) l->views[l->nviews++] = (View){l->bin.len, 6 * n, 0, 0};
        if (scale) put_q16(&l->bin, set->s, n, 3, NULL, q[3], false);
        return;
    }
    l->views[l->nviews++] = (View){l->bin.len, 12 * n, 0, 0};
    glb_words(&l->bin, set->t, 3 * n);
    l->views[l->nviews++] = (View){l->bin.len, 16 * n, 0, 0};
    glb_words(&l->bin, set->r, 4 * n);
    if (scale) l->views[l->nviews++] = (View){l->bin.len, 12 * n, 0, 0};
    if (scale) glb_words(&l->bin, set->s, 3 * n);
}

/* Set i's accessors: TRANSLATION, ROTATION and SCALE, unless its prototype has the scale. */
/* The image whose PNG was written from `at` to the binary's end: its view, padded; its texture's number. */
static int add_image(Layout *l, size_t at, int kind) {
    l->image_view[l->ntex] = l->nviews;
    l->image_kind[l->ntex] = kind;
    l->views[l->nviews++] = (View){at, l->bin.len - at, 0, 0};
    glb_pad(&l->bin, 0);
    return l->ntex++;
}

static int set_accessors(const Layout *l, int i) { return l->mesh[l->set_mesh[i]].fold > 0 ? 2 : 3; }

/* One PNG texture per slot used, each in a view of its own. */
static void layout_textures(Layout *l) {
    bool used[SLOTS] = {false};
    /* the cards' shapes: first the one of those that draw their mesh's leaf_shape (the levels
     * of detail share the last level's), then the others in order of first use */
    int cluster_shape = 0, card[SHAPES] = {0}, ncards = 1;
    for (int k = 0; k < l->nmeshes && !l->images; k++) l->images = l->mesh[k].m->images;
    for (int k = 0; k < l->nmeshes; k++)
        for (int g = 0; g < l->mesh[k].m->ngroups; g++) {
            int i = l->mesh[k].m->groups[g].material, t = slot_of(l, &l->mesh[k], i);
            if (t >= 0) used[t] = true;
            if (t >= IMAGE0 && l->mesh[k].m->materials[i].kind != SYL_MATERIAL_BARK) l->image_leaf[t - IMAGE0] = true;
            if (t == CARD) card[0] = l->mesh[k].m->leaf_shape;
            if (t == CLUSTER) cluster_shape = l->mesh[k].m->leaf_shape;
        }
    for (int k = 0; k < l->nmeshes; k++)
        for (int g = 0; g < l->mesh[k].m->ngroups; g++) {
            const SylMesh *m = l->mesh[k].m;
            int i = m->groups[g].material, c = syl_mesh_card_shape(m, i), j = 0;
            if (slot_of(l, &l->mesh[k], i) != CARD || c == m->leaf_shape) continue;
            while (j < ncards && card[j] != c) j++;
            if (j == ncards) card[ncards++] = c;
        }
    GlbPixels px = {0};
    const GlbScene *sc = l->sc;
    l->card_shape = card[0];
    for (int k = 0, c = 1; k < SLOTS || (c < ncards && !l->bin.failed); k++) {
        if (k >= SLOTS) { /* a further card shape */
            size_t at = l->bin.len;
            if (!glb_slot_png_cached(sc->textures, &l->bin, CARD, card[c], &px)) {
                l->bin.failed = true;
                break;
            }
            l->card_tex[card[c++]] = add_image(l, at, CARD);
            continue;
        }
        if (!used[k]) continue;
        if (k >= IMAGE0) { /* the file's bytes as they are */
            const SylImage *g = &l->images->img[k - IMAGE0];
            l->image_view[l->ntex] = l->nviews;
            l->image_kind[l->ntex] = k;
            l->views[l->nviews++] = (View){l->bin.len, g->len, 0, 0};
            io_put(&l->bin, g->png, g->len);
            glb_pad(&l->bin, 0);
            l->tex_of_kind[k] = l->ntex++;
            continue;
        }
        size_t at = l->bin.len;
        bool ok = k == ATLAS ? io_png_rgba(&l->bin, sc->atlas, sc->atlas_w, sc->atlas_h)
                             : glb_slot_png_cached(sc->textures, &l->bin, k, k == CLUSTER ? cluster_shape : card[0], &px);
        if (!ok) {
            l->bin.failed = true;
            break;
        }
        int t = add_image(l, at, k);
        if (k == CARD) l->card_tex[card[0]] = t;
        l->tex_of_kind[k] = t;
    }
    glb_pixels_free(&px);
}

/* With levels of detail the joints are the scene's own roots, beside NAME_LOD0: every level
 * is skinned to them, whichever one is drawn. One plant's are children of its node. */
static bool joints_at_root(const Layout *l) { return l->wind && l->sc->nparts > 1; }

static const char *mesh_name(const Layout *l, const MeshRef *r) {
    return r->set < 0 ? l->sc->part[r->part].name : l->sc->part[r->part].sets[r->set].name;
}

/* Mesh k's primitives, one per group. */
static void json_mesh(IoBuf *js, const Layout *l, int k) {
    const MeshRef *r = &l->mesh[k];
    int a = r->accessor;
    io_printf(js, "%s{\"name\":", k ? "," : "");
    io_json_string(js, mesh_name(l, r));
    io_printf(js, ",\"primitives\":[");
    for (size_t c = 0; c < r->pr.n; c++) {
        int at = r->pr.split ? a + (int)c * (4 + skin_accessors(r)) : a; /* its attributes */
        int idx = r->pr.split ? at + 3 : a + 3 + (int)c;
        io_printf(js, "%s{\"attributes\":{\"POSITION\":%d,\"NORMAL\":%d,\"TEXCOORD_0\":%d", c ? "," : "", at, at + 1, at + 2);
        if (r->skinned) glb_skin_attributes(js, r->pr.split ? at + 4 : a + 3 + (int)r->pr.n);
        io_printf(js, "},\"indices\":%d,\"material\":%d,\"mode\":%d}", idx, r->material + r->pr.prim[c].group,
                  r->strips ? 5 : 4);
    }
    io_printf(js, "]}");
}

/* Materials: metallic-roughness, one per group of each mesh; leaf cards and the impostor's
 * billboards alpha-tested. */
static void json_materials(IoBuf *js, const Layout *l) {
    io_printf(js, ",\"materials\":[");
    for (int k = 0; k < l->nmeshes; k++) {
        const SylMesh *m = l->mesh[k].m;
        for (int g = 0; g < m->ngroups; g++) {
            int i = m->groups[g].material, slot = slot_of(l, &l->mesh[k], i);
            int c = syl_mesh_card_shape(m, i);
            int t = slot == CARD ? l->card_tex[c == m->leaf_shape ? l->card_shape : c] : slot >= 0 ? l->tex_of_kind[slot] : -1;
            if (slot == ATLAS) {
                io_printf(js, "%s{\"name\":\"impostor\",\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":%d},"
                              "\"metallicFactor\":0,\"roughnessFactor\":0.9},\"alphaMode\":\"MASK\",\"alphaCutoff\":0.5}",
                          k || g ? "," : "", t);
                continue;
            }
            const SylMaterial *mat = &m->materials[i];
            char mname[32];
            io_material_name(m, i, mname, sizeof mname);
            /* an image of the model's own is the colour itself: a white factor */
            const float white[3] = {1, 1, 1}, *rgb = slot >= IMAGE0 ? white : mat->rgb;
            io_printf(js, "%s{\"name\":\"%s\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[%.6f,%.6f,%.6f,1]",
                      k || g ? "," : "", mname, glb_linear(rgb[0]), glb_linear(rgb[1]), glb_linear(rgb[2]));
            const float *uq = l->mesh[k].uvq;
            if (t >= 0 && uq[2] > 0)
                io_printf(js, ",\"baseColorTexture\":{\"index\":%d,\"extensions\":{\"KHR_texture_transform\":"
                              "{\"offset\":[%.9g,%.9g],\"scale\":[%.9g,%.9g]}}}", t, (double)uq[0], (double)uq[1],
                          (double)uq[2], (double)uq[3]);
            else if (t >= 0) io_printf(js, ",\"baseColorTexture\":{\"index\":%d}", t);
            io_printf(js, ",\"metallicFactor\":0,\"roughnessFactor\":%s}",
                      mat->kind == SYL_MATERIAL_BARK ? "0.95" : "0.7");
            bool leaf_image = slot >= IMAGE0 && mat->kind != SYL_MATERIAL_BARK;
            if (slot == CARD || slot == CLUSTER || (leaf_image && l->images->img[slot - IMAGE0].alpha))
                io_printf(js, ",\"alphaMode\":\"MASK\",\"alphaCutoff\":0.5,\"doubleSided\":true");
            else if (m->double_sided[i] || leaf_image) io_printf(js, ",\"doubleSided\":true"); /* one-sided leaves */
            if (mat->translucency) /* the extension both the Khronos validator and Blender's importer read */
                io_printf(js, ",\"extensions\":{\"KHR_materials_transmission\":{\"transmissionFactor\":%.4f}}",
                          mat->translucency / 255.0);
            io_put(js, "}", 1);
        }
    }
    io_put(js, "]", 1);
}

/* A mesh's POSITION, NORMAL and TEXCOORD_0 over vertices lo .. lo + nv - 1; n: accessors so far. */
static void json_attributes(IoBuf *js, const Layout *l, const MeshRef *r, size_t lo, size_t nv, int n) {
    static const char *const types[3] = {"VEC3", "VEC3", "VEC2"};
    const SylMesh *m = r->m;
    const float *data[3] = {m->pos + 3 * lo, m->nrm + 3 * lo, m->uv + 2 * lo};
    const float *q = r->set < 0 && l->quant[r->part][3] > 0 ? l->quant[r->part] : NULL;
    const bool quv = r->uvq[2] > 0;
    for (int a = 0; a < 3; a++, n++) {
        int type = q && a < 2 ? (a ? BYTE : SHORT) : a == 2 && quv ? UNSIGNED_SHORT : FLOAT;
        size_t size = q && a < 2 ? (a ? 4 : 8) : a == 2 ? (quv ? 4 : 8) : 12; /* an element's bytes */
        io_printf(js, "%s{\"bufferView\":%d,", n ? "," : "", r->view + a);
        if (lo) io_printf(js, "\"byteOffset\":%zu,", lo * size);
        io_printf(js, "\"componentType\":%d,%s\"count\":%zu,\"type\":\"%s\"", type,
                  type != FLOAT ? "\"normalized\":true," : "", nv, types[a]);
        if (q && a == 0) min_max_q16(js, data[0], nv, q, q[3]);
        else if (!(q && a == 1) && !(quv && a == 2)) glb_min_max(js, data[a], nv, a == 2 ? 2 : 3);
        io_put(js, "}", 1);
    }
}

/* A primitive's range of indices. */
static void json_indices(IoBuf *js, const MeshRef *r, const GlbPrim *pr) {
    io_printf(js, ",{\"bufferView\":%d,\"byteOffset\":%zu,\"componentType\":%d,\"count\":%u,\"type\":\"SCALAR\"}",
              r->view + 3, (size_t)pr->first * (r->pr.wide ? 4 : 2), r->pr.wide ? UNSIGNED_INT : UNSIGNED_SHORT, pr->count);
}

/* Accessors: per mesh the three attributes, then each group's range of indices (split: per
 * primitive its attributes and indices); per instance set its TRANSLATION, ROTATION and SCALE. */
static void json_accessors(IoBuf *js, const Layout *l) {
    io_printf(js, ",\"accessors\":[");
    int n = 0;
    for (int k = 0; k < l->nmeshes; k++) {
        const MeshRef *r = &l->mesh[k];
        const SylMesh *m = r->m;
        for (size_t c = 0; c < r->pr.n; c++) {
            const GlbPrim *pr = &r->pr.prim[c];
            if (r->pr.split || c == 0) json_attributes(js, l, r, pr->lo, pr->nv, n), n += 3;
            if (!r->pr.split) continue;
            json_indices(js, r, pr), n++;
            if (r->skinned) glb_skin_vertex_accessors(js, &l->sc->part[r->part], r->view + 4, pr->lo, pr->nv), n += 5;
        }
        if (r->pr.split) continue;
        for (size_t c = 0; c < r->pr.n; c++, n++) json_indices(js, r, &r->pr.prim[c]);
        if (r->skinned) glb_skin_vertex_accessors(js, &l->sc->part[r->part], r->view + 4, 0, m->nverts), n += 5;
    }
    int i = 0;
    for (int p = 0; p < l->sc->nparts; p++)
        for (int s = 0; s < l->sc->part[p].nsets; s++, i++) {
            static const char *const ttypes[3] = {"VEC3", "VEC4", "VEC3"};
            if (l->set_view[i] < 0) continue;
            bool q = l->quant[p][3] > 0;
            for (int a = 0; a < set_accessors(l, i); a++, n++)
                io_printf(js, "%s{\"bufferView\":%d,\"componentType\":%d,%s\"count\":%zu,\"type\":\"%s\"}", n ? "," : "",
                          l->set_view[i] + a, q ? SHORT : FLOAT, q ? "\"normalized\":true," : "",
                          l->sc->part[p].sets[s].count, ttypes[a]);
        }
    if (l->wind) glb_skin_anim_accessors(js, l->wind, l->anim_view);
    io_put(js, "]", 1);
}

/* Whether texture slot k is clamped: cards, the atlas, clusters and a leaf's own image. */
static bool clamps(const Layout *l, int k) {
    return k >= IMAGE0 ? l->image_leaf[k - IMAGE0] : k >= CARD;
}

/* Sampler, images and textures, when there are textures. Cards and the atlas clamp: a leaf
 * does not repeat, and wrapping would bleed the far edge's alpha into the base. */
static void json_textures(IoBuf *js, const Layout *l) {
    if (!l->ntex) return;
    int alpha = 0;
    for (int t = 0; t < l->ntex; t++) alpha += clamps(l, l->image_kind[t]);
    bool clamped = alpha > 0, tiled = l->ntex > alpha;
    io_printf(js, ",\"samplers\":[");
    if (tiled) io_printf(js, "{\"magFilter\":9729,\"minFilter\":9987,\"wrapS\":10497,\"wrapT\":10497}");
    if (clamped) io_printf(js, "%s{\"magFilter\":9729,\"minFilter\":9987,\"wrapS\":33071,\"wrapT\":33071}", tiled ? "," : "");
    io_printf(js, "],\"images\":[");
    for (int t = 0, cards = 0; t < l->ntex; t++) {
        int k = l->image_kind[t];
        io_printf(js, "%s{\"name\":", t ? "," : "");
        if (k == CARD && cards++) io_printf(js, "\"leafcard%d\"", cards); /* a further shape */
        else io_json_string(js, k >= IMAGE0 ? l->images->img[k - IMAGE0].name : glb_slot_name(k));
        io_printf(js, ",\"bufferView\":%d,\"mimeType\":\"image/png\"}", l->image_view[t]);
    }
    io_printf(js, "],\"textures\":[");
    for (int t = 0; t < l->ntex; t++)
        io_printf(js, "%s{\"sampler\":%d,\"source\":%d}", t ? "," : "", clamps(l, l->image_kind[t]) && tiled, t);
    io_put(js, "]", 1);
}

/* The joints, then each level's copy of them; instance sets hang from the joint they
 * follow: the joints themselves for one plant, the level's copy with levels of detail. */
static void json_joints(IoBuf *js, const Layout *l) {
    const GlbScene *sc = l->sc;
    int nj = l->wind->njoints;
    bool lods = joints_at_root(l);
    int *start = malloc(2 * ((size_t)nj + 1) * sizeof *start), *extra = malloc(((size_t)l->nsets + 1) * sizeof *extra);
    if (!start || !extra) {
        js->failed = true;
        free(start), free(extra);
        return;
    }
    int *at = start + nj + 1;
    for (int p = lods ? -1 : 0; p < (lods ? sc->nparts : 1); p++) { /* -1: the joints, without sets */
        if (p >= 0 && lods && l->anchor_node[p] < 0) continue;
        for (int pass = 0; pass < 2; pass++) { /* count each joint's sets, then list them */
            if (pass) {
                for (int j = 0; j < nj; j++) start[j + 1] += start[j];
                memcpy(at, start, ((size_t)nj + 1) * sizeof *at);
            } else {
                memset(start, 0, ((size_t)nj + 1) * sizeof *start);
            }
            for (int q = 0, i = 0; q < sc->nparts; q++)
                for (int s = 0; s < sc->part[q].nsets; s++, i++) {
                    if (q != p || l->set_node[i] < 0 || !l->set_joint || l->set_joint[i] < 0) continue;
                    if (pass) extra[at[l->set_joint[i]]++] = l->set_node[i];
                    else start[l->set_joint[i] + 1]++;
                }
        }
        bool copy = p >= 0 && lods;
        glb_skin_nodes(js, l->wind, copy ? l->anchor_node[p] : l->joint_node, copy ? sc->part[p].name : NULL, start, extra);
    }
    free(start), free(extra);
}

/* Each part a node (with its mesh, if it has one) and its instance sets child nodes of it;
 * with levels of detail, the first part lists the others in MSFT_lod. */
static void json_nodes(IoBuf *js, const Layout *l) {
    const GlbScene *sc = l->sc;
    io_printf(js, ",\"nodes\":[");
    int i0 = 0;
    for (int p = 0; p < sc->nparts; p++) {
        const GlbPart *pt = &sc->part[p];
        io_printf(js, "%s{\"name\":", p ? "," : "");
        io_json_string(js, pt->name);
        if (l->part_mesh[p] >= 0) io_printf(js, ",\"mesh\":%d", l->part_mesh[p]);
        const float *q = l->quant[p];
        if (q[3] > 0)
            io_printf(js, ",\"translation\":[%.9g,%.9g,%.9g],\"scale\":[%.9g,%.9g,%.9g]", (double)q[0], (double)q[1],
                      (double)q[2], (double)q[3], (double)q[3], (double)q[3]);
        bool skin = l->part_mesh[p] >= 0 && l->mesh[l->part_mesh[p]].skinned;
        if (skin) io_printf(js, ",\"skin\":0");
        skin &= !joints_at_root(l) && p == 0;
        bool any = false;
        for (int s = 0; s < pt->nsets; s++)
            if (l->set_node[i0 + s] >= 0 && !(l->set_joint && l->set_joint[i0 + s] >= 0))
                io_printf(js, "%s%d", any ? "," : ",\"children\":[", l->set_node[i0 + s]), any = true;
        int roots = skin ? l->joint_node : l->anchor_node[p];
        if (roots >= 0) {
            if (!any) io_printf(js, ",\"children\":[");
            glb_skin_roots(js, l->wind, roots, any);
            any = true;
        }
        if (any) io_put(js, "]", 1);
        if (sc->lods && p == 0 && sc->nparts > 1) {
            io_printf(js, ",\"extensions\":{\"MSFT_lod\":{\"ids\":[");
            for (int q = 1; q < sc->nparts; q++) io_printf(js, "%s%d", q > 1 ? "," : "", l->part_node[q]);
            io_printf(js, "]}},\"extras\":{\"MSFT_screencoverage\":[");
            for (int q = 0; q < sc->nparts; q++) io_printf(js, "%s%.6g", q ? "," : "", (double)sc->coverage[q]);
            io_put(js, "]}", 2);
        }
        if (sc->extras && p == sc->nparts - 1) io_printf(js, ",\"extras\":%s", sc->extras);
        io_put(js, "}", 1);
        i0 += pt->nsets;
    }
    int i = 0, a = 0;
    for (int k = 0; k < l->nmeshes; k++) a += accessors_of(&l->mesh[k]);
    for (int p = 0; p < sc->nparts; p++)
        for (int s = 0; s < sc->part[p].nsets; s++, i++) {
            if (l->set_node[i] < 0) continue;
            int mesh = l->set_mesh[i];
            io_printf(js, ",{\"name\":");
            io_json_string(js, sc->part[p].sets[s].name);
            io_printf(js, ",\"mesh\":%d,\"extensions\":{\"EXT_mesh_gpu_instancing\":{\"attributes\":"
                          "{\"TRANSLATION\":%d,\"ROTATION\":%d", mesh, a, a + 1);
            if (set_accessors(l, i) == 3) io_printf(js, ",\"SCALE\":%d", a + 2);
            io_printf(js, "}}}}");
            a += set_accessors(l, i);
        }
    if (l->wind) json_joints(js, l);
    io_put(js, "]", 1);
}

/* The JSON chunk, padded with spaces; the scene shows the first part (the other levels are
 * reached through MSFT_lod). Without geometry, a scene with empty nodes. */
static void write_json(IoBuf *js, const Layout *l) {
    const GlbScene *sc = l->sc;
    io_printf(js, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"Sylva\"}");
    bool lod = sc->lods && sc->nparts > 1, quant = false, uvt = false;
    for (int p = 0; p < sc->nparts; p++) quant |= l->quant[p][3] > 0;
    for (int k = 0; k < l->nmeshes; k++) uvt |= l->mesh[k].uvq[2] > 0;
    bool translucent = false; /* leaves that let light through (Pafčo's BIL_TRANSLUC) */
    for (int k = 0; k < l->nmeshes; k++)
        for (int g = 0; g < l->mesh[k].m->ngroups; g++)
            translucent |= l->mesh[k].m->materials[l->mesh[k].m->groups[g].material].translucency > 0;
    const char *used[5];
    int nused = 0;
    if (lod) used[nused++] = "MSFT_lod";
    if (l->nsets) used[nused++] = "EXT_mesh_gpu_instancing";
    if (quant) used[nused++] = "KHR_mesh_quantization";
    if (uvt && nused) used[nused++] = "KHR_texture_transform";
    if (translucent) used[nused++] = "KHR_materials_transmission";
    for (int i = 0; i < nused; i++) io_printf(js, "%s\"%s\"%s", i ? "," : ",\"extensionsUsed\":[", used[i], i == nused - 1 ? "]" : "");
    if (quant) io_printf(js, ",\"extensionsRequired\":[\"KHR_mesh_quantization\"%s]", uvt ? ",\"KHR_texture_transform\"" : "");
    io_printf(js, ",\"scene\":0,\"scenes\":[{\"name\":");
    io_json_string(js, sc->scene_name);
    io_printf(js, ",\"nodes\":[0");
    for (int p = 1; !sc->lods && p < sc->nparts; p++) io_printf(js, ",%d", p); /* a scene's objects */
    if (joints_at_root(l)) glb_skin_roots(js, l->wind, l->joint_node, true);
    io_printf(js, "]}]");
    json_nodes(js, l);
    if (l->nmeshes) {
        io_printf(js, ",\"meshes\":[");
        for (int k = 0; k < l->nmeshes; k++) json_mesh(js, l, k);
        io_put(js, "]", 1);
        json_materials(js, l);
        json_accessors(js, l);
        json_textures(js, l);
        if (l->wind) {
            int copies[SYL_LOD_MAX + 2], ncopies = 0;
            for (int p = 0; p < sc->nparts && ncopies < SYL_LOD_MAX + 2; p++)
                if (l->anchor_node[p] >= 0) copies[ncopies++] = l->anchor_node[p];
            glb_skin_json(js, l->wind, l->joint_node, l->anim_accessor, copies, ncopies);
        }
        glb_buffer_views(js, l->views, l->nviews, l->bin.len);
    }
    io_put(js, "}", 1);
    glb_pad(js, ' ');
}

/* A part's box: the centre and the largest half-extent of its mesh and instance positions. */
static void plan_quantization(const GlbPart *pt, float q[4]) {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    const float *xs[257];
    size_t ns[257];
    int k = 0;
    if (has_geometry(pt->mesh)) xs[k] = pt->mesh->pos, ns[k++] = pt->mesh->nverts;
    for (int s = 0; s < pt->nsets && k < 257; s++) xs[k] = pt->sets[s].t, ns[k++] = pt->sets[s].count;
    for (int i = 0; i < k; i++)
        for (size_t v = 0; v < ns[i]; v++)
            for (int c = 0; c < 3; c++) lo[c] = fminf(lo[c], xs[i][3 * v + (size_t)c]), hi[c] = fmaxf(hi[c], xs[i][3 * v + (size_t)c]);
    q[3] = 0;
    for (int c = 0; c < 3 && lo[0] <= hi[0]; c++) {
        q[c] = (lo[c] + hi[c]) / 2;
        q[3] = fmaxf(q[3], (hi[c] - lo[c]) / 2);
    }
    if (!(q[3] > 0) || !isfinite(q[3])) q[3] = 0; /* nothing to quantize: floats */
}

/* The size of every instance of set, when they all have the same one, the same along each
 * axis (Weber-Penn leaves: LeafScale): it goes into the prototype, and the set has no SCALE
 * (8 bytes a leaf quantized, 12 as floats). 0: they differ. */
static float one_size(const SylInstances *set) {
    const float s = set->s[0];
    if (!(s > 0) || !isfinite(s)) return 0;
    for (size_t i = 0; i < 3 * set->count; i++)
        if (set->s[i] != s) return 0;
    return s;
}

/* A copy of proto with its positions scaled by k (its other arrays shared); NULL: out of memory. */
static SylMesh *scaled(const SylMesh *proto, float k) {
    SylMesh *c = malloc(sizeof *c);
    float *pos = malloc((3 * proto->nverts + 1) * sizeof *pos);
    if (!c || !pos) {
        free(c), free(pos);
        return NULL;
    }
    *c = *proto;
    for (size_t i = 0; i < 3 * proto->nverts; i++) pos[i] = proto->pos[i] * k;
    c->pos = pos;
    return c;
}

/* Number the meshes, sets and nodes: parts first, then the instance sets' nodes. */
static bool plan(Layout *l) {
    const GlbScene *sc = l->sc;
    int sets = 0;
    for (int p = 0; p < sc->nparts; p++) sets += sc->part[p].nsets;
    size_t n = (size_t)(sc->nparts + sets) + 1;
    l->mesh = calloc(n, sizeof *l->mesh);
    l->views = malloc(sizeof *l->views * (9 * n + 3 * (size_t)sets + TEXTURES + 3));
    int *ints = malloc(sizeof(int) * (4 * (size_t)sets + 3 * (size_t)sc->nparts + 1));
    if (!l->mesh || !l->views || !ints) {
        free(ints);
        return false;
    }
    l->set_view = ints, l->set_accessor = ints + sets, l->set_node = ints + 2 * sets;
    l->part_mesh = ints + 3 * sets, l->part_node = ints + 3 * sets + sc->nparts;
    l->anchor_node = ints + 3 * sets + 2 * sc->nparts, l->set_mesh = ints + 3 * sets + 3 * sc->nparts;
    l->nnodes = sc->nparts;
    for (int p = 0; p < sc->nparts; p++) {
        l->part_node[p] = p;
        l->part_mesh[p] = -1;
        if (has_geometry(sc->part[p].mesh)) {
            l->part_mesh[p] = l->nmeshes;
            const GlbPart *pt = &sc->part[p];
            bool skinned = pt->wind && pt->wind->njoints > 0 && pt->skel && pt->mesh->node;
            l->mesh[l->nmeshes++] = (MeshRef){.m = pt->mesh, .part = p, .set = -1, .skinned = skinned};
            if (skinned) l->wind = pt->wind; /* one skin for all the parts */
        }
    }
    if (!(l->quant = calloc((size_t)sc->nparts + 1, sizeof *l->quant))) return false;
    for (int p = 0; p < sc->nparts && sc->quantize && !l->wind; p++) plan_quantization(sc->part + p, l->quant[p]);
    int i = 0;
    for (int p = 0; p < sc->nparts; p++)
        for (int s = 0; s < sc->part[p].nsets; s++, i++) {
            const SylInstances *set = &sc->part[p].sets[s];
            l->set_view[i] = l->set_node[i] = l->set_mesh[i] = -1;
            if (!has_geometry(set->proto) || !set->count) continue; /* an empty set is left out */
            l->set_node[i] = l->nnodes++;
            l->nsets++;
            float fold = one_size(set);
            if (l->quant[p][3] > 0) fold /= l->quant[p][3]; /* the part's node scales it again */
            for (int k = 0; k < l->nmeshes && l->set_mesh[i] < 0; k++) /* sets of one prototype and size share it */
                if (l->mesh[k].set >= 0 && l->mesh[k].proto == set->proto && l->mesh[k].fold == fold) l->set_mesh[i] = k;
            if (l->set_mesh[i] < 0) {
                l->set_mesh[i] = l->nmeshes;
                MeshRef r = {.m = set->proto, .proto = set->proto, .fold = fold, .part = p, .set = s};
                if (fold > 0 && !(r.m = scaled(set->proto, fold))) return false;
                l->mesh[l->nmeshes++] = r;
            }
        }
    l->joint_node = l->nnodes;
    if (l->wind) l->nnodes += l->wind->njoints;
    i = 0;
    for (int p = 0; p < sc->nparts; p++) { /* with levels, each level's copy of the joints */
        l->anchor_node[p] = -1;
        for (int s = 0; s < sc->part[p].nsets; s++, i++)
            if (l->set_joint && l->set_joint[i] >= 0 && l->set_node[i] >= 0 && joints_at_root(l) && l->anchor_node[p] < 0)
                l->anchor_node[p] = l->nnodes, l->nnodes += l->wind->njoints;
    }
    return true;
}

/* The file of sc; set_joint (may be NULL): the joint each instance set follows. */
static int write_scene(const GlbScene *sc, const int *set_joint, const char *path, const SylSink *sink) {
    Layout l = {.sc = sc, .set_joint = set_joint};
    for (int k = 0; k < SLOTS; k++) l.tex_of_kind[k] = -1;
    for (int k = 0; k < SHAPES; k++) l.card_tex[k] = -1;
    IoBuf js = {0};
    bool ok = plan(&l);
    if (!ok) l.bin.failed = true;
    for (int k = 0; k < l.nmeshes && ok; k++) ok = glb_primitives(l.mesh[k].m, &l.mesh[k].pr);
    if (!ok) l.bin.failed = true;
    size_t own = 0;
    for (int k = 0; k < l.nmeshes && ok; k++) own += attribute_bytes(&l.mesh[k]);
    io_reserve(&l.bin, own);
    for (int k = 0; k < l.nmeshes && ok; k++) layout_attributes(&l, &l.mesh[k]);
    int i = 0;
    for (int p = 0; p < sc->nparts && ok; p++)
        for (int s = 0; s < sc->part[p].nsets; s++, i++)
            if (l.set_node[i] >= 0) layout_instances(&l, &sc->part[p].sets[s], i, l.quant[p]);
    l.anim_view = l.nviews;
    if (l.wind && ok) glb_skin_animation(l.wind, &l.bin, l.views, &l.nviews);
    int mat = 0, acc = 0;
    for (int k = 0; k < l.nmeshes && ok; k++) {
        l.mesh[k].material = mat, mat += l.mesh[k].m->ngroups;
        l.mesh[k].accessor = acc, acc += accessors_of(&l.mesh[k]);
    }
    for (int q = 0, i = 0; q < sc->nparts; q++)
        for (int s = 0; s < sc->part[q].nsets; s++, i++)
            if (l.set_node[i] >= 0) acc += set_accessors(&l, i);
    l.anim_accessor = acc;
    if (ok) layout_textures(&l);
    glb_pad(&l.bin, 0);
    if (ok) write_json(&js, &l);
    int status = glb_container_to(path, sc->stream, &js, &l.bin, l.nmeshes > 0, sink);
    io_free(&js);
    io_free(&l.bin);
    free(l.views);
    for (int k = 0; k < l.nmeshes; k++) {
        free(l.mesh[k].pr.prim);
        if (l.mesh[k].m != l.mesh[k].proto && l.mesh[k].proto) free(l.mesh[k].m->pos), free((SylMesh *)l.mesh[k].m);
    }
    free(l.mesh);
    free(l.set_view);
    free(l.quant);
    return status;
}

/* A skinned scene's instance sets split by the joint each instance follows (glb_skin_split),
 * into parts (a copy of sc's); set_joint numbers them over all parts (-1: not split). */
static int write_split(const GlbScene *sc, GlbPart *parts, const char *path, const SylSink *sink) {
    int total = 0, status = SYL_OK;
    int *set_joint = NULL;
    for (int p = 0; p < sc->nparts; p++) parts[p] = sc->part[p], parts[p].sets = NULL, parts[p].nsets = 0;
    for (int p = 0; p < sc->nparts && !status; p++) {
        const GlbPart *pt = &sc->part[p];
        SylInstances *sets = NULL;
        int *joint = NULL, n = 0;
        bool skinned = pt->wind && pt->wind->njoints > 0 && pt->skel;
        if (skinned && !glb_skin_split(pt, &sets, &joint, &n)) status = SYL_ELIMIT;
        int *all = realloc(set_joint, ((size_t)total + (size_t)(skinned ? n : pt->nsets) + 1) * sizeof *all);
        if (!all) status = SYL_ELIMIT;
        else set_joint = all;
        if (status) {
            glb_skin_split_free(sets, n);
            free(joint);
            break;
        }
        if (skinned) {
            parts[p].sets = sets, parts[p].nsets = n;
            if (n) memcpy(set_joint + total, joint, (size_t)n * sizeof *joint);
            total += n;
        } else {
            parts[p].sets = pt->sets, parts[p].nsets = pt->nsets;
            for (int s = 0; s < pt->nsets; s++) set_joint[total++] = -1;
        }
        free(joint);
    }
    GlbScene split = *sc;
    split.part = parts;
    if (!status) status = write_scene(&split, set_joint, path, sink);
    else sink_error(sink, "out of memory writing '%s'", path);
    for (int p = 0; p < sc->nparts; p++)
        if (parts[p].sets != sc->part[p].sets) glb_skin_split_free((SylInstances *)parts[p].sets, parts[p].nsets);
    free(set_joint);
    return status;
}

int glb_write(const GlbScene *sc, const char *path, const SylSink *sink) {
    bool split = false;
    for (int p = 0; p < sc->nparts; p++) split |= sc->part[p].wind && sc->part[p].nsets > 0;
    if (!split) return write_scene(sc, NULL, path, sink);
    GlbPart *parts = calloc((size_t)sc->nparts + 1, sizeof *parts);
    if (!parts) {
        sink_error(sink, "out of memory writing '%s'", path);
        return SYL_ELIMIT;
    }
    int status = write_split(sc, parts, path, sink);
    free(parts);
    return status;
}

static int write_instanced(const SylMesh *m, const SylInstances *sets, int n, const char *path, FILE *stream,
                           SylTextureCache *tc, const SylSink *sink) {
    const char *name = m->name[0] ? m->name : "plant";
    GlbPart part = {.mesh = m, .sets = sets, .nsets = n > 0 ? n : 0, .name = name};
    GlbScene sc = {.part = &part, .nparts = 1, .scene_name = name, .quantize = n > 0, /* instanced: small */
                   .stream = stream, .textures = tc};
    return glb_write(&sc, path, sink);
}

int syl_mesh_write_glb_instanced(const SylMesh *m, const SylInstances *sets, int n, const char *path, const SylSink *sink) {
    return write_instanced(m, sets, n, path, NULL, NULL, sink);
}

int syl_mesh_write_glb_instanced_stream(const SylMesh *m, const SylInstances *sets, int n, FILE *out, const SylSink *sink) {
    return write_instanced(m, sets, n, "(stream)", out, NULL, sink);
}

int syl_mesh_write_glb_instanced_cached(const SylMesh *m, const SylInstances *sets, int n, SylTextureCache *tc,
                                        FILE *out, const SylSink *sink) {
    return write_instanced(m, sets, n, "(stream)", out, tc, sink);
}

int syl_mesh_write_glb(const SylMesh *m, const char *path, const SylSink *sink) { return syl_mesh_write_glb_instanced(m, NULL, 0, path, sink); }

int syl_mesh_write_glb_parts(SylMesh *const *parts, int n, const char *name, const char *path, const SylSink *sink) {
    GlbPart *part = calloc((size_t)(n > 0 ? n : 1), sizeof *part);
    if (!part) return SYL_ELIMIT;
    for (int i = 0; i < n; i++) part[i] = (GlbPart){.mesh = parts[i], .name = parts[i]->name};
    GlbScene sc = {.part = part, .nparts = n, .scene_name = name};
    int st = glb_write(&sc, path, sink);
    free(part);
    return st;
}
