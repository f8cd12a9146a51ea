/* The glTF 2.0 binary writer of a chain of levels of detail (.glb, `sylva mesh --lod`).
 * Its words, padding, buffer views and container are glb_parts.c's, shared with glb.c; its
 * layout and JSON are still its own (no leaf cards, instance sets or 16-bit indices), to be
 * folded into glb.c's so that levels of detail take every leaf mode. */

/* One scene, a node named after the model (or one per level of detail, NAME_LOD0 .. with
 * MSFT_lod on the first), a mesh per node with one primitive per material group. POSITION,
 * NORMAL and TEXCOORD_0 are shared by the primitives; each has its own
 * range of indices. Materials are metallic-roughness with the
 * material's colour (converted to linear, as glTF wants) and, for bark, leaf and flower
 * kinds, the procedural texture (PNG, embedded in the BIN chunk). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "io/glb.h"
#include "sylva/lod.h"
#include "sylva/texture.h"








enum { GLB_MAX_MESHES = SYL_LOD_MAX + 1 };

/* What is written: meshes, one node each (with its name), LOD0's MSFT_lod. */
typedef struct GlbPart {
    const SylMesh *mesh;
    char name[80];
} GlbPart;

typedef struct GlbScene {
    GlbPart part[GLB_MAX_MESHES];
    int nparts;
    float coverage[GLB_MAX_MESHES]; /* MSFT_screencoverage, when lods */
    bool lods;
    const SylLodChain *chain;       /* its atlas and extras (last part), or NULL */
} GlbScene;

/* The BIN chunk and how it is cut into buffer views: each mesh's attributes and indices,
 * then images. */
typedef struct Layout {
    IoBuf bin;
    View views[4 * GLB_MAX_MESHES + 4]; /* and the images: three kinds and an atlas */
    int nviews;
    int first_view[GLB_MAX_MESHES];     /* of each mesh's four views (-1: no geometry) */
    int tex_of_kind[3], ntex, image_view[4]; /* texture of each kind (-1: none), its view */
    int atlas_tex;                           /* the chain's atlas texture (-1: none) */
    int mat_slot[256], nmat, mat_of_slot[256]; /* glTF material of each Sylva material (-1: unused) */
} Layout;

static const int kinds[] = {SYL_MATERIAL_BARK, SYL_MATERIAL_LEAF, SYL_MATERIAL_FLOWER};

static bool has_geometry(const SylMesh *m) { return m->nverts > 0 && m->nidx > 0 && m->ngroups > 0; }

/* POSITION, NORMAL and TEXCOORD_0, then the indices: four views. */
static void layout_attributes(const SylMesh *m, Layout *l) {
    const size_t nv = m->nverts;
    l->views[l->nviews++] = (View){l->bin.len, 12 * nv, ARRAY_BUFFER};
    glb_words(&l->bin, m->pos, 3 * nv);
    l->views[l->nviews++] = (View){l->bin.len, 12 * nv, ARRAY_BUFFER};
    glb_words(&l->bin, m->nrm, 3 * nv);
    l->views[l->nviews++] = (View){l->bin.len, 8 * nv, ARRAY_BUFFER};
    glb_words(&l->bin, m->uv, 2 * nv);
    l->views[l->nviews++] = (View){l->bin.len, 4 * m->nidx, ELEMENT_ARRAY_BUFFER};
    glb_words(&l->bin, m->idx, m->nidx);
}

/* The materials the meshes use, in the order of their indices: one glTF material each. */
static void layout_materials(const GlbScene *sc, Layout *l) {
    bool used[256] = {false};
    for (int p = 0; p < sc->nparts; p++)
        for (int g = 0; g < sc->part[p].mesh->ngroups; g++) used[sc->part[p].mesh->groups[g].material] = true;
    for (int i = 0; i < 256; i++) {
        l->mat_slot[i] = used[i] ? l->nmat : -1;
        if (used[i]) l->mat_of_slot[l->nmat++] = i;
    }
}

/* One PNG texture per kind used (bark, leaf, flower), each in a view of its own. */
static void layout_textures(const GlbScene *sc, Layout *l) {
    uint8_t *rgb = NULL;
    const SylMesh *m = sc->part[0].mesh; /* the levels share one material table */
    int skip = sc->chain && sc->chain->atlas ? sc->chain->atlas_material : -1;
    for (int k = 0; k < 3; k++) {
        bool used = false;
        for (int s = 0; s < l->nmat && !used; s++)
            used = l->mat_of_slot[s] != skip && m->materials[l->mat_of_slot[s]].kind == kinds[k];
        if (!used) continue;
        if (!rgb && !(rgb = malloc((size_t)SYL_TEXTURE_SIZE * SYL_TEXTURE_SIZE * 3))) {
            l->bin.failed = true;
            break;
        }
        size_t at = l->bin.len;
        if (!syl_texture(kinds[k], NULL, SYL_TEXTURE_SIZE, rgb) || !io_png(&l->bin, rgb, SYL_TEXTURE_SIZE)) {
            l->bin.failed = true;
            break;
        }
        l->image_view[l->ntex] = l->nviews;
        l->views[l->nviews++] = (View){at, l->bin.len - at, 0};
        glb_pad(&l->bin, 0);
        l->tex_of_kind[k] = l->ntex++;
    }
    free(rgb);
    const SylLodChain *c = sc->chain;
    if (c && c->atlas && !l->bin.failed) {
        size_t at = l->bin.len;
        if (!io_png_rgba(&l->bin, c->atlas, c->atlas_w, c->atlas_h)) {
            l->bin.failed = true;
            return;
        }
        l->image_view[l->ntex] = l->nviews;
        l->views[l->nviews++] = (View){at, l->bin.len - at, 0};
        glb_pad(&l->bin, 0);
        l->atlas_tex = l->ntex++;
    }
}

