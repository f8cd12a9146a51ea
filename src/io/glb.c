/* The glTF 2.0 binary writer (.glb): BIN layout, JSON, and the container. */

/* One scene, one node named after the model, one mesh with one primitive per material
 * group. POSITION, NORMAL and TEXCOORD_0 are shared by the primitives; each has its own
 * range of indices (16-bit up to 65,535 vertices, 32-bit above). Instance sets are child
 * nodes of their own, each with a prototype mesh and EXT_mesh_gpu_instancing transforms. Materials are metallic-roughness with the
 * material's colour (converted to linear, as glTF wants) and, for bark, leaf and flower
 * kinds, the procedural texture (PNG, embedded in the BIN chunk). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "io/glb.h"
#include "sylva/texture.h"








enum { KINDS = 4, CARD = 3 }; /* texture slots: bark, leaf, flower, and the leaf card (RGBA) */

/* What goes in the file: meshes (the plant's, then each instance set's prototype), and the
 * BIN chunk cut into buffer views: per mesh its attributes and indices, per instance set its
 * transforms, then the images. */
typedef struct Layout {
    IoBuf bin;
    View *views;
    int nviews;
    const SylMesh *mesh[257];
    int nmeshes, first_view[257], first_accessor[257], first_material[257];
    bool wide[257];    /* 32-bit indices (more than 65,535 vertices) */
    int plant_mesh;    /* -1: the plant has no geometry of its own */
    const SylInstances *sets;
    int nsets, set_mesh[256], set_view[256], set_accessor[256];
    int tex_of_kind[KINDS], ntex, image_view[KINDS], image_kind[KINDS];
} Layout;

static const int kinds[] = {SYL_MATERIAL_BARK, SYL_MATERIAL_LEAF, SYL_MATERIAL_FLOWER};

static bool has_geometry(const SylMesh *m) { return m && m->nverts > 0 && m->nidx > 0 && m->ngroups > 0; }
static bool cards(const SylMesh *m) { return m->leaves == SYL_LEAVES_CARDS || m->leaves == SYL_LEAVES_INSTANCED_CARDS; }

/* The texture slot a material of m uses (-1: none). */
static int slot_of(const SylMesh *m, int material) {
    int kind = m->materials[material].kind;
    if (kind == SYL_MATERIAL_LEAF && cards(m)) return CARD;
    for (int k = 0; k < 3; k++)
        if (kind == kinds[k]) return k;
    return -1;
}

/* POSITION, NORMAL and TEXCOORD_0, then the indices, the smallest type that holds them. */
static void layout_attributes(const SylMesh *m, Layout *l, int k) {
    const size_t nv = m->nverts;
    l->first_view[k] = l->nviews;
    l->views[l->nviews++] = (View){l->bin.len, 12 * nv, ARRAY_BUFFER};
    glb_words(&l->bin, m->pos, 3 * nv);
    l->views[l->nviews++] = (View){l->bin.len, 12 * nv, ARRAY_BUFFER};
    glb_words(&l->bin, m->nrm, 3 * nv);
    l->views[l->nviews++] = (View){l->bin.len, 8 * nv, ARRAY_BUFFER};
    glb_words(&l->bin, m->uv, 2 * nv);
    /* 16 bits up to 65,535 vertices: 65,535 itself is the primitive restart value */
    l->wide[k] = nv > 65535;
    l->views[l->nviews++] = (View){l->bin.len, (l->wide[k] ? 4 : 2) * m->nidx, ELEMENT_ARRAY_BUFFER};
    if (l->wide[k]) {
        glb_words(&l->bin, m->idx, m->nidx);
    } else {
        for (size_t i = 0; i < m->nidx; i++) {
            uint8_t p[2] = {(uint8_t)m->idx[i], (uint8_t)(m->idx[i] >> 8)};
            io_put(&l->bin, p, 2);
        }
        glb_pad(&l->bin, 0);
    }
}

