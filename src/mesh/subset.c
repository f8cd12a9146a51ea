/* A scene's objects (syl_mesh_split): each plant's and each obstacle's triangles as a mesh of
 * its own, for writers that keep them apart (an OBJ's `o`, a glTF node each). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/mesh_internal.h"
#include "mesh/store.h"

/* The triangles of m whose part[t] is k, their vertices renumbered in order of first use. */
static SylMesh *subset(const SylMesh *m, const int *part, int k, const char *name) {
    SylMesh *s = calloc(1, sizeof *s);
    uint32_t *map = malloc((m->nverts + 1) * sizeof *map);
    size_t ntri = 0;
    for (size_t t = 0; t < m->nidx / 3; t++) ntri += part[t] == k;
    if (s) {
        s->pos = malloc((3 * 3 * ntri + 4) * sizeof *s->pos); /* at most 3 vertices a triangle */
        s->nrm = malloc(3 * 3 * ntri * sizeof *s->nrm + 1);
        s->uv = m->uv ? malloc(2 * 3 * ntri * sizeof *s->uv + 1) : NULL;
        s->idx = malloc(3 * ntri * sizeof *s->idx + 1);
        s->groups = malloc((size_t)(m->ngroups + 1) * sizeof *s->groups);
    }
    if (!s || !map || !s->pos || !s->nrm || (m->uv && !s->uv) || !s->idx || !s->groups) {
        free(map);
        syl_mesh_free(s);
        return NULL;
    }
    for (size_t v = 0; v < m->nverts; v++) map[v] = UINT32_MAX;
    for (int g = 0; g < m->ngroups; g++) {
        const SylMeshGroup *gr = &m->groups[g];
        size_t first = s->nidx;
        for (uint32_t i = 0; i < gr->count; i += 3) {
            size_t t = (gr->first + i) / 3;
            if (part[t] != k) continue;
            for (int c = 0; c < 3; c++) {
                uint32_t v = m->idx[gr->first + i + (uint32_t)c];
                if (map[v] == UINT32_MAX) {
                    size_t w = s->nverts++;
                    map[v] = (uint32_t)w;
                    memcpy(s->pos + 3 * w, m->pos + 3 * v, 3 * sizeof *s->pos);
                    memcpy(s->nrm + 3 * w, m->nrm + 3 * v, 3 * sizeof *s->nrm);
                    if (m->uv) memcpy(s->uv + 2 * w, m->uv + 2 * v, 2 * sizeof *s->uv);
                }
                s->idx[s->nidx++] = map[v];
            }
        }
        if (s->nidx > first)
            s->groups[s->ngroups++] = (SylMeshGroup){.first = (uint32_t)first, .count = (uint32_t)(s->nidx - first),
                                                     .material = gr->material};
    }
    memset(s->pos + 3 * s->nverts, 0, 4 * sizeof *s->pos); /* Embree reads 16 bytes */
    mesh_mark_spare(s);
    memcpy(s->materials, m->materials, sizeof s->materials);
    s->images = syl_images_ref(m->images);
    memcpy(s->double_sided, m->double_sided, sizeof s->double_sided);
    s->nmaterials = m->nmaterials, s->leaves = m->leaves, s->leaf_shape = m->leaf_shape;
    memcpy(s->card_shape, m->card_shape, sizeof s->card_shape);
    snprintf(s->name, sizeof s->name, "%s", name);
    free(map);
    return s;
}

/* Which part triangle t of m is: its first vertex made for a node, by the parts' first nodes. */
static int plant_of(const SylMesh *m, const SylSkeleton *sk, size_t t) {
    int32_t node = -1;
    for (int c = 0; c < 3 && node < 0; c++) node = m->node[m->idx[3 * t + (size_t)c]];
    int k = 0;
    for (int i = 0; i < sk->nparts; i++)
        if (!sk->parts[i].obstacle && node >= 0 && sk->parts[i].first_node <= (size_t)node) k = i;
    return k;
}

int syl_mesh_split(const SylMesh *plants, const SylMesh *obstacles, const SylSkeleton *sk, SylMesh ***out, int *n) {
    *out = NULL, *n = 0;
    if (!sk->nparts || !plants->node || (obstacles && !obstacles->node)) return SYL_OK;
    SylMesh **parts = calloc((size_t)sk->nparts, sizeof *parts);
    int *pp = malloc((plants->nidx / 3 + 1) * sizeof *pp);
    int *po = obstacles ? malloc((obstacles->nidx / 3 + 1) * sizeof *po) : NULL;
    int st = parts && pp && (!obstacles || po) ? SYL_OK : SYL_ELIMIT;
    for (size_t t = 0; !st && t < plants->nidx / 3; t++) pp[t] = plant_of(plants, sk, t);
    for (size_t t = 0; !st && obstacles && t < obstacles->nidx / 3; t++) {
        int k = obstacles->node[obstacles->idx[3 * t]] + 1, i = 0;
        while (i < sk->nparts && sk->parts[i].obstacle != k) i++;
        po[t] = i;
    }
    for (int i = 0; !st && i < sk->nparts; i++) {
        const SylMesh *from = sk->parts[i].obstacle ? obstacles : plants;
        if (!from) continue; /* an obstacle of no triangles */
        parts[*n] = subset(from, sk->parts[i].obstacle ? po : pp, i, sk->parts[i].name);
        if (!parts[*n]) st = SYL_ELIMIT;
        else if (parts[*n]->nidx) (*n)++;
        else syl_mesh_free(parts[*n]), parts[*n] = NULL;
    }
    free(pp), free(po);
    if (st) {
        syl_mesh_parts_free(parts, *n);
        *n = 0;
        return st;
    }
    *out = parts;
    return SYL_OK;
}

void syl_mesh_parts_free(SylMesh **parts, int n) {
    for (int i = 0; parts && i < n; i++) syl_mesh_free(parts[i]);
    free(parts);
}