/* The nodes: one per part, with its mesh; LOD0 lists the lower levels in MSFT_lod. */
static void json_nodes(IoBuf *js, const GlbScene *sc, const Layout *l) {
    io_printf(js, ",\"nodes\":[");
    int mesh = 0;
    for (int p = 0; p < sc->nparts; p++) {
        io_printf(js, "%s{\"name\":", p ? "," : "");
        io_json_string(js, sc->part[p].name);
        if (l->first_view[p] >= 0) io_printf(js, ",\"mesh\":%d", mesh++);
        if (sc->lods && p == 0 && sc->nparts > 1) {
            io_printf(js, ",\"extensions\":{\"MSFT_lod\":{\"ids\":[");
            for (int q = 1; q < sc->nparts; q++) io_printf(js, "%s%d", q > 1 ? "," : "", q);
            io_printf(js, "]}},\"extras\":{\"MSFT_screencoverage\":[");
            for (int q = 0; q < sc->nparts; q++) io_printf(js, "%s%.6g", q ? "," : "", (double)sc->coverage[q]);
            io_put(js, "]}", 2);
        }
        if (sc->chain && sc->chain->extras && p == sc->nparts - 1) io_printf(js, ",\"extras\":%s", sc->chain->extras);
        io_put(js, "}", 1);
    }
    io_put(js, "]", 1);
}

/* The meshes (one primitive per group) and the materials. acc: each part's first accessor. */
static void json_meshes(IoBuf *js, const GlbScene *sc, const Layout *l, const int *acc) {
    io_printf(js, ",\"meshes\":[");
    bool first = true;
    for (int p = 0; p < sc->nparts; p++) {
        const SylMesh *m = sc->part[p].mesh;
        if (l->first_view[p] < 0) continue;
        io_printf(js, "%s{\"name\":", first ? "" : ",");
        first = false;
        io_json_string(js, sc->part[p].name);
        io_printf(js, ",\"primitives\":[");
        for (int g = 0; g < m->ngroups; g++)
            io_printf(js, "%s{\"attributes\":{\"POSITION\":%d,\"NORMAL\":%d,\"TEXCOORD_0\":%d},\"indices\":%d,"
                          "\"material\":%d,\"mode\":4}",
                      g ? "," : "", acc[p], acc[p] + 1, acc[p] + 2, acc[p] + 3 + g, l->mat_slot[m->groups[g].material]);
        io_put(js, "]}", 2);
    }
    io_printf(js, "],\"materials\":[");
    const SylMesh *m = sc->part[0].mesh;
    for (int s = 0; s < l->nmat; s++) {
        int i = l->mat_of_slot[s];
        const SylMaterial *mat = &m->materials[i];
        char mname[32];
        if (sc->chain && l->atlas_tex >= 0 && i == sc->chain->atlas_material) { /* the billboards' picture */
            io_printf(js, "%s{\"name\":\"impostor\",\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":%d},"
                          "\"metallicFactor\":0,\"roughnessFactor\":0.9},\"alphaMode\":\"MASK\",\"alphaCutoff\":0.5}",
                      s ? "," : "", l->atlas_tex);
            continue;
        }
        io_material_name(m, i, mname, sizeof mname);
        io_printf(js, "%s{\"name\":\"%s\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[%.6f,%.6f,%.6f,1]",
                  s ? "," : "", mname, glb_linear(mat->rgb[0]), glb_linear(mat->rgb[1]),
                  glb_linear(mat->rgb[2]));
        int t = -1;
        for (int k = 0; k < 3; k++)
            if (mat->kind == kinds[k]) t = l->tex_of_kind[k];
        if (t >= 0) io_printf(js, ",\"baseColorTexture\":{\"index\":%d}", t);
        io_printf(js, ",\"metallicFactor\":0,\"roughnessFactor\":%s}}",
                  mat->kind == SYL_MATERIAL_BARK ? "0.95" : "0.7");
    }
    io_put(js, "]", 1);
}

