/* The glTF 2.0 binary writer (.glb): BIN layout, JSON, and the container. */

/* One scene, one node named after the model, one mesh with one primitive per material
 * group. POSITION, NORMAL and TEXCOORD_0 are shared by the primitives; each has its own
 * range of indices. Materials are metallic-roughness with the
 * material's colour (converted to linear, as glTF wants) and, for bark, leaf and flower
 * kinds, the procedural texture (PNG, embedded in the BIN chunk). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "io/io_internal.h"
#include "sylva/texture.h"

enum { GLB_MAGIC = 0x46546C67, GLB_JSON = 0x4E4F534A, GLB_BIN = 0x004E4942 };
enum { ARRAY_BUFFER = 34962, ELEMENT_ARRAY_BUFFER = 34963, FLOAT = 5126, UNSIGNED_INT = 5125 };

static float srgb_to_linear(float c) {
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

static void put_u32(IoBuf *b, uint32_t u) {
    uint8_t p[4] = {(uint8_t)u, (uint8_t)(u >> 8), (uint8_t)(u >> 16), (uint8_t)(u >> 24)};
    io_put(b, p, 4);
}

/* Little-endian 32-bit words (floats or integers), whatever the host. */
static void put_words(IoBuf *b, const void *x, size_t n) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    io_put(b, x, 4 * n);
#else
    const uint32_t *w = x;
    for (size_t i = 0; i < n; i++) put_u32(b, w[i]);
#endif
}

static void pad(IoBuf *b, uint8_t with) {
    while (b->len % 4 && !b->failed) io_put(b, &with, 1); /* a failed buffer no longer grows */
}

/* "min":[..],"max":[..] of n vectors of k floats. */
static void min_max(IoBuf *j, const float *x, size_t n, int k) {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < k; c++) {
            float v = x[k * i + (size_t)c];
            if (v < lo[c]) lo[c] = v;
            if (v > hi[c]) hi[c] = v;
        }
    for (int w = 0; w < 2; w++) {
        io_printf(j, ",\"%s\":[", w ? "max" : "min");
        for (int c = 0; c < k; c++) io_printf(j, "%s%.17g", c ? "," : "", (double)(w ? hi[c] : lo[c]));
        io_put(j, "]", 1);
    }
}

typedef struct View {
    size_t offset, length;
    int target; /* 0: none */
} View;

/* The BIN chunk and how it is cut into buffer views: attributes, indices, then images. */
typedef struct Layout {
    IoBuf bin;
    View views[8];
    int nviews;
    int tex_of_kind[3], ntex, image_view[3]; /* texture of each kind (-1: none), its view */
} Layout;

static const int kinds[] = {SYL_MATERIAL_BARK, SYL_MATERIAL_LEAF, SYL_MATERIAL_FLOWER};

/* POSITION, NORMAL and TEXCOORD_0, then the indices: views 0 to 3. */
static void layout_attributes(const SylMesh *m, Layout *l) {
    const size_t nv = m->nverts;
    l->views[l->nviews++] = (View){l->bin.len, 12 * nv, ARRAY_BUFFER};
    put_words(&l->bin, m->pos, 3 * nv);
    l->views[l->nviews++] = (View){l->bin.len, 12 * nv, ARRAY_BUFFER};
    put_words(&l->bin, m->nrm, 3 * nv);
    l->views[l->nviews++] = (View){l->bin.len, 8 * nv, ARRAY_BUFFER};
    put_words(&l->bin, m->uv, 2 * nv);
    l->views[l->nviews++] = (View){l->bin.len, 4 * m->nidx, ELEMENT_ARRAY_BUFFER};
    put_words(&l->bin, m->idx, m->nidx);
}

/* One PNG texture per kind used (bark, leaf, flower), each in a view of its own. */
static void layout_textures(const SylMesh *m, Layout *l) {
    uint8_t *rgb = NULL;
    for (int k = 0; k < 3; k++) {
        bool used = false;
        for (int g = 0; g < m->ngroups && !used; g++) used = m->materials[m->groups[g].material].kind == kinds[k];
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
        pad(&l->bin, 0);
        l->tex_of_kind[k] = l->ntex++;
    }
    free(rgb);
}

/* The mesh's primitives (one per group) and their materials. */
static void json_mesh(IoBuf *js, const SylMesh *m, const Layout *l, const char *name) {
    io_printf(js, ",\"mesh\":0}],\"meshes\":[{\"name\":");
    io_json_string(js, name);
    io_printf(js, ",\"primitives\":[");
    for (int g = 0; g < m->ngroups; g++)
        io_printf(js, "%s{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2},\"indices\":%d,"
                      "\"material\":%d,\"mode\":4}",
                  g ? "," : "", 3 + g, g);
    io_printf(js, "]}],\"materials\":[");
    for (int g = 0; g < m->ngroups; g++) {
        const SylMaterial *mat = &m->materials[m->groups[g].material];
        char mname[32];
        io_material_name(m, m->groups[g].material, mname, sizeof mname);
        io_printf(js, "%s{\"name\":\"%s\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[%.6f,%.6f,%.6f,1]",
                  g ? "," : "", mname, srgb_to_linear(mat->rgb[0]), srgb_to_linear(mat->rgb[1]),
                  srgb_to_linear(mat->rgb[2]));
        int t = -1;
        for (int k = 0; k < 3; k++)
            if (mat->kind == kinds[k]) t = l->tex_of_kind[k];
        if (t >= 0) io_printf(js, ",\"baseColorTexture\":{\"index\":%d}", t);
        io_printf(js, ",\"metallicFactor\":0,\"roughnessFactor\":%s}}",
                  mat->kind == SYL_MATERIAL_BARK ? "0.95" : "0.7");
    }
    io_put(js, "]", 1);
}

