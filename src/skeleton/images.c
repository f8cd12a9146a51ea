/* A skeleton's texture images, shared with its meshes, and the textures a model's lines give
 * its materials (skeleton.h: syl_skeleton_apply_textures). */
#include <stdlib.h>
#include <string.h>

#include "sylva/skeleton.h"
#include "util/rng.h"

SylImages *syl_images_ref(SylImages *im) {
    if (im) __atomic_add_fetch(&im->refs, 1, __ATOMIC_RELAXED);
    return im;
}

const SylImage *syl_material_image(const SylImages *im, const SylMaterial *m) {
    return im && m->image >= 1 && m->image <= im->n ? &im->img[m->image - 1] : NULL;
}

void syl_images_release(SylImages *im) {
    if (!im || __atomic_sub_fetch(&im->refs, 1, __ATOMIC_ACQ_REL) > 0) return;
    for (int i = 0; i < im->n; i++) free(im->img[i].png);
    free(im);
}

int syl_images_add(SylImages **into, const SylImage *g) {
    SylImages *im = *into;
    for (int k = 0; im && k < im->n; k++)
        if (im->img[k].len == g->len && !strcmp(im->img[k].name, g->name) && !memcmp(im->img[k].png, g->png, g->len))
            return k + 1;
    if (!im && (im = *into = calloc(1, sizeof *im))) im->refs = 1;
    if (!im || im->n == SYL_IMAGES_MAX) return 0;
    SylImage *c = &im->img[im->n];
    *c = *g;
    if (!(c->png = malloc(g->len ? g->len : 1))) return 0;
    memcpy(c->png, g->png, g->len);
    return ++im->n;
}

int syl_skeleton_apply_textures(SylSkeleton *sk, SylTextureSpec *spec, uint64_t seed) {
    if (!spec->images) return SYL_OK;
    syl_images_release(sk->images);
    sk->images = spec->images;
    spec->images = NULL;
    const int n0 = sk->nmaterials;
    for (int m = 0; m < n0; m++)
        if (sk->materials[m].kind == SYL_MATERIAL_BARK && spec->bark) {
            sk->materials[m].image = (uint8_t)spec->bark;
            sk->materials[m].tile[0] = spec->tile[0], sk->materials[m].tile[1] = spec->tile[1];
        }
    if (spec->nleaf <= 0) return SYL_OK;
    /* the leaf materials the leaves use, each copied once per further image */
    uint8_t used[256] = {0}, copy[256][SYL_IMAGES_MAX];
    for (size_t i = 0; i < sk->norgans; i++)
        if (sk->organs[i].kind == SYL_KIND_LEAF) used[sk->organs[i].material] = 1;
    for (int m = 0; m < 256; m++) {
        if (!used[m] || sk->materials[m].kind != SYL_MATERIAL_LEAF) continue;
        sk->materials[m].image = spec->leaf[0];
        copy[m][0] = (uint8_t)m;
        if (m >= sk->nmaterials) sk->nmaterials = m + 1;
        for (int k = 1; k < spec->nleaf; k++) {
            if (sk->nmaterials >= 256) return SYL_ELIMIT;
            int slot = sk->nmaterials++;
            sk->materials[slot] = sk->materials[m];
            sk->materials[slot].image = spec->leaf[k];
            copy[m][k] = (uint8_t)slot;
        }
    }
    /* a leaf's image by its own draw: the same whatever the order of the others */
    for (size_t i = 0; i < sk->norgans; i++) {
        SylOrgan *o = &sk->organs[i];
        if (o->kind != SYL_KIND_LEAF || sk->materials[o->material].kind != SYL_MATERIAL_LEAF) continue;
        Rng r = rng_stream(seed, 0, 0x7e47, i);
        o->material = copy[o->material][rng_next(&r) % (uint64_t)spec->nleaf];
    }
    return SYL_OK;
}
