/* Alpha-tested leaves: a ray passes through a leaf card or a leaf cluster's card where its
 * texture's alpha is below one half (glTF's alphaCutoff), as a viewer of the .glb draws it.
 * An Embree filter function on the mesh's geometry, with the cards' alpha drawn once. */
#include <stdlib.h>

#include "render/scene.h"
#include "sylva/texture.h"

enum { MASK_SIZE = 256 };

struct AlphaTest {
    const SylMesh *m;
    const uint8_t *tri_mat;
    const uint32_t (*halves)[2]; /* NULL, or the quads' triangles (an impostor bake, quads.c) */
    uint8_t which[256];          /* per material: 0 opaque, 1 card, 2 cluster */
    uint8_t mask[2][MASK_SIZE * MASK_SIZE]; /* 1 where alpha >= 1/2 */
};

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
        int w = at->which[at->tri_mat[tri]];
        if (!w) continue;
        float b0 = 1 - b1 - b2, uv[2];
        const uint32_t *t = at->m->idx + 3 * (size_t)tri;
        for (int c = 0; c < 2; c++)
            uv[c] = b0 * at->m->uv[2 * t[0] + c] + b1 * at->m->uv[2 * t[1] + c] + b2 * at->m->uv[2 * t[2] + c];
        int x = (int)(uv[0] * MASK_SIZE), y = (int)(uv[1] * MASK_SIZE); /* clamped, as the writer's sampler */
        x = x < 0 ? 0 : x >= MASK_SIZE ? MASK_SIZE - 1 : x;
        y = y < 0 ? 0 : y >= MASK_SIZE ? MASK_SIZE - 1 : y;
        if (!at->mask[w - 1][y * MASK_SIZE + x]) args->valid[i] = 0;
    }
}

int render_alpha_test(Scene *s, RTCGeometry g) {
    const SylMesh *m = s->m;
    bool cards = m->leaves == SYL_LEAVES_CARDS || m->leaves == SYL_LEAVES_INSTANCED_CARDS;
    bool clusters = m->leaves == SYL_LEAVES_CLUSTERS, any = false;
    for (int gi = 0; gi < m->ngroups; gi++) any |= m->materials[m->groups[gi].material].kind == SYL_MATERIAL_LEAF;
    if (!(cards || clusters) || !any) return SYL_OK;
    AlphaTest *at = calloc(1, sizeof *at);
    uint8_t *rgba = malloc(4 * MASK_SIZE * MASK_SIZE);
    bool ok = at && rgba && (clusters ? syl_leaf_cluster(m->leaf_shape, MASK_SIZE, rgba) : syl_leaf_card(m->leaf_shape, MASK_SIZE, rgba));
    if (ok) {
        at->m = m, at->tri_mat = s->tri_mat, at->halves = (const uint32_t (*)[2])s->quad_halves;
        for (int k = 0; k < 256; k++) at->which[k] = m->materials[k].kind == SYL_MATERIAL_LEAF ? (clusters ? 2 : 1) : 0;
        for (int p = 0; p < MASK_SIZE * MASK_SIZE; p++) at->mask[clusters][p] = rgba[4 * p + 3] >= 128;
        rtcSetGeometryUserData(g, at);
        rtcSetGeometryIntersectFilterFunction(g, filter);
        rtcSetGeometryOccludedFilterFunction(g, filter);
        s->alphatest = at;
    } else {
        free(at);
    }
    free(rgba);
    return ok ? SYL_OK : SYL_ELIMIT;
}
