/* sylva mesh: derive a model, draw it with the turtle, mesh it and write .glb, .obj or .ply. */
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli/cli.h"
#include "sylva/mesh.h"

const CliCommand cli_mesh_command = {
    .name = "mesh",
    .what = "draw a model and write a triangle mesh (.glb, .obj, .ply)",
    .run = cmd_mesh,
    .usage = "sylva mesh FILE[:Model] -o OUT.{glb,obj,ply} [options]",
    .about = "Derive the model, draw it with the 3D turtle and write a triangle mesh: a closed tube\n"
             "along every axis (rotation-minimising frames, end caps, smooth normals, bark UVs),\n"
             "leaves and polygons as double-sided faces, one material group per colour. The format\n"
             "follows the extension: glTF 2.0 binary (.glb), Wavefront OBJ with NAME.mtl and\n"
             "NAME_bark.png etc. (.obj), or binary PLY (.ply).\n",
    .options = (const CliUse[]){
        {.option = CLI_OPT_OUTPUT, .help = "the mesh file (required)"},
        {.option = CLI_OPT_SIDES},
        {.option = CLI_OPT_MIN_SIDES},
        {.option = CLI_OPT_RADIUS},
        {.option = CLI_OPT_TIP},
        {.option = CLI_OPT_NO_CAPS},
        {.option = CLI_OPT_LEAVES},
        {.option = CLI_OPT_LEAF_SHAPE},
        {.option = CLI_OPT_STATS},
        {.group = cli_derive_uses},
        {0},
    },
    .epilogue = "\n" CLI_EXIT_CODES,
    .args_error = "expects one model file",
};

int cmd_mesh(int argc, char **argv) {
    ModelArgs m = {0};
    SylDeriveOptions d = {.steps = -1, .diag = stderr};
    SylMeshOptions mo = {.diag = stderr};
    CliArgs a = {.m = &m, .d = &d, .mo = &mo};
    int done = cli_parse(&cli_mesh_command, argc, argv, &a);
    if (done != CLI_RUN) return done;
    const char *output = a.output;
    bool stats = a.stats;
    if (!output || !strcmp(output, "-")) {
        fprintf(stderr, "sylva mesh: -o OUT.glb, OUT.obj or OUT.ply is required\n");
        return SYL_EUSAGE;
    }
    const char *dot = strrchr(output, '.');
    if (!dot || strchr(dot, '/') || (strcasecmp(dot, ".glb") && strcasecmp(dot, ".obj") && strcasecmp(dot, ".ply"))) {
        fprintf(stderr, "sylva: error: cannot tell the format of '%s': name it *.glb, *.obj or *.ply\n", output);
        return SYL_EUSAGE;
    }
    bool instanced = mo.leaves == SYL_LEAVES_INSTANCED || mo.leaves == SYL_LEAVES_INSTANCED_CARDS;
    if (instanced && strcasecmp(dot, ".glb")) {
        fprintf(stderr, "sylva: error: --leaves %s needs a .glb (OBJ and PLY cannot instance)\n",
                syl_leaves_names[mo.leaves]);
        return SYL_EUSAGE;
    }
    mo.threads = d.threads;
    cli_model_spec(&m, a.files[0]);
    SylBudget *budget = syl_budget_new(d.max_memory); /* one --max-memory for every engine */
    d.budget = budget;
    mo.budget = budget;
    Plant pl;
    int status = cli_plant(&m, &d, &mo, &pl);
    if (status) {
        syl_budget_free(budget);
        return status;
    }
    const SylSkeleton *sk = pl.sk;
    const SylMesh *mesh = pl.mesh;
    double t3 = cli_now();
    SylInstances *sets = NULL;
    int nsets = 0;
    size_t instances = 0;
    if (instanced) {
        status = syl_leaf_instances(sk, &mo, &sets, &nsets);
        if (status) fprintf(stderr, "sylva: error: out of memory placing the leaves\n");
        for (int i = 0; i < nsets; i++) instances += sets[i].count;
    }
    if (!status) status = instanced ? syl_write_glb_instanced(mesh, sets, nsets, output, stderr)
                                    : syl_write_mesh(mesh, output, stderr);
    syl_instances_free(sets, nsets);
    double t4 = cli_now();
    if (!status && stats) {
        size_t tris = mesh->nidx / 3;
        fprintf(stderr, "modules: %zu\nnodes: %zu\norgans: %zu\npolygons: %zu\n", pl.modules, sk->nnodes,
                sk->norgans, sk->npolys);
        fprintf(stderr, "vertices: %zu\ntriangles: %zu\nmaterial groups: %d\n", mesh->nverts, tris, mesh->ngroups);
        if (instanced) fprintf(stderr, "leaf instances: %zu\n", instances);
        fprintf(stderr, "derive time: %.6f s\nturtle time: %.6f s\nmesh time: %.6f s\n", pl.derive_s, pl.turtle_s,
                pl.mesh_s);
        if (pl.mesh_s > 0) fprintf(stderr, "mesh rate: %.2f M triangles/s\n", (double)tris / pl.mesh_s / 1e6);
        fprintf(stderr, "write time: %.6f s\npeak memory: %.2f MB\n", t4 - t3, cli_peak_mb());
    }
    cli_plant_free(&pl);
    syl_budget_free(budget);
    return status;
}