/* Each set's translations, rotations and scales: three views. */
static void layout_instances(Layout *l) {
    for (int i = 0; i < l->nsets; i++) {
        const SylInstances *set = &l->sets[i];
        l->set_view[i] = l->nviews;
        l->views[l->nviews++] = (View){l->bin.len, 12 * set->count, 0};
        glb_words(&l->bin, set->t, 3 * set->count);
        l->views[l->nviews++] = (View){l->bin.len, 16 * set->count, 0};
        glb_words(&l->bin, set->r, 4 * set->count);
        l->views[l->nviews++] = (View){l->bin.len, 12 * set->count, 0};
        glb_words(&l->bin, set->s, 3 * set->count);
    }
}

/* One PNG texture per slot used (bark, leaf, flower, leaf card), each in a view of its own. */
static void layout_textures(Layout *l) {
    bool used[KINDS] = {false};
    int shape = 0;
    for (int k = 0; k < l->nmeshes; k++)
        for (int g = 0; g < l->mesh[k]->ngroups; g++) {
            int t = slot_of(l->mesh[k], l->mesh[k]->groups[g].material);
            if (t >= 0) used[t] = true;
            if (t == CARD) shape = l->mesh[k]->leaf_shape;
        }
    uint8_t *img = NULL;
    for (int k = 0; k < KINDS; k++) {
        if (!used[k]) continue;
        if (!img && !(img = malloc((size_t)SYL_TEXTURE_SIZE * SYL_TEXTURE_SIZE * 4))) {
            l->bin.failed = true;
            break;
        }
        size_t at = l->bin.len;
        bool ok = k == CARD ? syl_leaf_card(shape, SYL_TEXTURE_SIZE, img) &&
                                  io_png_rgba(&l->bin, img, SYL_TEXTURE_SIZE, SYL_TEXTURE_SIZE)
                            : syl_texture(kinds[k], NULL, SYL_TEXTURE_SIZE, img) &&
                                  io_png(&l->bin, img, SYL_TEXTURE_SIZE);
        if (!ok) {
            l->bin.failed = true;
            break;
        }
        l->image_view[l->ntex] = l->nviews;
        l->image_kind[l->ntex] = k;
        l->views[l->nviews++] = (View){at, l->bin.len - at, 0};
        glb_pad(&l->bin, 0);
        l->tex_of_kind[k] = l->ntex++;
    }
    free(img);
}

/* Mesh k's primitives, one per group. */
static void json_mesh(IoBuf *js, const Layout *l, int k, const char *name) {
    const SylMesh *m = l->mesh[k];
    int a = l->first_accessor[k];
    io_printf(js, "%s{\"name\":", k ? "," : "");
    io_json_string(js, name);
    io_printf(js, ",\"primitives\":[");
    for (int g = 0; g < m->ngroups; g++)
        io_printf(js, "%s{\"attributes\":{\"POSITION\":%d,\"NORMAL\":%d,\"TEXCOORD_0\":%d},\"indices\":%d,"
                      "\"material\":%d,\"mode\":4}",
                  g ? "," : "", a, a + 1, a + 2, a + 3 + g, l->first_material[k] + g);
    io_printf(js, "]}");
}

/* Materials: metallic-roughness, one per group of each mesh; leaf cards alpha-tested. */
static void json_materials(IoBuf *js, const Layout *l) {
    io_printf(js, ",\"materials\":[");
    for (int k = 0; k < l->nmeshes; k++) {
        const SylMesh *m = l->mesh[k];
        for (int g = 0; g < m->ngroups; g++) {
            const SylMaterial *mat = &m->materials[m->groups[g].material];
            char mname[32];
            io_material_name(m, m->groups[g].material, mname, sizeof mname);
            io_printf(js, "%s{\"name\":\"%s\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[%.6f,%.6f,%.6f,1]",
                      k || g ? "," : "", mname, glb_linear(mat->rgb[0]), glb_linear(mat->rgb[1]),
                      glb_linear(mat->rgb[2]));
            int slot = slot_of(m, m->groups[g].material), t = slot >= 0 ? l->tex_of_kind[slot] : -1;
            if (t >= 0) io_printf(js, ",\"baseColorTexture\":{\"index\":%d}", t);
            io_printf(js, ",\"metallicFactor\":0,\"roughnessFactor\":%s}",
                      mat->kind == SYL_MATERIAL_BARK ? "0.95" : "0.7");
            if (slot == CARD) io_printf(js, ",\"alphaMode\":\"MASK\",\"alphaCutoff\":0.5,\"doubleSided\":true");
            io_put(js, "}", 1);
        }
    }
    io_put(js, "]", 1);
}

