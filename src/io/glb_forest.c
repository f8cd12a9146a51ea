/* glb_write_forest: a ground mesh and sets of instances in one .glb, the sets that share a
 * prototype sharing its mesh (a forest's cells: docs/ecosystem.md#gltf). */
#include <stdlib.h>
#include <string.h>

#include "io/glb.h"

typedef struct Forest {
    const SylMesh *mesh[257]; /* distinct meshes: the ground first (when it has triangles) */
    int nmeshes, ground;
    int set_mesh[4096];
    int first_view[257], first_acc[257], first_mat[257], set_view0, set_acc0;
    bool uv[257];                                     /* mesh k has UVs (an accessor after NORMAL) */
    int tex_of[GLB_SLOTS], image_view[GLB_SLOTS + SYL_IMAGES_MAX], image_slot[GLB_SLOTS + SYL_IMAGES_MAX], ntex; /* as a tree's file */
    /* the images of the models' own the looks wear (io_image), each once however many looks
     * read it (one file, the same bytes): then a texture each, after the slots' */
    const SylImage *image[SYL_IMAGES_MAX];
    bool image_leaf[SYL_IMAGES_MAX]; /* a leaf wears it: clamped, not repeated */
    int nimages;
    View *views;
    int nviews;
    IoBuf bin;
    SylTextureCache *tc; /* may be NULL */
} Forest;

static bool drawable(const SylMesh *m) { return m && m->nverts && m->nidx && m->ngroups; }

static int mesh_index(Forest *f, const SylMesh *m) {
    for (int k = 0; k < f->nmeshes; k++)
        if (f->mesh[k] == m) return k;
    if (f->nmeshes == 257) return -1;
    f->mesh[f->nmeshes] = m;
    return f->nmeshes++;
}

static void view(Forest *f, const void *x, size_t words, int target) {
    size_t at = f->bin.len;
    glb_words(&f->bin, x, words);
    f->views[f->nviews++] = (View){.offset = at, .length = words * 4, .target = target};
}

/* The index in f->image of the image mesh k's material i wears; -1 none (or no room). */
static int image_of(Forest *f, int k, int i) {
    const SylImage *g = f->uv[k] ? io_image(f->mesh[k], i) : NULL;
    if (!g) return -1;
    int j = 0;
    while (j < f->nimages && !(f->image[j]->len == g->len && !strcmp(f->image[j]->name, g->name) &&
                               !memcmp(f->image[j]->png, g->png, g->len)))
        j++;
    if (j == f->nimages) {
        if (j == SYL_IMAGES_MAX) return -1;
        f->image[f->nimages++] = g;
    }
    if (f->mesh[k]->materials[i].kind != SYL_MATERIAL_BARK) f->image_leaf[j] = true;
    return j;
}

/* One picture per texture slot the meshes' materials use, and one per image of the models'
 * own (its file's bytes), each in a view of its own. */
static bool textures(Forest *f) {
    int shape[GLB_SLOTS] = {0};
    for (int k = 0; k < GLB_SLOTS; k++) f->tex_of[k] = -1;
    for (int k = 0; k < f->nmeshes; k++)
        for (int g = 0; f->uv[k] && g < f->mesh[k]->ngroups; g++) {
            int i = f->mesh[k]->groups[g].material, slot = glb_slot(f->mesh[k], i);
            if (image_of(f, k, i) >= 0) continue;
            if (slot >= 0) f->tex_of[slot] = 0, shape[slot] = f->mesh[k]->leaf_shape;
        }
    GlbPixels px = {0};
    for (int k = 0; k < GLB_SLOTS; k++) {
        if (f->tex_of[k] < 0) continue;
        glb_pad(&f->bin, 0);
        size_t at = f->bin.len;
        if (!glb_slot_png_cached(f->tc, &f->bin, k, shape[k], &px)) {
            glb_pixels_free(&px);
            return false;
        }
        f->image_view[f->ntex] = f->nviews, f->image_slot[f->ntex] = k, f->tex_of[k] = f->ntex++;
        f->views[f->nviews++] = (View){.offset = at, .length = f->bin.len - at};
    }
    glb_pixels_free(&px);
    for (int j = 0; j < f->nimages; j++) { /* the file's bytes as they are */
        glb_pad(&f->bin, 0);
        f->image_view[f->ntex] = f->nviews, f->image_slot[f->ntex++] = GLB_SLOTS + j;
        f->views[f->nviews++] = (View){.offset = f->bin.len, .length = f->image[j]->len};
        io_put(&f->bin, f->image[j]->png, f->image[j]->len);
    }
    return !f->bin.failed;
}

