/* Appending one mesh to another (a scene's obstacles to its plants): vertices are
 * concatenated and triangles regrouped so that groups stay sorted by material, one each. */
#include <stdlib.h>
#include <string.h>

#include "mesh/store.h"

int syl_mesh_append(SylMesh *dst, const SylMesh *src) {
    if (!src || !src->nverts) return SYL_OK;
    size_t nv = dst->nverts + src->nverts, ni = dst->nidx + src->nidx;
    if (nv > UINT32_MAX) return SYL_ELIMIT;
    float *pos = malloc((3 * nv + 4) * sizeof *pos), *nrm = malloc(3 * nv * sizeof *nrm), *uv = malloc(2 * nv * sizeof *uv);
    uint32_t *idx = malloc((ni ? ni : 1) * sizeof *idx);
    SylMeshGroup *groups = malloc((size_t)(dst->ngroups + src->ngroups + 1) * sizeof *groups);
    if (!pos || !nrm || !uv || !idx || !groups) {
        free(pos), free(nrm), free(uv), free(idx), free(groups);
        return SYL_ELIMIT;
    }
    memcpy(pos, dst->pos, 3 * dst->nverts * sizeof *pos);
    memcpy(pos + 3 * dst->nverts, src->pos, 3 * src->nverts * sizeof *pos);
    memset(pos + 3 * nv, 0, 4 * sizeof *pos);
    memcpy(nrm, dst->nrm, 3 * dst->nverts * sizeof *nrm);
    memcpy(nrm + 3 * dst->nverts, src->nrm, 3 * src->nverts * sizeof *nrm);
    memcpy(uv, dst->uv, 2 * dst->nverts * sizeof *uv);
    memcpy(uv + 2 * dst->nverts, src->uv, 2 * src->nverts * sizeof *uv);
    int ng = 0;
    size_t at = 0;
    for (int m = 0; m < 256; m++) {
        size_t start = at;
        for (int g = 0; g < dst->ngroups; g++)
            if (dst->groups[g].material == m) {
                memcpy(idx + at, dst->idx + dst->groups[g].first, dst->groups[g].count * sizeof *idx);
                at += dst->groups[g].count;
            }
        for (int g = 0; g < src->ngroups; g++)
            if (src->groups[g].material == m) {
                for (uint32_t k = 0; k < src->groups[g].count; k++)
                    idx[at++] = src->idx[src->groups[g].first + k] + (uint32_t)dst->nverts;
                dst->materials[m] = src->materials[m];
                dst->double_sided[m] |= src->double_sided[m];
                if (src->card_shape[m]) dst->card_shape[m] = src->card_shape[m];
            }
        if (at > start) groups[ng++] = (SylMeshGroup){(uint32_t)start, (uint32_t)(at - start), (uint8_t)m};
    }
    if (!dst->images) dst->images = syl_images_ref(src->images); /* dst's images, else src's (obstacles have none) */
    if (dst->store && dst->store->block) free(dst->store->block), dst->store->block = NULL;
    else free(dst->pos), free(dst->nrm), free(dst->uv), free(dst->idx);
    free(dst->groups);
    free(dst->node); /* src's vertices have no nodes of dst's skeleton */
    dst->node = NULL;
    dst->pos = pos, dst->nrm = nrm, dst->uv = uv, dst->idx = idx, dst->groups = groups;
    dst->nverts = nv;
    mesh_mark_spare(dst); /* pos has 4 floats past the last vertex */
    dst->nidx = at;
    dst->ngroups = ng;
    if (src->nmaterials > dst->nmaterials) dst->nmaterials = src->nmaterials;
    return SYL_OK;
}
