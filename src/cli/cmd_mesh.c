/* sylva mesh: derive a model, draw it with the turtle, mesh it and write .glb, .obj or .ply. */
#include <getopt.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli.h"
#include "sylva/mesh.h"

static const char usage[] =
    "usage: sylva mesh FILE[:Model] -o OUT.{glb,obj,ply} [options]\n"
    "\n"
    "Derive the model, draw it with the 3D turtle and write a triangle mesh: a closed tube\n"
    "along every axis (rotation-minimising frames, end caps, smooth normals, bark UVs),\n"
    "leaves and polygons as double-sided faces, one material group per colour. The format\n"
    "follows the extension: glTF 2.0 binary (.glb), Wavefront OBJ with NAME.mtl and\n"
    "NAME_bark.png etc. (.obj), or binary PLY (.ply).\n"
    "\n"
    "  -o, --output FILE     the mesh file (required)\n"
    "  --sides N             sides around the thickest branch, 3 to 256 (default 8);\n"
    "                        thinner ones get fewer, down to --min-sides (default 3)\n"
    "  --min-sides N         the fewest sides of a thin branch\n"
    "  --radius model|pipe[:EXP]\n"
    "                        branch radii: the model's widths (default), or the pipe model\n"
    "                        r^EXP = sum of the children's r^EXP (EXP default 2)\n"
    "  --tip R               pipe model: the radius of a tip (default: the model's mean)\n"
    "  --no-caps             leave the ends of the tubes open\n"
    "  --stats               print counts and times to stderr\n"
    CLI_DERIVE_HELP
    "\n"
    "Exit codes: 0 ok, 1 the model is wrong, 2 bad command line, 3 limit hit, 4 I/O error.\n";

enum { OPT_SIDES = 1000, OPT_MIN_SIDES, OPT_RADIUS, OPT_TIP, OPT_NO_CAPS, OPT_STATS };

static bool parse_radius(const char *arg, SylMeshOptions *mo) {
    if (!strcmp(arg, "model")) {
        mo->radius = SYL_RADIUS_MODEL;
        return true;
    }
    if (!strncmp(arg, "pipe", 4) && (!arg[4] || arg[4] == ':')) {
        mo->radius = SYL_RADIUS_PIPE;
        double v;
        if (arg[4] == ':') {
            if (!cli_number("--radius pipe:", arg + 5, 0.5, 10, &v)) return false;
            mo->pipe_exponent = (float)v;
        }
        return true;
    }
    fprintf(stderr, "sylva: error: --radius expects model, pipe or pipe:EXPONENT, not '%s'\n", arg);
    return false;
}

int cmd_mesh(int argc, char **argv) {
    static const struct option opts[] = {
        CLI_DERIVE_OPTIONS,
        {"output", required_argument, 0, 'o'},         {"sides", required_argument, 0, OPT_SIDES},
        {"min-sides", required_argument, 0, OPT_MIN_SIDES}, {"radius", required_argument, 0, OPT_RADIUS},
        {"tip", required_argument, 0, OPT_TIP},        {"no-caps", no_argument, 0, OPT_NO_CAPS},
        {"stats", no_argument, 0, OPT_STATS},          {"help", no_argument, 0, 'h'},
        {0, 0, 0, 0},
    };
    ModelArgs m = {0};
    SylDeriveOptions d = {.steps = -1, .diag = stderr};
    SylMeshOptions mo = {.diag = stderr};
    const char *output = NULL;
    bool stats = false;
    double v;
    int c;
    optind = 1;
    while ((c = getopt_long(argc, argv, CLI_DERIVE_SHORT "o:h", opts, NULL)) != -1) {
        int done = cli_derive_option(c, optarg, &m, &d);
        if (done < 0) return SYL_EUSAGE;
        if (done) continue;
        switch (c) {
        case 'o': output = optarg; break;
        case OPT_SIDES:
            if (!cli_integer("--sides", optarg, 3, 256, &v)) return SYL_EUSAGE;
            mo.sides = (int)v;
            break;
        case OPT_MIN_SIDES:
            if (!cli_integer("--min-sides", optarg, 3, 256, &v)) return SYL_EUSAGE;
            mo.min_sides = (int)v;
            break;
        case OPT_RADIUS:
            if (!parse_radius(optarg, &mo)) return SYL_EUSAGE;
            break;
        case OPT_TIP:
            if (!cli_number("--tip", optarg, 1e-9, 1e9, &v)) return SYL_EUSAGE;
            mo.tip_radius = (float)v;
            break;
        case OPT_NO_CAPS: mo.caps = -1; break;
        case OPT_STATS: stats = true; break;
        case 'h': fputs(usage, stdout); return SYL_OK;
        default: fputs(usage, stderr); return SYL_EUSAGE;
        }
    }
    if (optind != argc - 1) {
        fprintf(stderr, "sylva mesh: expects one model file\n%s", usage);
        return SYL_EUSAGE;
    }
    if (!output || !strcmp(output, "-")) {
        fprintf(stderr, "sylva mesh: -o OUT.glb, OUT.obj or OUT.ply is required\n");
        return SYL_EUSAGE;
    }
    const char *dot = strrchr(output, '.');
    if (!dot || strchr(dot, '/') || (strcasecmp(dot, ".glb") && strcasecmp(dot, ".obj") && strcasecmp(dot, ".ply"))) {
        fprintf(stderr, "sylva: error: cannot tell the format of '%s': name it *.glb, *.obj or *.ply\n", output);
        return SYL_EUSAGE;
    }
    mo.threads = d.threads;
    cli_model_spec(&m, argv[optind]);
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
    status = syl_write_mesh(mesh, output, stderr);
    double t4 = cli_now();
    if (!status && stats) {
        size_t tris = mesh->nidx / 3;
        fprintf(stderr, "modules: %zu\nnodes: %zu\norgans: %zu\npolygons: %zu\n", pl.modules, sk->nnodes,
                sk->norgans, sk->npolys);
        fprintf(stderr, "vertices: %zu\ntriangles: %zu\nmaterial groups: %d\n", mesh->nverts, tris, mesh->ngroups);
        fprintf(stderr, "derive time: %.6f s\nturtle time: %.6f s\nmesh time: %.6f s\n", pl.derive_s, pl.turtle_s,
                pl.mesh_s);
        if (pl.mesh_s > 0) fprintf(stderr, "mesh rate: %.2f M triangles/s\n", (double)tris / pl.mesh_s / 1e6);
        fprintf(stderr, "write time: %.6f s\npeak memory: %.2f MB\n", t4 - t3, cli_peak_mb());
    }
    cli_plant_free(&pl);
    syl_budget_free(budget);
    return status;
}