static void json(IoBuf *js, Forest *f, const SylInstances *sets, const char *const *extras, int n) {
    io_printf(js, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"Sylva\"},\"extensionsUsed\":"
                  "[\"EXT_mesh_gpu_instancing\"],\"scene\":0,\"scenes\":[{\"nodes\":[");
    int nodes = (f->ground >= 0) + n;
    for (int i = 0; i < nodes; i++) io_printf(js, "%s%d", i ? "," : "", i);
    io_printf(js, "]}],\"nodes\":[");
    int node = 0;
    if (f->ground >= 0) io_printf(js, "{\"name\":\"terrain\",\"mesh\":%d}", f->ground), node++;
    for (int i = 0; i < n; i++) {
        int a = f->set_acc0 + 3 * i;
        io_printf(js, "%s{\"name\":", node++ ? "," : "");
        io_json_string(js, sets[i].name);
        io_printf(js, ",\"mesh\":%d,\"extensions\":{\"EXT_mesh_gpu_instancing\":{\"attributes\":"
                      "{\"TRANSLATION\":%d,\"ROTATION\":%d,\"SCALE\":%d}}}",
                  f->set_mesh[i], a, a + 1, a + 2);
        if (extras && extras[i]) io_printf(js, ",\"extras\":%s", extras[i]);
        io_put(js, "}", 1);
    }
    io_printf(js, "],\"meshes\":[");
    for (int k = 0; k < f->nmeshes; k++) {
        const SylMesh *m = f->mesh[k];
        io_printf(js, "%s{\"name\":", k ? "," : "");
        io_json_string(js, m->name[0] ? m->name : "mesh");
        io_printf(js, ",\"primitives\":[");
        int a = f->first_acc[k], uv = f->uv[k];
        for (int g = 0; g < m->ngroups; g++) {
            io_printf(js, "%s{\"attributes\":{\"POSITION\":%d,\"NORMAL\":%d", g ? "," : "", a, a + 1);
            if (uv) io_printf(js, ",\"TEXCOORD_0\":%d", a + 2);
            io_printf(js, "},\"indices\":%d,\"material\":%d,\"mode\":4}", a + 2 + uv + g, f->first_mat[k] + g);
        }
        io_printf(js, "]}");
    }
    io_printf(js, "],\"materials\":[");
    for (int k = 0; k < f->nmeshes; k++)
        for (int g = 0; g < f->mesh[k]->ngroups; g++) { /* named and textured as a tree's own file */
            const SylMesh *m = f->mesh[k];
            int i = m->groups[g].material, slot = f->uv[k] ? glb_slot(m, i) : -1, j = image_of(f, k, i);
            static const float white[3] = {1, 1, 1}; /* an image of the model's own is the colour itself */
            const float *c = j >= 0 ? white : m->materials[i].rgb;
            char name[32];
            if (k == f->ground) snprintf(name, sizeof name, g ? "terrain%d" : "terrain", g);
            else io_material_name(m, i, name, sizeof name);
            io_printf(js, "%s{\"name\":\"%s\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[%.4f,%.4f,%.4f,1]",
                      k || g ? "," : "", name, glb_linear(c[0]), glb_linear(c[1]), glb_linear(c[2]));
            if (j >= 0) io_printf(js, ",\"baseColorTexture\":{\"index\":%d}", f->ntex - f->nimages + j);
            else if (slot >= 0) io_printf(js, ",\"baseColorTexture\":{\"index\":%d}", f->tex_of[slot]);
            io_printf(js, ",\"metallicFactor\":0,\"roughnessFactor\":0.9},\"doubleSided\":true");
            if (j >= 0 ? f->image_leaf[j] && f->image[j]->alpha : slot == GLB_CARD || slot == GLB_CLUSTER)
                io_printf(js, ",\"alphaMode\":\"MASK\",\"alphaCutoff\":0.5");
            io_put(js, "}", 1);
        }
    io_printf(js, "],\"accessors\":[");
    bool first = true;
    for (int k = 0; k < f->nmeshes; k++) {
        const SylMesh *m = f->mesh[k];
        int v = f->first_view[k];
        io_printf(js, "%s{\"bufferView\":%d,\"componentType\":%d,\"count\":%zu,\"type\":\"VEC3\"", first ? "" : ",", v,
                  FLOAT, m->nverts);
        glb_min_max(js, m->pos, m->nverts, 3);
        io_printf(js, "},{\"bufferView\":%d,\"componentType\":%d,\"count\":%zu,\"type\":\"VEC3\"}", v + 1, FLOAT,
                  m->nverts);
        if (f->uv[k])
            io_printf(js, ",{\"bufferView\":%d,\"componentType\":%d,\"count\":%zu,\"type\":\"VEC2\"}", v + 2, FLOAT,
                      m->nverts);
        for (int g = 0; g < m->ngroups; g++)
            io_printf(js, ",{\"bufferView\":%d,\"byteOffset\":%zu,\"componentType\":%d,\"count\":%u,\"type\":\"SCALAR\"}",
                      v + 2 + f->uv[k], (size_t)m->groups[g].first * 4, UNSIGNED_INT, m->groups[g].count);
        first = false;
    }
    for (int i = 0; i < n; i++) {
        int v = f->set_view0 + 3 * i;
        size_t c = sets[i].count;
        io_printf(js, "%s{\"bufferView\":%d,\"componentType\":%d,\"count\":%zu,\"type\":\"VEC3\"", first ? "" : ",", v,
                  FLOAT, c);
        glb_min_max(js, sets[i].t, c, 3);
        io_printf(js, "},{\"bufferView\":%d,\"componentType\":%d,\"count\":%zu,\"type\":\"VEC4\"}", v + 1, FLOAT, c);
        io_printf(js, ",{\"bufferView\":%d,\"componentType\":%d,\"count\":%zu,\"type\":\"VEC3\"}", v + 2, FLOAT, c);
        first = false;
    }
    io_put(js, "]", 1);
    if (f->ntex) { /* as a tree's file: tiled bark and leaves, clamped cards */
        io_printf(js, ",\"samplers\":[{\"magFilter\":9729,\"minFilter\":9987,\"wrapS\":10497,\"wrapT\":10497},"
                      "{\"magFilter\":9729,\"minFilter\":9987,\"wrapS\":33071,\"wrapT\":33071}],\"images\":[");
        for (int t = 0; t < f->ntex; t++) {
            int k = f->image_slot[t];
            io_printf(js, "%s{\"name\":", t ? "," : "");
            io_json_string(js, k >= GLB_SLOTS ? f->image[k - GLB_SLOTS]->name : glb_slot_name(k));
            io_printf(js, ",\"bufferView\":%d,\"mimeType\":\"image/png\"}", f->image_view[t]);
        }
        io_printf(js, "],\"textures\":[");
        for (int t = 0; t < f->ntex; t++) {
            int k = f->image_slot[t];
            io_printf(js, "%s{\"sampler\":%d,\"source\":%d}", t ? "," : "",
                      k >= GLB_SLOTS ? f->image_leaf[k - GLB_SLOTS] : k >= GLB_CARD, t);
        }
        io_put(js, "]", 1);
    }
    glb_buffer_views(js, f->views, f->nviews, f->bin.len);
    io_put(js, "}", 1);
    glb_pad(js, ' ');
}