/* Accessors: per mesh the three attributes, then each group's range of indices; per
 * instance set its TRANSLATION, ROTATION and SCALE. */
static void json_accessors(IoBuf *js, const Layout *l) {
    io_printf(js, ",\"accessors\":[");
    static const char *const types[3] = {"VEC3", "VEC3", "VEC2"};
    int n = 0;
    for (int k = 0; k < l->nmeshes; k++) {
        const SylMesh *m = l->mesh[k];
        const float *data[3] = {m->pos, m->nrm, m->uv};
        for (int a = 0; a < 3; a++, n++) {
            io_printf(js, "%s{\"bufferView\":%d,\"componentType\":%d,\"count\":%zu,\"type\":\"%s\"", n ? "," : "",
                      l->first_view[k] + a, FLOAT, m->nverts, types[a]);
            glb_min_max(js, data[a], m->nverts, a == 2 ? 2 : 3);
            io_put(js, "}", 1);
        }
        for (int g = 0; g < m->ngroups; g++, n++)
            io_printf(js, ",{\"bufferView\":%d,\"byteOffset\":%zu,\"componentType\":%d,\"count\":%u,\"type\":\"SCALAR\"}",
                      l->first_view[k] + 3, (size_t)m->groups[g].first * (l->wide[k] ? 4 : 2),
                      l->wide[k] ? UNSIGNED_INT : UNSIGNED_SHORT, m->groups[g].count);
    }
    for (int i = 0; i < l->nsets; i++) {
        static const char *const ttypes[3] = {"VEC3", "VEC4", "VEC3"};
        for (int a = 0; a < 3; a++, n++)
            io_printf(js, "%s{\"bufferView\":%d,\"componentType\":%d,\"count\":%zu,\"type\":\"%s\"}", n ? "," : "",
                      l->set_view[i] + a, FLOAT, l->sets[i].count, ttypes[a]);
    }
    io_put(js, "]", 1);
}

/* Sampler, images and textures, when there are textures. Cards clamp: a leaf does not
 * repeat, and wrapping would bleed the far edge's alpha into the base. */
static void json_textures(IoBuf *js, const Layout *l) {
    if (!l->ntex) return;
    bool card = l->tex_of_kind[CARD] >= 0, tiled = l->ntex > card;
    io_printf(js, ",\"samplers\":[");
    if (tiled) io_printf(js, "{\"magFilter\":9729,\"minFilter\":9987,\"wrapS\":10497,\"wrapT\":10497}");
    if (card) io_printf(js, "%s{\"magFilter\":9729,\"minFilter\":9987,\"wrapS\":33071,\"wrapT\":33071}", tiled ? "," : "");
    io_printf(js, "],\"images\":[");
    for (int t = 0; t < l->ntex; t++)
        io_printf(js, "%s{\"name\":\"%s\",\"bufferView\":%d,\"mimeType\":\"image/png\"}", t ? "," : "",
                  l->image_kind[t] == CARD ? "leafcard" : syl_texture_name(kinds[l->image_kind[t]]), l->image_view[t]);
    io_printf(js, "],\"textures\":[");
    for (int t = 0; t < l->ntex; t++)
        io_printf(js, "%s{\"sampler\":%d,\"source\":%d}", t ? "," : "", l->image_kind[t] == CARD && tiled, t);
    io_put(js, "]", 1);
}

