/* Leaves as instances of one prototype leaf: where the mesher would copy a leaf, record its
 * place, frame and size instead (a writer puts them in EXT_mesh_gpu_instancing). The
 * prototype is made by the mesher itself from a one-leaf skeleton, so an instance's vertices
 * are the copied leaf's, moved. */
#include <stdlib.h>
#include <string.h>

#include <cglm/cglm.h>

#include "mesh/mesh_internal.h"

void syl_instances_free(SylInstances *sets, int n) {
    if (!sets) return;
    for (int i = 0; i < n; i++) {
        syl_mesh_free(sets[i].proto);
        free(sets[i].t);
        free(sets[i].r);
        free(sets[i].s);
        free(sets[i].node);
    }
    free(sets);
}

/* One leaf of size 1 at the origin (H = +x, L = +y), of the given material. */
static int prototype(const SylSkeleton *s, const SylMeshOptions *opt, int material, SylMesh **out) {
    SylSkeleton *one = syl_skeleton_new(s->name);
    if (!one) return SYL_ELIMIT;
    memcpy(one->materials, s->materials, sizeof one->materials);
    one->nmaterials = s->nmaterials;
    one->images = syl_images_ref(s->images);
    SylOrgan leaf = {.h = {1, 0, 0}, .l = {0, 1, 0}, .u = {0, 0, 1}, .size = 1, .node = -1,
                     .kind = SYL_KIND_LEAF, .material = (uint8_t)material};
    int status = syl_skeleton_add_organ(one, &leaf) < 0 ? SYL_ELIMIT : SYL_OK;
    SylMeshOptions o = *opt;
    o.leaves = opt->leaves == SYL_LEAVES_INSTANCED_CARDS ? SYL_LEAVES_CARDS : SYL_LEAVES_MESH;
    o.threads = 1;
    o.budget = NULL;
    if (!status) status = syl_mesh_build(one, &o, out);
    syl_skeleton_free(one);
    return status;
}

int syl_instances_build(const SylSkeleton *s, const SylMeshOptions *opt, SylInstances **out, int *n) {
    *out = NULL;
    *n = 0;
    size_t count[256] = {0};
    float h[3], l[3], u[3];
    for (size_t i = 0; i < s->norgans; i++)
        if (s->organs[i].kind == SYL_KIND_LEAF && mesh_organ_frame(&s->organs[i], h, l, u))
            count[s->organs[i].material]++;
    int nsets = 0, slot[256];
    for (int m = 0; m < 256; m++) slot[m] = count[m] ? nsets++ : -1;
    if (!nsets) return SYL_OK;
    SylInstances *sets = calloc((size_t)nsets, sizeof *sets);
    if (!sets) return SYL_ELIMIT;
    int status = SYL_OK;
    for (int m = 0; m < 256 && !status; m++) {
        if (slot[m] < 0) continue;
        SylInstances *set = &sets[slot[m]];
        snprintf(set->name, sizeof set->name, "%.48s_leaves%d", s->name[0] ? s->name : "plant", slot[m] & 255);
        set->t = malloc(count[m] * 3 * sizeof(float));
        set->r = malloc(count[m] * 4 * sizeof(float));
        set->s = malloc(count[m] * 3 * sizeof(float));
        if (opt->vertex_nodes) set->node = malloc(count[m] * sizeof *set->node);
        if (!set->t || !set->r || !set->s || (opt->vertex_nodes && !set->node)) status = SYL_ELIMIT;
        if (!status) status = prototype(s, opt, m, &set->proto);
    }
    for (size_t i = 0; i < s->norgans && !status; i++) {
        const SylOrgan *o = &s->organs[i];
        if (o->kind != SYL_KIND_LEAF || !mesh_organ_frame(o, h, l, u)) continue;
        SylInstances *set = &sets[slot[o->material]];
        size_t k = set->count++;
        mat3 rot; /* columns: where the prototype's x, y and z go */
        memcpy(rot[0], h, sizeof(vec3));
        memcpy(rot[1], l, sizeof(vec3));
        memcpy(rot[2], u, sizeof(vec3));
        versor q;
        glm_mat3_quat(rot, q);
        glm_quat_normalize(q);
        memcpy(set->t + 3 * k, o->pos, sizeof(vec3));
        memcpy(set->r + 4 * k, q, sizeof(versor));
        set->s[3 * k] = set->s[3 * k + 1] = set->s[3 * k + 2] = o->size;
        if (set->node) set->node[k] = o->node;
    }
    if (status) {
        syl_instances_free(sets, nsets);
        return status;
    }
    *out = sets;
    *n = nsets;
    return SYL_OK;
}

const char *const syl_leaves_names[SYL_LEAVES_MODES] = {"mesh", "cards", "instanced", "instanced-cards", "clusters"};