int glb_write_forest(const SylMesh *ground, const SylInstances *sets, const char *const *extras, int n,
                     SylTextureCache *tc, const char *path, const SylSink *sink) {
    Forest *f = calloc(1, sizeof *f);
    if (!f) return SYL_ELIMIT;
    f->ground = -1, f->tc = tc;
    if (n < 0 || n > 4096) {
        sink_error(sink, "glb: %d sets of instances (at most 4096)", n);
        free(f);
        return SYL_EUSAGE;
    }
    if (drawable(ground)) f->ground = mesh_index(f, ground);
    for (int i = 0; i < n; i++) {
        f->set_mesh[i] = drawable(sets[i].proto) && sets[i].count ? mesh_index(f, sets[i].proto) : -1;
        if (f->set_mesh[i] < 0) {
            sink_error(sink, "glb: set '%s' has no mesh or no instances", sets[i].name);
            free(f);
            return SYL_EUSAGE;
        }
    }
    f->views = malloc(sizeof *f->views * (size_t)(4 * f->nmeshes + 3 * n + GLB_SLOTS + SYL_IMAGES_MAX + 1));
    int st = SYL_ELIMIT;
    if (f->views) {
        int acc = 0, mat = 0;
        for (int k = 0; k < f->nmeshes; k++) {
            const SylMesh *m = f->mesh[k];
            f->first_view[k] = f->nviews, f->first_acc[k] = acc, f->first_mat[k] = mat;
            f->uv[k] = m->uv != NULL;
            acc += 2 + f->uv[k] + m->ngroups, mat += m->ngroups;
            view(f, m->pos, 3 * m->nverts, ARRAY_BUFFER);
            if (m->nrm) view(f, m->nrm, 3 * m->nverts, ARRAY_BUFFER);
            else { /* glTF wants what it is told: up, when the mesh has no normals */
                size_t at = f->bin.len;
                for (size_t i = 0; i < m->nverts; i++) glb_words(&f->bin, (const float[3]){0, 1, 0}, 3);
                f->views[f->nviews++] = (View){.offset = at, .length = 12 * m->nverts, .target = ARRAY_BUFFER};
            }
            if (f->uv[k]) view(f, m->uv, 2 * m->nverts, ARRAY_BUFFER);
            view(f, m->idx, m->nidx, ELEMENT_ARRAY_BUFFER);
        }
        f->set_view0 = f->nviews, f->set_acc0 = acc;
        for (int i = 0; i < n; i++) {
            view(f, sets[i].t, 3 * sets[i].count, 0);
            view(f, sets[i].r, 4 * sets[i].count, 0);
            view(f, sets[i].s, 3 * sets[i].count, 0);
        }
        st = textures(f) ? SYL_OK : SYL_ELIMIT;
        glb_pad(&f->bin, 0);
        IoBuf js = {0};
        json(&js, f, sets, extras, n);
        if (!st) st = glb_container(path, &js, &f->bin, f->nmeshes > 0, sink);
        io_free(&js);
    }
    io_free(&f->bin);
    free(f->views);
    free(f);
    return st;
}
