/* Every option of `sylva`: its names, its help row and what it sets (cli/options.h). */
#include <errno.h>
#include <stddef.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"
#include "sylva/ecosystem.h"
#include "sylva/texture.h"
#include "sylva/lod.h"

static bool read_seed(CliArgs *a, char *arg) {
    double v;
    if (!cli_integer("--seed", arg, 0, 9007199254740991.0, &v)) return false;
    a->d->use_seed = 1;
    a->d->seed = (uint64_t)v;
    return true;
}

static bool read_set(CliArgs *a, char *arg) { return cli_set(a->m, arg); }

/* --allow-path DIR: a folder (that must exist) whose files a model may name */
static bool read_allow_path(CliArgs *a, char *arg) {
    struct stat st;
    if (stat(arg, &st) || !S_ISDIR(st.st_mode)) {
        fprintf(stderr, "sylva: error: --allow-path expects a folder, and '%s' is %s\n", arg,
                errno == ENOENT ? "not there" : "not a folder");
        return false;
    }
    if (a->m->nallow == MAX_ALLOW_PATHS) {
        fprintf(stderr, "sylva: error: at most %d --allow-path options\n", MAX_ALLOW_PATHS);
        return false;
    }
    a->m->allow[a->m->nallow++] = arg;
    return true;
}
static bool read_view(CliArgs *a, char *arg) { return cli_view(arg, &a->ro->view); }
static bool read_size(CliArgs *a, char *arg) { return cli_picture_size(arg, &a->ro->width, &a->ro->height); }

static bool read_eco_view(CliArgs *a, char *arg) {
    if (!strcmp(arg, "bird") || !strcmp(arg, "walker")) {
        a->eco_view = arg[0] == 'w'; /* SYL_FOREST_BIRD, SYL_FOREST_WALKER */
        return true;
    }
    fprintf(stderr, "sylva: error: --view expects bird or walker, not '%s'\n", arg);
    return false;
}

/* sylva render's --view: a plant's (iso, front, side, top) or a snapshot's (bird, walker) */
static bool read_render_view(CliArgs *a, char *arg) {
    if (strcmp(arg, "bird") && strcmp(arg, "walker")) return cli_view_or(arg, &a->ro->view, " (a plant), bird or walker (--plants)");
    a->eco_view_set = true;
    return read_eco_view(a, arg);
}

static bool read_ao(CliArgs *a, char *arg) {
    double v;
    if (!cli_integer("--ao", arg, 0, 64, &v)) return false;
    a->ro->ao_samples = v > 0 ? (int)v : -1; /* 0 is the mesher's default: -1 is none */
    return true;
}