/* Accessors: per mesh, the three attributes, then each group's range of indices. */
static void json_accessors(IoBuf *js, const GlbScene *sc, const Layout *l, int *acc) {
    io_printf(js, ",\"accessors\":[");
    static const char *const types[3] = {"VEC3", "VEC3", "VEC2"};
    int n = 0;
    for (int p = 0; p < sc->nparts; p++) {
        const SylMesh *m = sc->part[p].mesh;
        int v = l->first_view[p];
        if (v < 0) continue;
        acc[p] = n;
        const float *data[3] = {m->pos, m->nrm, m->uv};
        for (int a = 0; a < 3; a++) {
            io_printf(js, "%s{\"bufferView\":%d,\"componentType\":%d,\"count\":%zu,\"type\":\"%s\"", n ? "," : "",
                      v + a, FLOAT, m->nverts, types[a]);
            glb_min_max(js, data[a], m->nverts, a == 2 ? 2 : 3);
            io_put(js, "}", 1);
            n++;
        }
        for (int g = 0; g < m->ngroups; g++, n++)
            io_printf(js, ",{\"bufferView\":%d,\"byteOffset\":%zu,\"componentType\":%d,\"count\":%u,\"type\":\"SCALAR\"}",
                      v + 3, (size_t)m->groups[g].first * 4, UNSIGNED_INT, m->groups[g].count);
    }
    io_put(js, "]", 1);
}

/* Sampler, images and textures, when there are textures. */
static void json_textures(IoBuf *js, const Layout *l) {
    if (!l->ntex) return;
    io_printf(js, ",\"samplers\":[{\"magFilter\":9729,\"minFilter\":9987,\"wrapS\":10497,\"wrapT\":10497}]"
                  ",\"images\":[");
    int t = 0;
    for (int k = 0; k < 3; k++)
        if (l->tex_of_kind[k] >= 0)
            io_printf(js, "%s{\"name\":\"%s\",\"bufferView\":%d,\"mimeType\":\"image/png\"}", t ? "," : "",
                      syl_texture_name(kinds[k]), l->image_view[t]), t++;
    if (l->atlas_tex >= 0)
        io_printf(js, "%s{\"name\":\"impostor\",\"bufferView\":%d,\"mimeType\":\"image/png\"}", t ? "," : "",
                  l->image_view[l->atlas_tex]);
    io_printf(js, "],\"textures\":[");
    for (t = 0; t < l->ntex; t++) io_printf(js, "%s{\"sampler\":0,\"source\":%d}", t ? "," : "", t);
    io_put(js, "]", 1);
}

/* The JSON chunk, padded with spaces; the scene shows the first node (the other levels are
 * reached through MSFT_lod). Without geometry, a scene with empty nodes. */
static void write_json(IoBuf *js, const GlbScene *sc, const Layout *l, bool geometry) {
    const SylMesh *m = sc->part[0].mesh;
    io_printf(js, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"Sylva\"}");
    if (sc->lods && sc->nparts > 1) io_printf(js, ",\"extensionsUsed\":[\"MSFT_lod\"]");
    io_printf(js, ",\"scene\":0,\"scenes\":[{\"name\":");
    io_json_string(js, m->name[0] ? m->name : "plant");
    io_printf(js, ",\"nodes\":[0]}]");
    json_nodes(js, sc, l);
    if (geometry) {
        int acc[GLB_MAX_MESHES] = {0};
        json_accessors(js, sc, l, acc);
        json_meshes(js, sc, l, acc);
        json_textures(js, l);
        glb_buffer_views(js, l->views, l->nviews, l->bin.len);
    }
    io_put(js, "}", 1);
    glb_pad(js, ' ');
}


static int write_scene(const GlbScene *sc, const char *path, FILE *diag) {
    Layout l = {.tex_of_kind = {-1, -1, -1}, .atlas_tex = -1};
    IoBuf js = {0};
    bool geometry = false;
    for (int p = 0; p < sc->nparts; p++) {
        l.first_view[p] = -1;
        if (!has_geometry(sc->part[p].mesh)) continue;
        l.first_view[p] = l.nviews;
        layout_attributes(sc->part[p].mesh, &l);
        geometry = true;
    }
    if (geometry) {
        layout_materials(sc, &l);
        layout_textures(sc, &l);
    }
    glb_pad(&l.bin, 0);
    write_json(&js, sc, &l, geometry);
    int status = glb_container(path, &js, &l.bin, geometry, diag);
    io_free(&js);
    io_free(&l.bin);
    return status;
}

int syl_write_glb_lods(const SylLodChain *c, const char *path, FILE *diag) {
    GlbScene sc = {.nparts = c->n, .lods = true, .chain = c};
    const char *name = c->level[0].mesh->name[0] ? c->level[0].mesh->name : "plant";
    for (int k = 0; k < c->n; k++) {
        sc.part[k].mesh = c->level[k].mesh;
        snprintf(sc.part[k].name, sizeof sc.part[k].name, "%s_LOD%d", name, k);
        sc.coverage[k] = c->level[k].coverage;
    }
    return write_scene(&sc, path, diag);
}
