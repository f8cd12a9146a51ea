/* The Wavefront OBJ writer, with its MTL library and textures. */

/* PATH (NAME.obj), NAME.mtl and NAME_bark.png, NAME_leaf.png, NAME_flower.png for the kinds of material it uses
 * (NAME_tex_FILE, a copy of each image file of the model's own it uses). One
 * `usemtl` per material group. OBJ's v runs up the picture, so v is written as 1 - v. */
#include <stdlib.h>
#include <string.h>

#include "io/io_internal.h"
#include "sylva/texture.h"
#include "util/numcache.h"
#include "util/numtext.h"

/* "dir/NAME.obj" -> "dir/NAME" (the caller frees). */
static char *strip_extension(const char *path) {
    char *s = strdup(path);
    if (!s) return NULL;
    char *dot = strrchr(s, '.');
    if (dot && !strchr(dot, '/')) *dot = 0;
    return s;
}

static const char *base_name(const char *path) {
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

static void write_mtl(const SylMesh *m, FILE *f, const char *stem) {
    char title[sizeof m->name];
    io_line_text(title, sizeof title, m->name, false);
    fprintf(f, "# Sylva %s: materials of %s\n", SYLVA_VERSION, title);
    for (int g = 0; g < m->ngroups; g++) {
        int k = m->groups[g].material;
        char name[32];
        io_material_name(m, k, name, sizeof name);
        const SylImage *img = io_image(m, k);
        static const float white[3] = {1, 1, 1}; /* an image of the model's own is the colour itself */
        const float *c = img ? white : m->materials[k].rgb;
        fprintf(f, "\nnewmtl %s\nKa 0 0 0\nKd %.4f %.4f %.4f\nKs 0 0 0\nNs 1\nd 1\nillum 1\n", name, c[0], c[1], c[2]);
        if (img) { /* its copy beside the MTL (syl_mesh_write_textures) */
            char file[sizeof img->name + 80];
            io_image_file(m, m->materials[k].image - 1, stem, file, sizeof file);
            fprintf(f, "map_Kd %s\n", file);
            if (img->alpha && m->materials[k].kind != SYL_MATERIAL_BARK) fprintf(f, "map_d %s\n", file);
            continue;
        }
        const char *tex = io_texture_kind(m, k);
        bool card = m->materials[k].kind == SYL_MATERIAL_LEAF &&
                    (m->leaves == SYL_LEAVES_CARDS || m->leaves == SYL_LEAVES_CLUSTERS);
        if (card) tex = m->leaves == SYL_LEAVES_CARDS ? "leafcard" : "leafcluster"; /* RGBA: silhouettes in alpha, read again by map_d */
        char own[24]; /* a card of a scene's plant whose outline is not the first's: its own */
        if (card && syl_mesh_card_shape(m, k) != m->leaf_shape)
            snprintf(own, sizeof own, "leafcard%d", syl_mesh_card_shape(m, k)), tex = own;
        if (tex) fprintf(f, "map_Kd %s_%s.png\n", stem, tex); /* the rest of the line: spaces work */
        if (card) fprintf(f, "map_d %s_%s.png\n", stem, tex);
    }
}

/* Vertices, UVs, normals and faces of all (m: one object; a scene: its objects parts[0..n),
 * numbered on from the last one's vertices), through a buffer; false when out of memory. */
static bool write_obj_body(const SylMesh *all, SylMesh *const *parts, int nparts, FILE *f, const char *stem) {
    enum { CHUNK = 1 << 18 };
    char *buf = malloc(CHUNK + 256), *p = buf;
    NumCache *cache = malloc(3 * sizeof *cache); /* positions, UVs, normals: each its own repeats */
    if (!buf || !cache) {
        free(buf), free(cache);
        return false;
    }
    for (int c = 0; c < 3; c++) numcache_init(&cache[c], "0", 1);
    /* mtllib takes the rest of the line (Blender, Assimp, trimesh), so a stem with spaces
     * works; object and material names are single words. */
    char comment[sizeof all->name], object[sizeof all->name];
    io_line_text(comment, sizeof comment, all->name, false);
    fprintf(f, "# Sylva %s: %s, %zu vertices, %zu triangles\nmtllib %s.mtl\n", SYLVA_VERSION, comment, all->nverts,
            all->nidx / 3, stem);
    size_t base = 0;
    for (int o = 0; o < (nparts ? nparts : 1); o++) {
    const SylMesh *m = nparts ? parts[o] : all;
    io_line_text(object, sizeof object, m->name[0] ? m->name : "plant", true);
    p += sprintf(p, "o %s\n", object); /* after the last object's faces, still in buf */
#define FLUSH()                                      \
    do {                                             \
        if (p - buf > CHUNK) {                       \
            fwrite(buf, 1, (size_t)(p - buf), f);    \
            p = buf;                                 \
        }                                            \
    } while (0)
    for (size_t i = 0; i < m->nverts; i++) {
        const float *v = m->pos + 3 * i;
        *p++ = 'v';
        for (int k = 0; k < 3; k++) *p++ = ' ', p = numcache_put(&cache[0], p, v[k], 7, io_float);
        *p++ = '\n';
        FLUSH();
    }
    for (size_t i = 0; i < m->nverts; i++) {
        const float *t = m->uv + 2 * i;
        *p++ = 'v', *p++ = 't', *p++ = ' ';
        p = numcache_put(&cache[1], p, t[0], 6, io_float);
        *p++ = ' ';
        p = numcache_put(&cache[1], p, 1.0f - t[1], 6, io_float);
        *p++ = '\n';
        FLUSH();
    }
    for (size_t i = 0; i < m->nverts; i++) {
        const float *n = m->nrm + 3 * i;
        *p++ = 'v', *p++ = 'n';
        for (int k = 0; k < 3; k++) *p++ = ' ', p = numcache_put(&cache[2], p, n[k], 6, io_float);
        *p++ = '\n';
        FLUSH();
    }
    for (int g = 0; g < m->ngroups; g++) {
        char name[32];
        io_material_name(m, m->groups[g].material, name, sizeof name);
        p += sprintf(p, "usemtl %s\n", name);
        const uint32_t *ix = m->idx + m->groups[g].first;
        for (uint32_t t = 0; t < m->groups[g].count; t += 3) {
            *p++ = 'f';
            for (int k = 0; k < 3; k++) {
                size_t x = base + ix[t + (uint32_t)k] + 1;
                *p++ = ' ';
#ifdef NUMTEXT_WORDS
                if (x < 100000000) { /* the digits built once in a register, stored three times */
                    uint64_t w = numtext_word8((uint32_t)x);
                    int lead = __builtin_ctzll(w ^ 0x3030303030303030ull) / 8, n = 8 - lead; /* x > 0 */
                    w >>= 8 * lead;
                    memcpy(p, &w, 8), p[n] = '/';
                    memcpy(p + n + 1, &w, 8), p[2 * n + 1] = '/';
                    memcpy(p + 2 * n + 2, &w, 8);
                    p += 3 * n + 2;
                    continue;
                }
#endif
                if (x <= UINT32_MAX) { /* the digits in place, without a 64-bit division */
                    int n = numtext_ndigits((uint32_t)x);
                    for (int r = 0; r < 3; r++, p += n + 1) numtext_digits(p + n, (uint32_t)x, n), p[n] = '/';
                    p--; /* the last '/' */
                    continue;
                }
                char num[24];
                int n = 0;
                do num[n++] = (char)('0' + x % 10), x /= 10;
                while (x);
                for (int r = 0; r < 3; r++) {
                    for (int d = n - 1; d >= 0; d--) *p++ = num[d];
                    if (r < 2) *p++ = '/';
                }
            }
            *p++ = '\n';
            FLUSH();
        }
    }
    base += m->nverts;
    }
#undef FLUSH
    fwrite(buf, 1, (size_t)(p - buf), f);
    free(buf);
    free(cache);
    return true;
}

static int write_obj(const SylMesh *m, SylMesh *const *parts, int nparts, const char *path, const SylSink *sink) {
    if (!strcmp(path, "-")) {
        sink_error(sink, "an OBJ cannot go to standard output: its .mtl is written beside it");
        return SYL_EUSAGE;
    }
    char *prefix = strip_extension(path);
    size_t n = prefix ? strlen(prefix) + 8 : 0;
    char *mtl = prefix ? malloc(n) : NULL;
    if (!prefix || !mtl) {
        free(prefix);
        sink_error(sink, "out of memory writing '%s'", path);
        return SYL_ELIMIT;
    }
    snprintf(mtl, n, "%s.mtl", prefix);
    const char *stem = base_name(prefix);
    /* Both files stay uncommitted until the textures are written: a failure leaves none. */
    OutFile fo, fm;
    int status = SYL_EIO;
    if (io_open(&fo, path, sink)) {
        status = SYL_OK;
        if (!write_obj_body(m, parts, nparts, fo.f, stem)) {
            sink_error(sink, "out of memory writing '%s'", path);
            status = SYL_ELIMIT;
        }
        fflush(fo.f); /* a write error is kept in fo.err and reported by io_close */
        if (!status && !fo.err) {
            if (io_open(&fm, mtl, sink)) {
                write_mtl(m, fm.f, stem);
                fflush(fm.f);
                if (!fm.err) status = syl_mesh_write_textures(m, prefix, sink);
                status = io_close(&fm, status, sink);
            } else {
                status = SYL_EIO;
            }
        }
        status = io_close(&fo, status, sink);
    }
    free(prefix);
    free(mtl);
    return status;
}

int syl_mesh_write_obj(const SylMesh *m, const char *path, const SylSink *sink) { return write_obj(m, NULL, 0, path, sink); }

int syl_mesh_write_obj_parts(const SylMesh *m, SylMesh *const *parts, int n, const char *path, const SylSink *sink) {
    return write_obj(m, parts, n, path, sink);
}