static bool read_radius(CliArgs *a, char *arg) {
    SylMeshOptions *mo = a->mo;
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

static bool read_leaves(CliArgs *a, char *arg) {
    for (int k = 0; k < SYL_LEAVES_MODES; k++)
        if (!strcmp(arg, syl_leaves_names[k])) {
            a->mo->leaves = k;
            return true;
        }
    fprintf(stderr, "sylva: error: --leaves expects mesh, cards, instanced, instanced-cards or clusters, not '%s'\n", arg);
    return false;
}

static bool read_wind_dir(CliArgs *a, char *arg) {
    char *comma = strchr(arg, ',');
    double x, z;
    if (comma) *comma = 0;
    bool ok = comma && cli_number("--wind-dir", arg, -1e6, 1e6, &x) && cli_number("--wind-dir", comma + 1, -1e6, 1e6, &z);
    if (comma) *comma = ',';
    if (ok && x == 0 && z == 0) ok = false, fprintf(stderr, "sylva: error: --wind-dir 0,0 has no direction\n");
    else if (!ok && !comma) fprintf(stderr, "sylva: error: --wind-dir expects X,Z (where the wind blows to), not '%s'\n", arg);
    if (ok) a->wind_dir[0] = (float)x, a->wind_dir[1] = (float)z;
    return ok;
}

static bool read_leaf_shape(CliArgs *a, char *arg) {
    int k = syl_leaf_shape_named(arg);
    if (k >= 0) {
        a->mo->leaf_shape = k;
        return true;
    }
    fprintf(stderr, "sylva: error: --leaf-shape expects ovate, linear, cordate, maple or palmate, not '%s'\n", arg);
    return false;
}

int cli_format_named(const char *name) {
    if (!strcmp(name, "csv")) return CLI_FORMAT_CSV;
    if (!strcmp(name, "json")) return CLI_FORMAT_JSON;
    return CLI_FORMAT_NONE;
}

static bool read_format(CliArgs *a, char *arg) {
    a->format = cli_format_named(arg);
    if (a->format) return true;
    fprintf(stderr, "sylva: error: --format expects csv or json, not '%s'\n", arg);
    return false;
}

/* --heights LO,HI: the heights of black and white in a PNG DEM. */
/* --snapshots 20,60,180: increasing years */
static bool read_snapshots(CliArgs *a, char *arg) {
    a->nsnapshots = 0;
    for (char *s = arg, *end; *s; s = *end ? end + 1 : end) {
        end = s + strcspn(s, ",");
        char save = *end;
        *end = 0;
        double v;
        if (a->nsnapshots == SYL_ECO_MAX_SNAPSHOTS) {
            fprintf(stderr, "sylva: error: --snapshots takes at most %d years\n", SYL_ECO_MAX_SNAPSHOTS);
            return false;
        }
        bool ok = cli_integer("--snapshots", s, 0, SYL_ECO_MAX_YEARS, &v);
        *end = save;
        if (!ok || (a->nsnapshots && v <= a->snapshots[a->nsnapshots - 1])) {
            if (ok) fprintf(stderr, "sylva: error: --snapshots expects increasing years, as 20,60,180\n");
            return false;
        }
        a->snapshots[a->nsnapshots++] = (int)v;
    }
    return a->nsnapshots > 0;
}

/* --tiles NxM */
static bool read_tiles(CliArgs *a, char *arg) {
    int n, m, used = 0;
    if (sscanf(arg, "%dx%d%n", &n, &m, &used) != 2 || arg[used] || n < 1 || m < 1 || n > 64 || m > 64) {
        fprintf(stderr, "sylva: error: --tiles expects NxM with 1 <= N, M <= 64, as 3x2, not '%s'\n", arg);
        return false;
    }
    a->tiles_x = n;
    a->tiles_z = m;
    return true;
}

static bool read_heights(CliArgs *a, char *arg) {
    char *comma = strchr(arg, ',');
    if (comma) {
        *comma = 0;
        bool ok = cli_number("--heights", arg, -1e9, 1e9, &a->heights[0]) &&
                  cli_number("--heights", comma + 1, -1e9, 1e9, &a->heights[1]);
        *comma = ',';
        if (!ok) return false;
        if (a->heights[1] > a->heights[0]) return a->heights_set = true;
    }
    fprintf(stderr, "sylva: error: --heights expects LOW,HIGH with LOW below HIGH, not '%s'\n", arg);
    return false;
}

static bool read_measures(CliArgs *a, char *arg) {
    static const char *const words[] = {"gis", "zamuda", "both"};
    for (int i = 0; i < 3; i++)
        if (!strcmp(arg, words[i])) {
            a->measures = i + 1; /* SYL_TERRAIN_GIS, _ZAMUDA, _BOTH */
            return true;
        }
    fprintf(stderr, "sylva: error: --measures expects gis, zamuda or both, not '%s'\n", arg);
    return false;
}

#define IN(where, type, member) .in = CLI_IN_##where, .at = offsetof(type, member)
#define ARGS(member) IN(ARGS, CliArgs, member)
#define DERIVE(member) IN(DERIVE, SylDeriveOptions, member)
#define MODEL(member) IN(MODEL, ModelArgs, member)
#define MESH(member) IN(MESH, SylMeshOptions, member)
#define RENDER(member) IN(RENDER, SylRenderOptions, member)

const CliOption cli_options[CLI_OPT_COUNT] = {
    /* what is derived or grown, and the limits that stop it */
    [CLI_OPT_DERIVE] = {"derive", 'n', "N", "derivation steps (default: the model's `derive`)",
                        CLI_INT, DERIVE(steps), 0, 1e6},
    [CLI_OPT_SEED] = {"seed", 0, "S", "random seed (default: the model's `seed`)", CLI_READ, .read = read_seed},
    [CLI_OPT_SET] = {"set", 0, "NAME=VALUE", "give a `param`, a setting (angle, step...) or a grow\n"
                     "directive's number (lambda...) this value; repeatable", CLI_READ,
                     .read = read_set},
    [CLI_OPT_ALLOW_PATH] = {"allow-path", 0, "DIR", "let the model read files it names in DIR too (by default only\n"
                            "files in its own folder and below); repeatable", CLI_READ,
                            .read = read_allow_path},
    [CLI_OPT_THREADS] = {"threads", 'j', "N", "threads (default: all cores); the output never depends on N",
                         CLI_INT, DERIVE(threads), 1, 256},
    [CLI_OPT_MAX_MODULES] = {"max-modules", 0, "N",
                             "stop with exit code 3 beyond N modules in a string\n"
                             "(default 200000000)",
                             CLI_COUNT, DERIVE(max_modules), 1, 2147483647.0},
    [CLI_OPT_MAX_MEMORY] = {"max-memory", 0, "SIZE",
                            "stop with exit code 3 beyond SIZE of memory for strings, trees,\n"
                            "meshes, pictures and files, e.g. 2G (default: half the least of\n"
                            "the machine's memory, RLIMIT_AS, RLIMIT_DATA and the cgroup's\n"
                            "limit, at most 16G)",
                            CLI_SIZE, DERIVE(max_memory)},
    [CLI_OPT_MAX_WORK] = {"max-work", 0, "N",
                          "stop with exit code 3 beyond N modules rewritten by all steps\n"
                          "of a derivation (default 100000000000)",
                          CLI_COUNT, DERIVE(max_work), 1, 1e18},
    [CLI_OPT_MAX_METAMERS] = {"max-metamers", 0, "N", "stop with exit code 3 beyond N metamers (default 20000000)",
                              CLI_COUNT, MODEL(max_metamers), 1, 4e9},
    [CLI_OPT_MAX_BUDS] = {"max-buds", 0, "N", "stop with exit code 3 beyond N buds (default 100000000)",
                          CLI_COUNT, MODEL(max_buds), 1, 4e9},
    [CLI_OPT_MAX_PLANTS] = {"max-plants", 0, "N",
                            "stop with exit code 3 beyond N plants alive at once\n"
                            "(default 100000000)",
                            CLI_COUNT, ARGS(max_plants), 1, 4e9},
    [CLI_OPT_YEARS] = {"years", 0, "N",
                       "years to grow (default: the model's `years`; a scene: each\n"
                       "plant's)",
                       CLI_INT, DERIVE(steps), 0, SYL_GROW_MAX_YEARS},
    [CLI_OPT_ECO_YEARS] = {"years", 0, "N", "years to simulate (default: the block's `years`)", CLI_INT,
                           DERIVE(steps), 1, SYL_ECO_MAX_YEARS},
    [CLI_OPT_SEEDS] = {"seeds", 0, "N",
                       "grow each model with N seeds (its seed, +1, +2, ...) and print\n"
                       "mean +- sample standard deviation (default 1)",
                       CLI_INT, ARGS(seeds), 1, 10000},
    [CLI_OPT_AGE] = {"age", 0, "T",
                     "strands blocks: the tree at age T in (0, 1], with T^2 of its\n"
                     "strands and T^2 of its trunk length (default 1, full grown)",
                     CLI_REAL, MODEL(age), 1e-6, 1},
    [CLI_OPT_LEVELS] = {"levels", 0, "N",
                        "weber blocks: build only the first N stem levels, without leaves\n"
                        "(default: the block's Levels)",
                        CLI_INT, MODEL(levels), 1, 10},
    /* what is written */
    [CLI_OPT_OUTPUT] = {"output", 'o', "FILE", "write to FILE instead of standard output", CLI_TEXT, ARGS(output)},
    [CLI_OPT_OUT] = {"out", 0, "DIR", "where to write (default: out)", CLI_TEXT, ARGS(dir)},
    [CLI_OPT_IMAGE] = {"image", 0, "FILE",
                       "also render the plants side by side at one scale, with a height\n"
                       "ruler, into the PNG FILE (the first seed of each model)",
                       CLI_TEXT, ARGS(image)},
    [CLI_OPT_FORMAT] = {"format", 0, "csv|json", "the format, whatever the file name", CLI_READ, .read = read_format},
    [CLI_OPT_CSV] = {"csv", 0, NULL, "comma-separated values instead of the aligned table", CLI_CHOICE, ARGS(format),
                     .value = CLI_FORMAT_CSV},
    [CLI_OPT_JSON] = {"json", 0, NULL, "JSON instead of the aligned table", CLI_CHOICE, ARGS(format),
                      .value = CLI_FORMAT_JSON},
    [CLI_OPT_STEPS] = {"steps", 0, NULL, "print every step on its own line, step 0 being the axiom", CLI_FLAG,
                       ARGS(steps)},
    [CLI_OPT_INTERPRET] = {"interpret", 0, NULL, "apply the model's `interpret` rules before printing", CLI_FLAG,
                           ARGS(interpret)},
    [CLI_OPT_QUIET] = {"quiet", 'q', NULL, "do not print the string (with --stats: figures only)", CLI_FLAG,
                       ARGS(quiet)},
    /* the picture */
    [CLI_OPT_VIEW] = {"view", 0, "V", "iso, front, side or top (default: chosen from the shape)", CLI_READ,
                      .read = read_view},
    [CLI_OPT_SIZE] = {"size", 0, "WxH", "picture size (default 1024x1024)", CLI_READ, .read = read_size},
    [CLI_OPT_SAMPLES] = {"samples", 0, "N", "anti-aliasing samples per pixel, 1 to 64 (default 4)", CLI_INT,
                         RENDER(samples), 1, 64},
    [CLI_OPT_AO] = {"ao", 0, "N", "ambient occlusion rays per pixel, 0 (none) to 64 (default 8)", CLI_READ,
                    .read = read_ao},
    [CLI_OPT_NO_SHADOWS] = {"no-shadows", 0, NULL, "no sun shadows", CLI_CHOICE, RENDER(shadows), .value = -1},
    /* the mesh */
    [CLI_OPT_SIDES] = {"sides", 0, "N",
                       "sides around the thickest branch, 3 to 256 (default 8);\n"
                       "thinner ones get fewer, down to --min-sides (default 3)",
                       CLI_INT, MESH(sides), 3, 256},
    [CLI_OPT_MIN_SIDES] = {"min-sides", 0, "N", "the fewest sides of a thin branch", CLI_INT, MESH(min_sides), 3,
                           256},
    [CLI_OPT_RADIUS] = {"radius", 0, "model|pipe[:EXP]",
                        "branch radii: the model's widths (default), or the pipe model\n"
                        "r^EXP = sum of the children's r^EXP (EXP default 2)",
                        CLI_READ, .read = read_radius},
    [CLI_OPT_TIP] = {"tip", 0, "R", "pipe model: the radius of a tip (default: the model's mean)", CLI_REAL,
                     MESH(tip_radius), 1e-9, 1e9},
    [CLI_OPT_NO_CAPS] = {"no-caps", 0, NULL, "leave the ends of the tubes open", CLI_CHOICE, MESH(caps), .value = -1},
    [CLI_OPT_LEAVES] = {"leaves", 0, "MODE",
                        "mesh (copied blades, default), cards (one alpha-tested quad each),\n"
                        "instanced or instanced-cards (one leaf placed by EXT_mesh_gpu_instancing;\n"
                        ".glb only), clusters (about 8 leaves or needles on one alpha-tested card;\n"
                        ".glb only)",
                        CLI_READ, .read = read_leaves},
    [CLI_OPT_LEAF_SHAPE] = {"leaf-shape", 0, "NAME",
                            "the silhouette in a card's alpha: ovate (default), linear, cordate,\n"
                            "maple or palmate",
                            CLI_READ, .read = read_leaf_shape},
    /* the rest */
    [CLI_OPT_STATS] = {"stats", 0, NULL, "print counts and times to stderr", CLI_FLAG, ARGS(stats)},
    [CLI_OPT_WERROR] = {"werror", 0, NULL, "treat warnings as errors", CLI_FLAG, ARGS(werror)},
    [CLI_OPT_DUMP] = {"dump", 0, NULL, "print the compiled program: rules and bytecode", CLI_FLAG, ARGS(dump)},
    /* sylva terrain */
    [CLI_OPT_MAPS] = {"maps", 0, "DIR", "write every factor's map as DIR/NAME.png and DIR/NAME.asc, and\nin colour with a legend as DIR/NAME-colour.png", CLI_TEXT,
                      ARGS(maps)},
    [CLI_OPT_CELL] = {"cell", 0, "SIZE",
                      "a PNG's cell size (default 1); an OBJ's grid spacing (default:\n"
                      "about one cell per vertex)",
                      CLI_REAL, ARGS(cell), 1e-6, 1e6},
    [CLI_OPT_HEIGHTS] = {"heights", 0, "LO,HI", "a PNG's heights of black and of white (default 0,1)", CLI_READ,
                         .read = read_heights},
    [CLI_OPT_LATITUDE] = {"latitude", 0, "DEG", "degrees north, for the sun's path (default 46)", CLI_REAL,
                          ARGS(latitude), -90, 90},
    [CLI_OPT_SUN_DAYS] = {"sun-days", 0, "N", "days of the year the sun is followed on (default 12)", CLI_INT,
                          ARGS(sun_days), 1, 365},
    [CLI_OPT_SUN_MINUTES] = {"sun-minutes", 0, "M", "minutes between the sun's positions in a day (default 60)",
                             CLI_REAL, ARGS(sun_minutes), 1, 1440},
    [CLI_OPT_WIND_FROM] = {"wind-from", 0, "DEG",
                           "the prevailing wind's direction, degrees clockwise from north\n"
                           "it blows from (default 270: west)",
                           CLI_REAL, ARGS(wind_from), 0, 360},
    [CLI_OPT_WIND_DISTANCE] = {"wind-distance", 0, "D", "how far upwind the terrain shelters (default 300)",
                               CLI_REAL, ARGS(wind_distance), 1e-6, 1e9},
    [CLI_OPT_MEASURES] = {"measures", 0, "WHICH", "gis (default): wetness, insolation and wind as GIS computes\n"
                          "them; zamuda: Zamuda's humidity, sunniness and windiness; both",
                          CLI_READ, .read = read_measures},
    /* sylva animate */
    [CLI_OPT_FPS] = {"fps", 0, "N", "frames per second of the video (default 4)", CLI_INT, ARGS(fps), 1, 120},
    [CLI_OPT_FRAMES_PER_STEP] = {"frames-per-step", 0, "N", "frames that show each step or year (default 1)",
                                 CLI_INT, ARGS(frames_per_step), 1, 1000},
    /* sylva ecosystem */
    [CLI_OPT_SNAPSHOTS] = {"snapshots", 0, "Y1,Y2,..", "the years whose plants and map are written (default:\n"
                           "the block's `snapshots`)", CLI_READ, .read = read_snapshots},
    [CLI_OPT_TILES] = {"tiles", 0, "NxM", "run the terrain as N x M tiles exchanging their borders\n"
                       "(default 1x1); the output is the same", CLI_READ, .read = read_tiles},
    [CLI_OPT_REBALANCE] = {"rebalance", 0, "K", "under mpirun: re-cut the tiles over the ranks by plant\n"
                           "count every K years (default 0: never)", CLI_INT, ARGS(rebalance), 0, 60000},
    [CLI_OPT_CHECKPOINT] = {"checkpoint", 0, "DIR", "save the whole state into DIR/ecosystem.ckpt (with --every)",
                            CLI_TEXT, ARGS(checkpoint)},
    [CLI_OPT_EVERY] = {"every", 0, "K", "years between checkpoints (default 10)", CLI_INT, ARGS(every), 1, 60000},
    [CLI_OPT_RESUME] = {"resume", 0, "DIR", "continue the run saved in DIR/ecosystem.ckpt (same model,\n"
                        "seed and options; any number of ranks)", CLI_TEXT, ARGS(resume)},
    [CLI_OPT_ECO_VIEW] = {"view", 0, "CAMERA", "bird (default: the whole terrain from above) or walker (1.7 m\n"
                          "above the valley floor, looking along it): view-YEAR.png's camera",
                          CLI_READ, .read = read_eco_view},
    [CLI_OPT_GLB] = {"glb", 0, NULL, "also write forest-YEAR.glb: the terrain and the plants as\n"
                     "EXT_mesh_gpu_instancing nodes, one per species, age class and cell", CLI_FLAG, ARGS(glb)},
    [CLI_OPT_PLANTS] = {"plants", 0, "CSV", "render this plant table (plants-YEAR.csv of sylva ecosystem) of\n"
                        "the model's ecosystem block, as view-YEAR.png", CLI_TEXT, ARGS(plants)},
    [CLI_OPT_RENDER_VIEW] = {"view", 0, "V", "iso, front, side or top (default: chosen from the shape); with\n"
                             "--plants, bird (default) or walker", CLI_READ, .read = read_render_view},
    /* sylva mesh */
    [CLI_OPT_LOD] = {"lod", 0, "N", "levels of detail LOD0 .. LODN in one .glb (1 to 8; default: the\nmodel's lod setting)", CLI_INT, ARGS(lod), 1,
                     SYL_LOD_MAX},
    [CLI_OPT_IMPOSTOR] = {"impostor", 0, NULL,
                          "bake an octahedral impostor (8 x 8 views of 256 x 256 pixels) into\n"
                          "NAME_impostor.png and NAME_impostor_normal.png; the last level\n"
                          "becomes crossed billboards", CLI_FLAG, ARGS(impostor)},
    [CLI_OPT_IMPOSTOR_GRID] = {"impostor-grid", 0, "N", "views across the impostor atlas (2 to 32; default 8)", CLI_INT,
                               ARGS(impostor_grid), 2, 32},
    [CLI_OPT_IMPOSTOR_VIEW] = {"impostor-view", 0, "PX", "pixels per impostor view (16 to 1024; default 256)", CLI_INT,
                               ARGS(impostor_view), 16, 1024},
    [CLI_OPT_BILLBOARDS] = {"billboards", 0, "K", "the last level is K crossed billboards (2 to 4; default 3)", CLI_INT,
                            ARGS(billboards), 2, 4},
    [CLI_OPT_WIND] = {"wind", 0, "SPEED", "sway in a wind of SPEED m/s: a skinned .glb (a joint per stem)\n"
                      "with a looping animation and the shader attributes _BRANCH_LEVEL,\n"
                      "_PHASE, _STIFFNESS", CLI_REAL, ARGS(wind), 0.01, 100},
    [CLI_OPT_WIND_DIR] = {"wind-dir", 0, "X,Z", "where the wind blows to (default 1,0: +x)", CLI_READ, .read = read_wind_dir},
    [CLI_OPT_WIND_SECONDS] = {"wind-seconds", 0, "S", "length of the wind loop (0.5 to 600; default 4)", CLI_REAL,
                              ARGS(wind_seconds), 0.5, 600},
    [CLI_OPT_WIND_LEVELS] = {"wind-levels", 0, "N", "stems of branch order below N get a joint (1 to 8; default 2)",
                             CLI_INT, ARGS(wind_levels), 1, 8},
    /* sylva view */
    [CLI_OPT_PORT] = {"port", 0, "N", "listen on this TCP port (default 8470; 0: any free one)", CLI_INT, ARGS(port), 0,
                      65535},
    [CLI_OPT_HOST] = {"host", 0, "ADDR", "listen on this IPv4 address (default 127.0.0.1, this machine only;\n"
                      "0.0.0.0 lets every machine that can reach this one try the token)", CLI_TEXT, ARGS(host)},
    [CLI_OPT_OPEN] = {"open", 0, NULL, "open the page in the desktop's browser (xdg-open)", CLI_FLAG, ARGS(open)},
};

const CliUse cli_limits[] = {
    {.option = CLI_OPT_MAX_MEMORY}, {.option = CLI_OPT_MAX_MODULES}, {.option = CLI_OPT_MAX_WORK}, {0},
};
const CliUse cli_grow_limits[] = {{.option = CLI_OPT_MAX_METAMERS}, {.option = CLI_OPT_MAX_BUDS}, {0}};
const CliUse cli_derive_uses[] = {
    {.option = CLI_OPT_DERIVE}, {.option = CLI_OPT_SEED}, {.option = CLI_OPT_SET}, {.option = CLI_OPT_ALLOW_PATH},
    {.option = CLI_OPT_THREADS}, {.option = CLI_OPT_AGE}, {.option = CLI_OPT_LEVELS}, {.group = cli_limits}, {0},
};
