/* The texture files beside an OBJ: one PNG per kind of textured material the mesh uses. */
#include <stdlib.h>
#include <string.h>

#include "io/io_internal.h"
#include "sylva/texture.h"

/* PREFIX_leafcard.png or PREFIX_leafcluster.png: the card or cluster texture, RGBA; own: a
 * further card shape's, PREFIX_leafcardSHAPE.png (a scene's plant with an outline of its own). */
static int write_card(int shape, bool cluster, bool own, const char *prefix, char *path, size_t n,
                      const SylSink *sink) {
    const int size = SYL_TEXTURE_SIZE;
    uint8_t *rgba = malloc((size_t)size * size * 4);
    IoBuf b = {0};
    if (own) snprintf(path, n, "%s_leafcard%d.png", prefix, shape);
    else snprintf(path, n, "%s_%s.png", prefix, cluster ? "leafcluster" : "leafcard");
    int status = SYL_OK;
    if (!rgba || !(cluster ? syl_leaf_draw_cluster(shape, size, rgba) : syl_leaf_draw_card(shape, size, rgba)) ||
        !io_png_rgba(&b, rgba, size, size)) {
        sink_error(sink, "out of memory writing '%s'", path);
        status = SYL_ELIMIT;
    }
    OutFile fo;
    if (!status && !io_open(&fo, path, sink)) status = SYL_EIO;
    if (!status) {
        fwrite(b.data, 1, b.len, fo.f);
        status = io_close(&fo, status, sink);
    }
    io_free(&b);
    free(rgba);
    return status;
}

/* The images of the model's own m's groups use, each copied as it was read (io_image_file). */
static int write_images(const SylMesh *m, const char *prefix, const SylSink *sink) {
    bool used[SYL_IMAGES_MAX] = {false};
    for (int g = 0; m && g < m->ngroups; g++)
        if (io_image(m, m->groups[g].material)) used[m->materials[m->groups[g].material].image - 1] = true;
    int status = SYL_OK;
    for (int k = 0; k < SYL_IMAGES_MAX && !status; k++) {
        if (!used[k]) continue;
        size_t n = strlen(prefix) + sizeof m->images->img[k].name + 16;
        char *path = malloc(n);
        if (!path) {
            sink_error(sink, "out of memory writing textures");
            return SYL_ELIMIT;
        }
        io_image_file(m, k, prefix, path, n);
        OutFile fo;
        if (!io_open(&fo, path, sink)) status = SYL_EIO;
        else {
            fwrite(m->images->img[k].png, 1, m->images->img[k].len, fo.f);
            status = io_close(&fo, SYL_OK, sink);
        }
        free(path);
    }
    return status;
}

int syl_mesh_write_textures(const SylMesh *m, const char *prefix, const SylSink *sink) {
    static const int kinds[] = {SYL_MATERIAL_BARK, SYL_MATERIAL_LEAF, SYL_MATERIAL_FLOWER, -1};
    const int size = SYL_TEXTURE_SIZE;
    uint8_t *img = malloc((size_t)size * size * 3);
    size_t n = strlen(prefix) + 24; /* "_leafcluster.png" */
    char *path = malloc(n);
    if (!img || !path) {
        free(img);
        free(path);
        sink_error(sink, "out of memory writing textures");
        return SYL_ELIMIT;
    }
    int status = SYL_OK;
    for (size_t k = 0; k < sizeof kinds / sizeof *kinds && !status; k++) {
        bool used = !m;
        for (int g = 0; m && g < m->ngroups && !used; g++)
            used = m->materials[m->groups[g].material].kind == kinds[k] && !io_image(m, m->groups[g].material);
        if (!used) continue;
        snprintf(path, n, "%s_%s.png", prefix, syl_texture_name(kinds[k]));
        if (syl_texture_draw(kinds[k], NULL, size, img)) {
            status = syl_png_write(path, img, size, size, sink);
        } else {
            sink_error(sink, "out of memory writing '%s'", path);
            status = SYL_ELIMIT;
        }
    }
    bool leaf = false, cluster = m && m->leaves == SYL_LEAVES_CLUSTERS;
    for (int g = 0; m && g < m->ngroups; g++) leaf |= m->materials[m->groups[g].material].kind == SYL_MATERIAL_LEAF;
    if (leaf && (m->leaves == SYL_LEAVES_CARDS || cluster) && !status)
        status = write_card(m->leaf_shape, cluster, false, prefix, path, n, sink);
    bool done[256] = {false}; /* the further shapes, once each */
    for (int g = 0; m && g < m->ngroups && !status; g++) {
        int k = m->groups[g].material, shape = syl_mesh_card_shape(m, k);
        if (m->materials[k].kind != SYL_MATERIAL_LEAF || m->leaves != SYL_LEAVES_CARDS || shape == m->leaf_shape ||
            done[shape] || io_image(m, k))
            continue;
        done[shape] = true;
        status = write_card(shape, false, true, prefix, path, n, sink);
    }
    if (!status && m) status = write_images(m, prefix, sink);
    free(img);
    free(path);
    return status;
}
