/* sylva mesh: derive a model, draw it with the turtle, mesh it and write .glb, .obj or .ply. */
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli/cli.h"
#include "sylva/impostor.h"
#include "util/outgroup.h"
#include "sylva/lod.h"
#include "sylva/texture.h"
#include "sylva/mesh.h"
#include "sylva/wind.h"

const CliCommand cli_mesh_command = {
    .name = "mesh",
    .what = "draw a model and write a triangle mesh (.glb, .obj, .ply)",
    .run = cmd_mesh,
    .usage = "sylva mesh FILE[:Model] -o OUT.{glb,obj,ply} [options]",
    .about = "Derive the model, draw it with the 3D turtle and write a triangle mesh: a closed tube\n"
             "along every axis (rotation-minimising frames, end caps, smooth normals, bark UVs),\n"
             "leaves and polygons as double-sided faces (a .glb's leaves one face, their material\n"
             "doubleSided), one material group per colour. The format\n"
             "follows the extension: glTF 2.0 binary (.glb), Wavefront OBJ with NAME.mtl and\n"
             "NAME_bark.png etc. (.obj), or binary PLY (.ply). Triangles are ordered for the\n"
             "vertex cache (meshoptimizer). --lod N adds levels of detail NAME_LOD1 .. NAME_LODN\n"
             "to a .glb (MSFT_lod): fewer branch orders, fewer and larger leaves, simplified.\n",
    .options = (const CliUse[]){
        {.option = CLI_OPT_OUTPUT, .help = "the mesh file (required)"},
        {.option = CLI_OPT_SIDES},
        {.option = CLI_OPT_MIN_SIDES},
        {.option = CLI_OPT_RADIUS},
        {.option = CLI_OPT_TIP},
        {.option = CLI_OPT_NO_CAPS},
        {.option = CLI_OPT_LEAVES},
        {.option = CLI_OPT_LEAF_SHAPE},
        {.option = CLI_OPT_LOD},
        {.option = CLI_OPT_IMPOSTOR},
        {.option = CLI_OPT_IMPOSTOR_GRID},
        {.option = CLI_OPT_IMPOSTOR_VIEW},
        {.option = CLI_OPT_BILLBOARDS},
        {.option = CLI_OPT_WIND},
        {.option = CLI_OPT_WIND_DIR},
        {.option = CLI_OPT_WIND_SECONDS},
        {.option = CLI_OPT_WIND_LEVELS},
        {.option = CLI_OPT_IMAGE, .help = "with --lod, also render LOD0 .. LODN side by side (256 x 256\n"
                                           "each, one camera) into the PNG FILE"},
        {.option = CLI_OPT_STATS, .help = "print counts and times to stderr; with --lod, each level's\n"
                                          "triangles and silhouette error"},
        {.group = cli_derive_uses},
        {0},
    },
    .epilogue = "\n" CLI_EXIT_CODES,
    .args_error = "expects one model file",
};

/* OUT.glb -> OUT_SUFFIX */
static void beside(const char *output, const char *suffix, char *buf, size_t n) {
    size_t stem = strlen(output) - 4; /* without ".glb" */
    snprintf(buf, n, "%.*s%s", (int)stem, output, suffix);
}

/* Bake the impostor, make its crossed billboards the chain's last level (plant/billboard.c) and
 * write the octahedral atlas beside the file. */