/* Node 0 is the plant (with its mesh, if it has one); each instance set a child of it. */
static void json_nodes(IoBuf *js, const Layout *l, const char *name) {
    io_printf(js, ",\"nodes\":[{\"name\":");
    io_json_string(js, name);
    if (l->plant_mesh >= 0) io_printf(js, ",\"mesh\":%d", l->plant_mesh);
    if (l->nsets) {
        io_printf(js, ",\"children\":[");
        for (int i = 0; i < l->nsets; i++) io_printf(js, "%s%d", i ? "," : "", 1 + i);
        io_put(js, "]", 1);
    }
    io_put(js, "}", 1);
    for (int i = 0; i < l->nsets; i++) {
        int a = l->set_accessor[i];
        io_printf(js, ",{\"name\":");
        io_json_string(js, l->sets[i].name);
        io_printf(js, ",\"mesh\":%d,\"extensions\":{\"EXT_mesh_gpu_instancing\":{\"attributes\":"
                      "{\"TRANSLATION\":%d,\"ROTATION\":%d,\"SCALE\":%d}}}}",
                  l->set_mesh[i], a, a + 1, a + 2);
    }
    io_put(js, "]", 1);
}

/* The JSON chunk, padded with spaces; without geometry, a scene with one empty node. */
static void write_json(IoBuf *js, const SylMesh *m, const Layout *l) {
    const char *name = m->name[0] ? m->name : "plant";
    io_printf(js, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"Sylva\"}");
    if (l->nsets) io_printf(js, ",\"extensionsUsed\":[\"EXT_mesh_gpu_instancing\"]");
    io_printf(js, ",\"scene\":0,\"scenes\":[{\"name\":");
    io_json_string(js, name);
    io_printf(js, ",\"nodes\":[0]}]");
    json_nodes(js, l, name);
    if (l->nmeshes) {
        io_printf(js, ",\"meshes\":[");
        for (int k = 0; k < l->nmeshes; k++) json_mesh(js, l, k, k == l->plant_mesh ? name : l->sets[k - (l->plant_mesh + 1)].name);
        io_put(js, "]", 1);
        json_materials(js, l);
        json_accessors(js, l);
        json_textures(js, l);
        glb_buffer_views(js, l->views, l->nviews, l->bin.len);
    }
    io_put(js, "}", 1);
    glb_pad(js, ' ');
}


int syl_write_glb_instanced(const SylMesh *m, const SylInstances *sets, int n, const char *path, FILE *diag) {
    Layout l = {.tex_of_kind = {-1, -1, -1, -1}, .plant_mesh = -1, .sets = sets};
    IoBuf js = {0};
    if (has_geometry(m)) l.mesh[l.plant_mesh = l.nmeshes++] = m;
    for (int i = 0; i < n && i < 256; i++)
        if (has_geometry(sets[i].proto) && sets[i].count) { /* an empty set is left out */
            l.set_mesh[l.nsets] = l.nmeshes;
            l.mesh[l.nmeshes++] = sets[i].proto;
            l.nsets++;
        }
    /* the sets kept are the first ones with geometry: compact them so index i is set i */
    SylInstances kept[256];
    int nk = 0;
    for (int i = 0; i < n && i < 256; i++)
        if (has_geometry(sets[i].proto) && sets[i].count) kept[nk++] = sets[i];
    l.sets = kept;
    l.views = malloc(sizeof *l.views * (size_t)(4 * l.nmeshes + 3 * l.nsets + KINDS));
    if (!l.views) l.bin.failed = true;
    for (int k = 0; k < l.nmeshes && l.views; k++) layout_attributes(l.mesh[k], &l, k);
    if (l.views) layout_instances(&l);
    int mat = 0, acc = 0; /* numbering, before the JSON refers to it */
    for (int k = 0; k < l.nmeshes; k++) {
        l.first_material[k] = mat, mat += l.mesh[k]->ngroups;
        l.first_accessor[k] = acc, acc += 3 + l.mesh[k]->ngroups;
    }
    for (int i = 0; i < l.nsets; i++) l.set_accessor[i] = acc, acc += 3;
    if (l.views) layout_textures(&l);
    glb_pad(&l.bin, 0);
    if (l.views) write_json(&js, m, &l);
    int status = glb_container(path, &js, &l.bin, l.nmeshes > 0, diag);
    io_free(&js);
    io_free(&l.bin);
    free(l.views);
    return status;
}

int syl_write_glb(const SylMesh *m, const char *path, FILE *diag) { return syl_write_glb_instanced(m, NULL, 0, path, diag); }