/* Accessors: the three attributes, then each group's range of indices. */
static void json_accessors(IoBuf *js, const SylMesh *m) {
    io_printf(js, ",\"accessors\":[");
    static const char *const types[3] = {"VEC3", "VEC3", "VEC2"};
    const float *data[3] = {m->pos, m->nrm, m->uv};
    for (int a = 0; a < 3; a++) {
        io_printf(js, "%s{\"bufferView\":%d,\"componentType\":%d,\"count\":%zu,\"type\":\"%s\"", a ? "," : "", a,
                  FLOAT, m->nverts, types[a]);
        min_max(js, data[a], m->nverts, a == 2 ? 2 : 3);
        io_put(js, "}", 1);
    }
    for (int g = 0; g < m->ngroups; g++)
        io_printf(js, ",{\"bufferView\":3,\"byteOffset\":%zu,\"componentType\":%d,\"count\":%u,\"type\":\"SCALAR\"}",
                  (size_t)m->groups[g].first * 4, UNSIGNED_INT, m->groups[g].count);
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
    io_printf(js, "],\"textures\":[");
    for (t = 0; t < l->ntex; t++) io_printf(js, "%s{\"sampler\":0,\"source\":%d}", t ? "," : "", t);
    io_put(js, "]", 1);
}

/* The JSON chunk, padded with spaces; without geometry, a scene with one empty node. */
static void write_json(IoBuf *js, const SylMesh *m, const Layout *l, bool geometry) {
    const char *name = m->name[0] ? m->name : "plant";
    io_printf(js, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"Sylva\"},\"scene\":0,\"scenes\":[{\"name\":");
    io_json_string(js, name);
    io_printf(js, ",\"nodes\":[0]}],\"nodes\":[{\"name\":");
    io_json_string(js, name);
    if (geometry) {
        json_mesh(js, m, l, name);
        json_accessors(js, m);
        json_textures(js, l);
        io_printf(js, ",\"bufferViews\":[");
        for (int v = 0; v < l->nviews; v++) {
            io_printf(js, "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu", v ? "," : "", l->views[v].offset,
                      l->views[v].length);
            if (l->views[v].target) io_printf(js, ",\"target\":%d", l->views[v].target);
            io_put(js, "}", 1);
        }
        io_printf(js, "],\"buffers\":[{\"byteLength\":%zu}]}", l->bin.len);
    } else {
        io_printf(js, "}]}");
    }
    pad(js, ' ');
}

/* The GLB container: header, JSON chunk and (with geometry) BIN chunk, through a temporary
 * file. SYL_OK, SYL_ELIMIT or SYL_EIO, reported. */
static int write_container(const char *path, const IoBuf *js, const IoBuf *bin, bool geometry, FILE *diag) {
    int status = SYL_OK;
    if (js->failed || bin->failed) {
        if (diag) fprintf(diag, "sylva: error: out of memory writing '%s'\n", path);
        status = SYL_ELIMIT;
    } else if (12 + 8 + js->len + (geometry ? 8 + bin->len : 0) > UINT32_MAX) {
        if (diag) fprintf(diag, "sylva: error: '%s' would be larger than 4 GiB, the limit of .glb\n", path);
        status = SYL_ELIMIT;
    }
    OutFile fo;
    if (!status && !io_open(&fo, path, diag)) status = SYL_EIO;
    if (!status) {
        IoBuf head = {0};
        size_t total = 12 + 8 + js->len + (geometry ? 8 + bin->len : 0);
        put_u32(&head, GLB_MAGIC);
        put_u32(&head, 2);
        put_u32(&head, (uint32_t)total);
        put_u32(&head, (uint32_t)js->len);
        put_u32(&head, GLB_JSON);
        fwrite(head.data, 1, head.len, fo.f);
        fwrite(js->data, 1, js->len, fo.f);
        if (geometry) {
            head.len = 0;
            put_u32(&head, (uint32_t)bin->len);
            put_u32(&head, GLB_BIN);
            fwrite(head.data, 1, head.len, fo.f);
            fwrite(bin->data, 1, bin->len, fo.f);
        }
        if (head.failed && diag) fprintf(diag, "sylva: error: out of memory writing '%s'\n", path);
        if (head.failed) status = SYL_ELIMIT;
        io_free(&head);
        status = io_close(&fo, status, diag); /* also catches the fwrite failures above */
    }
    return status;
}

int syl_write_glb(const SylMesh *m, const char *path, FILE *diag) {
    Layout l = {.tex_of_kind = {-1, -1, -1}};
    IoBuf js = {0};
    bool geometry = m->nverts > 0 && m->nidx > 0 && m->ngroups > 0;
    if (geometry) {
        layout_attributes(m, &l);
        layout_textures(m, &l);
    }
    pad(&l.bin, 0);
    write_json(&js, m, &l, geometry);
    int status = write_container(path, &js, &l.bin, geometry, diag);
    io_free(&js);
    io_free(&l.bin);
    return status;
}
