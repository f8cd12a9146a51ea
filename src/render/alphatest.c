/* Alpha-tested leaves: a ray passes through a leaf card or a leaf cluster's card where its
 * texture's alpha is below one half (glTF's alphaCutoff), as a viewer of the .glb draws it.
 * An Embree filter function on the mesh's geometry, with the cards' alpha drawn once: on the
 * one mesh of a render, or on each prototype of an instanced one (instances.c), where
 * Embree calls the filter of the instanced geometry with its own user data. A leaf of an
 * image of the model's own is cut by that image's alpha, at its own pixels. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "render/scene.h"
#include "sylva/texture.h"
#include "util/pngin.h"

enum { MASK_SIZE = 256 };

struct AlphaTest {
    const SylMesh *m;
    const uint8_t *tri_mat;
    const uint32_t (*halves)[2]; /* NULL, or the quads' triangles (an impostor bake, quads.c) */
    uint8_t which[256];          /* per material: 1 a leaf card (or cluster card), 0 opaque */
    uint8_t mask[MASK_SIZE * MASK_SIZE]; /* 1 where the cards' alpha >= 1/2 */
    int8_t image[256];                   /* per material: its image's mask below, -1 none */
    uint8_t *imask[SYL_IMAGES_MAX];      /* an image's alpha >= 1/2, its w x h pixels */
    int iw[SYL_IMAGES_MAX], ih[SYL_IMAGES_MAX];
};

void render_alpha_free(AlphaTest *at) {
    if (!at) return;
    for (int k = 0; k < SYL_IMAGES_MAX; k++) free(at->imask[k]);
    free(at);
}

/* Whether (u, v) of image k is opaque: its nearest pixel, clamped (the writer's sampler). */
static bool image_opaque(const AlphaTest *at, int k, const float uv[2]) {
    int w = at->iw[k], h = at->ih[k], x = (int)floorf(uv[0] * (float)w), y = (int)floorf(uv[1] * (float)h);
    x = x < 0 ? 0 : x >= w ? w - 1 : x;
    y = y < 0 ? 0 : y >= h ? h - 1 : y;
    return at->imask[k][(size_t)y * w + x];
}

static void filter(const struct RTCFilterFunctionNArguments *args) {
    const AlphaTest *at = args->geometryUserPtr;
    const unsigned N = args->N;
    const float *hit = (const float *)args->hit;
    const unsigned *prim = (const unsigned *)args->hit + 5 * N;
    for (unsigned i = 0; i < N; i++) {
        if (args->valid[i] != -1) continue;
        unsigned tri = prim[i];
        float b1 = hit[3 * N + i], b2 = hit[4 * N + i];
        if (at->halves) render_quad_hit(at->halves, &tri, &b1, &b2); /* a quad's hit: its triangle's */
        int mat = at->tri_mat[tri];
        if (!at->which[mat] && at->image[mat] < 0) continue;
        float b0 = 1 - b1 - b2, uv[2];
        const uint32_t *t = at->m->idx + 3 * (size_t)tri;
        for (int c = 0; c < 2; c++)
            uv[c] = b0 * at->m->uv[2 * t[0] + c] + b1 * at->m->uv[2 * t[1] + c] + b2 * at->m->uv[2 * t[2] + c];
        if (at->image[mat] >= 0) {
            if (!image_opaque(at, at->image[mat], uv)) args->valid[i] = 0;
            continue;
        }
        int x = (int)(uv[0] * MASK_SIZE), y = (int)(uv[1] * MASK_SIZE); /* clamped, as the writer's sampler */
        x = x < 0 ? 0 : x >= MASK_SIZE ? MASK_SIZE - 1 : x;
        y = y < 0 ? 0 : y >= MASK_SIZE ? MASK_SIZE - 1 : y;
        if (!at->mask[y * MASK_SIZE + x]) args->valid[i] = 0;
    }
}

int render_alpha_attach(const SylMesh *m, const uint8_t *tri_mat, const uint32_t (*halves)[2], RTCGeometry g,
                        AlphaTest **out) {
    *out = NULL;
    bool cards = m->leaves == SYL_LEAVES_CARDS || m->leaves == SYL_LEAVES_INSTANCED_CARDS;
    bool clusters = m->leaves == SYL_LEAVES_CLUSTERS, any = false, images = false;
    int8_t image[256];
    for (int k = 0; k < 256; k++) { /* leaves of an image with alpha */
        int kind = m->materials[k].kind, i = kind == SYL_MATERIAL_LEAF || kind == SYL_MATERIAL_FLOWER ? render_material_image(m, k) : -1;
        image[k] = (int8_t)(i >= 0 && m->images->img[i].alpha ? i : -1);
    }
    for (int gi = 0; gi < m->ngroups; gi++) {
        int k = m->groups[gi].material;
        any |= m->materials[k].kind == SYL_MATERIAL_LEAF && image[k] < 0;
        images |= image[k] >= 0;
    }
    if (!((cards || clusters) && any) && !images) return SYL_OK;
    AlphaTest *at = calloc(1, sizeof *at);
    uint8_t *rgba = malloc(4 * MASK_SIZE * MASK_SIZE);
    bool ok = at && rgba && (!(cards || clusters) || (clusters ? syl_leaf_draw_cluster(m->leaf_shape, MASK_SIZE, rgba)
                                                                : syl_leaf_draw_card(m->leaf_shape, MASK_SIZE, rgba)));
    for (int k = 0; k < 256 && ok; k++) {
        int i = image[k];
        if (i < 0 || at->imask[i]) continue;
        const SylImage *g = &m->images->img[i];
        uint8_t *px = NULL;
        bool alpha;
        char why[160];
        ok = pngin_decode(g->png, g->len, &at->iw[i], &at->ih[i], &alpha, &px, why, sizeof why) &&
             (at->imask[i] = malloc((size_t)at->iw[i] * at->ih[i])) != NULL;
        for (size_t p = 0; ok && p < (size_t)at->iw[i] * at->ih[i]; p++) at->imask[i][p] = px[4 * p + 3] >= 128;
        free(px);
    }
    if (ok) {
        at->m = m, at->tri_mat = tri_mat, at->halves = halves;
        memcpy(at->image, image, sizeof image);
        for (int k = 0; k < 256; k++) at->which[k] = (cards || clusters) && m->materials[k].kind == SYL_MATERIAL_LEAF;
        for (int p = 0; p < MASK_SIZE * MASK_SIZE; p++) at->mask[p] = rgba[4 * p + 3] >= 128;
        rtcSetGeometryUserData(g, at);
        rtcSetGeometryIntersectFilterFunction(g, filter);
        rtcSetGeometryOccludedFilterFunction(g, filter);
        *out = at;
    } else {
        render_alpha_free(at);
    }
    free(rgba);
    return ok ? SYL_OK : SYL_ELIMIT;
}

int render_alpha_test(Scene *s, RTCGeometry g) {
    return render_alpha_attach(s->m, s->tri_mat, (const uint32_t (*)[2])s->quad_halves, g, &s->alphatest);
}