static int add_impostor(SylLodChain *c, const CliArgs *a, const SylSkeleton *sk, const SylMeshOptions *mo,
                        int threads, SylBudget *budget, const char *output, SylImpostor *imp, char *extras,
                        size_t n, OutGroup *outs) {
    SylImpostorOptions io = {.grid = a->impostor ? a->impostor_grid : -1, .view = a->impostor_view, .billboards = a->billboards ? a->billboards : 3,
                             .threads = threads, .sink = &cli_sink, .budget = budget};
    int status = syl_impostor_add_level(c, sk, mo, &io, imp);
    if (status) return status;
    char color[4096], normal[4096];
    beside(output, "_impostor.png", color, sizeof color);
    beside(output, "_impostor_normal.png", normal, sizeof normal);
    if (a->impostor) {
        status = outgroup_add(outs, color, &cli_sink) ? syl_png_write_rgba(color, imp->color, imp->size, imp->size, &cli_sink) : SYL_EIO;
        if (!status) status = outgroup_add(outs, normal, &cli_sink) ? syl_png_write_rgba(normal, imp->normal, imp->size, imp->size, &cli_sink) : SYL_EIO;
        if (status) return status;
    }
    const char *cs = strrchr(color, '/'), *ns = strrchr(normal, '/');
    cs = cs ? cs + 1 : color, ns = ns ? ns + 1 : normal;
    int len = snprintf(extras, n, "{\"sylva_billboards\":%d,\"sylva_impostor_centre\":[%.6g,%.6g,%.6g],"
                                  "\"sylva_impostor_radius\":%.6g", imp->billboards, (double)imp->centre[0],
                       (double)imp->centre[1], (double)imp->centre[2], (double)imp->radius);
    if (a->impostor && len > 0 && (size_t)len < n && !strpbrk(cs, "\"\\") && !strpbrk(ns, "\"\\"))
        len += snprintf(extras + len, n - (size_t)len,
                        ",\"sylva_impostor\":{\"layout\":\"hemi-octahedral\",\"grid\":%d,\"view\":%d,"
                        "\"size\":%d,\"color\":\"%s\",\"normal_depth\":\"%s\"}",
                        imp->grid, imp->view, imp->size, cs, ns);
    if (len > 0 && (size_t)len + 2 < n) strcat(extras, "}");
    c->extras = extras;
    return SYL_OK;
}

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
    const SylMeshFormat *format = syl_mesh_format(output, &cli_sink);
    if (!format) return SYL_EUSAGE;
    bool instanced = mo.leaves == SYL_LEAVES_INSTANCED || mo.leaves == SYL_LEAVES_INSTANCED_CARDS;
    if (instanced && !(format->can & SYL_FORMAT_INSTANCES)) {
        fprintf(stderr, "sylva: error: --leaves %s needs a .glb (OBJ and PLY cannot instance)\n",
                syl_leaves_names[mo.leaves]);
        return SYL_EUSAGE;
    }
    bool levels = a.lod || a.impostor || a.billboards;
    if (a.wind > 0 && !(format->can & SYL_FORMAT_WIND)) {
        fprintf(stderr, "sylva: error: --wind writes a skinned .glb, not '%s'\n", output);
        return SYL_EUSAGE;
    }
    mo.vertex_nodes = a.wind > 0;
    mo.one_sided = (format->can & SYL_FORMAT_DOUBLE_SIDED) != 0; /* glTF's doubleSided draws a leaf's back */
    if (levels && !(format->can & SYL_FORMAT_LEVELS)) {
        fprintf(stderr, "sylva: error: --lod, --impostor and --billboards write into a .glb only, not '%s'\n", output);
        return SYL_EUSAGE;
    }
    mo.threads = d.threads;
    cli_model_spec(&m, a.files[0]);
    SylBudget *budget = syl_budget_new(d.max_memory); /* one --max-memory for every engine */
    d.budget = budget;
    mo.budget = budget;
    Plant pl;
    OutGroup outs = {0}; /* the atlases, the mesh and --image: one transaction */
    int status = cli_plant(&m, &d, &mo, &pl);
    if (status) {
        syl_budget_free(budget);
        return status;
    }
    /* the model's `lod` setting, when --lod does not say: a .glb without wind only */
    if (!a.lod && pl.lod && (format->can & SYL_FORMAT_LEVELS) && !(a.wind > 0)) a.lod = pl.lod, levels = true;
    const SylSkeleton *sk = pl.sk;
    SylMesh *mesh = pl.mesh;
    if (a.wind > 0 && !mesh->node) { /* syl_mesh_append dropped them */
        fprintf(stderr, "sylva: error: --wind cannot skin this mesh: part of it is not the plant's (a scene's "
                        "obstacles)\n");
        cli_plant_free(&pl);
        syl_budget_free(budget);
        return SYL_EUSAGE;
    }
    SylLodChain lods = {0};
    SylImpostor imp = {0};
    char extras[1024];
    double t2 = cli_now(), t_imp = 0, c2 = cli_cpu_now(), c_imp = 0;
    if (levels) {
        bool last_billboard = a.impostor || a.billboards;
        int geometric = (a.lod ? a.lod : 1) - (last_billboard ? 1 : 0);
        status = syl_lod_build(sk, &mo, mesh, geometric, &lods);
        if (status) fprintf(stderr, "sylva: error: cannot build the levels of detail (out of memory)\n");
        double ti = cli_now(), ci = cli_cpu_now();
        if (!status && last_billboard)
            status = add_impostor(&lods, &a, sk, &mo, d.threads, budget, output, &imp, extras, sizeof extras, &outs);
        t_imp = cli_now() - ti, c_imp = cli_cpu_now() - ci;
    } else {
        status = syl_mesh_optimize(mesh);
        for (int i = 0; !status && i < pl.nparts; i++) status = syl_mesh_optimize(pl.parts[i]);
        if (!status && pl.nparts > 1 && !(format->can & SYL_FORMAT_PARTS))
            fprintf(stderr, "sylva: warning: a PLY file holds one mesh: the scene's %d objects are merged into it "
                            "(write .obj or .glb for one object each)\n", pl.nparts);
    }
    SylWind wind = {0};
    double t_wind = cli_now();
    if (!status && a.wind > 0) {
        SylWindOptions wo = {.speed = a.wind, .dir = {a.wind_dir[0], a.wind_dir[1]}, .seconds = a.wind_seconds,
                             .levels = a.wind_levels, .budget = budget, .diag = stderr};
        float *radius = malloc((sk->nnodes + 1) * sizeof *radius);
        status = radius ? syl_mesh_radii(sk, &mo, radius) : SYL_ELIMIT;
        if (!radius) fprintf(stderr, "sylva: error: out of memory\n");
        if (!status) status = syl_wind_build(sk, radius, &wo, &wind);
        free(radius);
        if (status && status != SYL_ELIMIT) fprintf(stderr, "sylva: error: cannot build the wind's joints (bad model)\n");
    }
    t_wind = cli_now() - t_wind;
    double t3 = cli_now(), c3 = cli_cpu_now();
    SylInstances *sets = NULL;
    int nsets = 0;
    size_t instances = 0;
    if (instanced) {
        status = syl_instances_build(sk, &mo, &sets, &nsets);
        if (status) fprintf(stderr, "sylva: error: out of memory placing the leaves\n");
        for (int i = 0; i < nsets; i++) instances += sets[i].count;
        if (levels) lods.level[0].sets = sets, lods.level[0].nsets = nsets; /* still ours to free */
    }
    if (!status && !outgroup_add(&outs, output, &cli_sink)) status = SYL_EIO;
    SylMeshOutput mout = {.mesh = mesh, .parts = pl.parts, .nparts = pl.nparts, .instanced = instanced,
                          .sets = sets, .nsets = nsets, .lods = levels ? &lods : NULL, .skeleton = sk,
                          .wind = a.wind > 0 ? &wind : NULL};
    if (!status) status = syl_mesh_write_output(&mout, output, &cli_sink);
    syl_instances_free(sets, nsets);
    double t4 = cli_now(), c4 = cli_cpu_now();
    if (!status && a.image && lods.n) { /* the billboards' quads are not pictures the renderer can draw */
        SylLodChain shown = lods;
        shown.n -= imp.billboards ? 1 : 0;
        SylPicture pic = {0};
        status = outgroup_add(&outs, a.image, &cli_sink)
                     ? syl_lod_draw_levels(&shown, &(SylLodCheckOptions){.threads = d.threads, .sink = &cli_sink}, &pic)
                     : SYL_EIO;
        if (!status) status = syl_png_write(a.image, pic.rgb, pic.width, pic.height, &cli_sink);
        syl_picture_free(&pic);
    }
    if (status) outgroup_undo(&outs); /* the command's files are one: all written, or none changed */
    else outgroup_commit(&outs);
    if (!status && stats) {
        size_t tris = mesh->nidx / 3;
        fprintf(stderr, "modules: %zu\nnodes: %zu\norgans: %zu\npolygons: %zu\n", pl.modules, sk->nnodes,
                sk->norgans, sk->npolys);
        fprintf(stderr, "vertices: %zu\ntriangles: %zu\nmaterial groups: %d\n", mesh->nverts, tris, mesh->ngroups);
        if (instanced) fprintf(stderr, "leaf instances: %zu\n", instances);
        fprintf(stderr, "derive time: %.6f s\nderive cpu time: %.6f s\nturtle time: %.6f s\nmesh time: %.6f s\n",
                pl.derive_s, pl.derive_cpu_s, pl.turtle_s, pl.mesh_s);
        fprintf(stderr, "mesh cpu time: %.6f s\n", pl.mesh_cpu_s);
        if (pl.mesh_s > 0) fprintf(stderr, "mesh rate: %.2f M triangles/s\n", (double)tris / pl.mesh_s / 1e6);
        fprintf(stderr, "%s time: %.6f s\n", levels ? "lod" : "optimize", t3 - t2 - t_imp - t_wind);
        if (levels) fprintf(stderr, "lod cpu time: %.6f s\n", c3 - c2 - c_imp);
        if (imp.billboards) fprintf(stderr, "impostor time: %.6f s\nimpostor cpu time: %.6f s\n", t_imp, c_imp);
        if (a.wind > 0) fprintf(stderr, "wind joints: %d\nwind keys: %d\nwind time: %.6f s\n", wind.njoints, wind.nkeys, t_wind);
        for (int k = 1; k < lods.n - (imp.billboards ? 1 : 0); k++) {
            SylLodSilhouette sil;
            if (syl_lod_check_silhouette(&lods, k, &(SylLodCheckOptions){.threads = d.threads, .sink = &cli_sink}, &sil)) break;
            const SylLodLevel *lv = &lods.level[k];
            char leaves[64];
            if (lv->cluster_leaves > 0) snprintf(leaves, sizeof leaves, "leaves in clusters of %.1f", (double)lv->cluster_leaves);
            else snprintf(leaves, sizeof leaves, "leaves %.0f%% x %.2f", 100.0 * lv->leaf_keep, (double)lv->leaf_scale);
            fprintf(stderr, "LOD%d: %zu triangles (%.2f%%), max order %d, %s, silhouette error %.2f%% (coverage %.2f%%) at %d px\n",
                    k, lv->mesh->nidx / 3, 100.0 * (double)lv->mesh->nidx / (double)(mesh->nidx ? mesh->nidx : 1),
                    lv->max_order, leaves, sil.percent, sil.soft, sil.pixels);
        }
        fprintf(stderr, "write time: %.6f s (cpu %.6f s)\npeak memory: %.2f MB\n", t4 - t3, c4 - c3, cli_peak_mb());
    }
    if (!status && stats && imp.billboards)
        fprintf(stderr, "LOD%d: %zu triangles, %d crossed billboards\n", lods.n - 1,
                lods.level[lods.n - 1].mesh->nidx / 3, imp.billboards);
    syl_lod_free(&lods);
    syl_wind_free(&wind);
    syl_impostor_free(&imp);
    cli_plant_free(&pl);
    syl_budget_free(budget);
    return status;
}
