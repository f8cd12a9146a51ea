/* The crossed billboards of an impostor as a chain's last level (sylva/impostor.h): `sylva mesh
 * --impostor/--billboards`, sylva view's far level and the Python package's lod= share it. */
#include "sylva/impostor.h"
#include "util/diag.h"

int syl_impostor_add_level(SylLodChain *c, const SylSkeleton *sk, const SylMeshOptions *mo, const SylImpostorOptions *io,
                           SylImpostor *imp) {
    if (!c->level[0].mesh->nidx) {
        sink_error(opt_sink(io), "the model draws nothing: there is no impostor to bake");
        return SYL_EMODEL;
    }
    /* LOD0's mesh leaves instanced leaves out (they are instances of the file): the picture
     * is baked from the plant meshed again with those leaves in it */
    const SylMesh *drawn = c->level[0].mesh;
    SylMesh *leafy = NULL;
    int status = SYL_OK;
    if (mo->leaves == SYL_LEAVES_INSTANCED || mo->leaves == SYL_LEAVES_INSTANCED_CARDS) {
        SylMeshOptions with = *mo;
        with.leaves = mo->leaves == SYL_LEAVES_INSTANCED_CARDS ? SYL_LEAVES_CARDS : SYL_LEAVES_MESH;
        with.vertex_nodes = 0;
        status = syl_mesh_build(sk, &with, &leafy);
        if (!status) drawn = leafy;
    }
    if (!status) status = syl_impostor_bake(drawn, io, imp);
    syl_mesh_free(leafy);
    if (status) { /* the mesher and the bake said why they ran out of memory */
        if (status != SYL_ELIMIT) sink_error(opt_sink(io), "cannot bake the impostor (bad request)");
        return status;
    }
    int k = c->n;
    c->level[k] = (SylLodLevel){.mesh = imp->bb_mesh, .coverage = syl_lod_coverage(k, k)};
    if (k > 0) c->level[k - 1].coverage = syl_lod_coverage(k - 1, k);
    c->n = k + 1;
    c->atlas = imp->bb_color;
    c->atlas_w = imp->bb_width;
    c->atlas_h = imp->view;
    c->atlas_material = SYL_IMPOSTOR_MATERIAL;
    imp->bb_mesh = NULL; /* the chain's now */
    return SYL_OK;
}
