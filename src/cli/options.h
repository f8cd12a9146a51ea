/* The command line as data: every option of `sylva` once, each command's table of them, and
 * the one parser (on getopt_long) that reads them and prints --help. */
#ifndef SYL_CLI_OPTIONS_H
#define SYL_CLI_OPTIONS_H
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "sylva/ecosystem.h"
#include "sylva/mesh.h"
#include "sylva/render.h"
#include "sylva/sylva.h"

struct ModelArgs;

/* Every option, in the order getopt_long is given them. That order shows: an abbreviation
 * that fits several ("--s") is refused with them listed in it, so keep it when adding one. */
typedef enum CliOptionId {
    CLI_OPT_NONE, /* ends a table */
    CLI_OPT_DERIVE, CLI_OPT_SEED, CLI_OPT_SET, CLI_OPT_ALLOW_PATH, CLI_OPT_THREADS,
    CLI_OPT_MAX_MODULES, CLI_OPT_MAX_MEMORY, CLI_OPT_MAX_WORK, CLI_OPT_MAX_METAMERS, CLI_OPT_MAX_BUDS, CLI_OPT_MAX_PLANTS,
    CLI_OPT_YEARS, CLI_OPT_ECO_YEARS, CLI_OPT_SEEDS, CLI_OPT_AGE, CLI_OPT_LEVELS,
    CLI_OPT_OUTPUT, CLI_OPT_OUT, CLI_OPT_IMAGE, CLI_OPT_FORMAT, CLI_OPT_CSV, CLI_OPT_JSON,
    CLI_OPT_STEPS, CLI_OPT_INTERPRET, CLI_OPT_QUIET,
    CLI_OPT_VIEW, CLI_OPT_SIZE, CLI_OPT_SAMPLES, CLI_OPT_AO, CLI_OPT_NO_SHADOWS,
    CLI_OPT_SIDES, CLI_OPT_MIN_SIDES, CLI_OPT_RADIUS, CLI_OPT_TIP, CLI_OPT_NO_CAPS, CLI_OPT_LEAVES, CLI_OPT_LEAF_SHAPE,
    CLI_OPT_STATS, CLI_OPT_WERROR, CLI_OPT_DUMP,
    /* sylva terrain */
    CLI_OPT_MAPS, CLI_OPT_CELL, CLI_OPT_HEIGHTS, CLI_OPT_LATITUDE, CLI_OPT_SUN_DAYS, CLI_OPT_SUN_MINUTES,
    CLI_OPT_WIND_FROM, CLI_OPT_WIND_DISTANCE, CLI_OPT_MEASURES,
    /* sylva animate */
    CLI_OPT_FPS, CLI_OPT_FRAMES_PER_STEP,
    /* sylva ecosystem */
    CLI_OPT_SNAPSHOTS, CLI_OPT_TILES, CLI_OPT_REBALANCE, CLI_OPT_CHECKPOINT, CLI_OPT_EVERY, CLI_OPT_RESUME, CLI_OPT_ECO_VIEW, CLI_OPT_GLB,
    /* sylva render of a snapshot */
    CLI_OPT_PLANTS, CLI_OPT_RENDER_VIEW,
    /* sylva mesh: levels of detail */
    CLI_OPT_LOD, CLI_OPT_IMPOSTOR, CLI_OPT_IMPOSTOR_GRID, CLI_OPT_IMPOSTOR_VIEW, CLI_OPT_BILLBOARDS,
    CLI_OPT_WIND, CLI_OPT_WIND_DIR, CLI_OPT_WIND_SECONDS, CLI_OPT_WIND_LEVELS,
    /* sylva view */
    CLI_OPT_PORT, CLI_OPT_HOST, CLI_OPT_OPEN,
    CLI_OPT_COUNT
} CliOptionId;

enum { CLI_FORMAT_NONE, CLI_FORMAT_CSV, CLI_FORMAT_JSON }; /* --format, --csv, --json */

/* What the options of a command set: the command's own structs (NULL where it has none of
 * their options) and the plain values. */
typedef struct CliArgs {
    struct ModelArgs *m;     /* --set, --max-metamers, --max-buds */
    SylDeriveOptions *d;     /* -n, --seed, -j, --max-modules, --max-memory, --max-work, --years */
    SylMeshOptions *mo;      /* --sides, --min-sides, --radius, --tip, --no-caps, --leaves, --leaf-shape */
    SylRenderOptions *ro;    /* --view, --size, --samples, --ao, --no-shadows */
    const char *output, *dir, *image; /* -o, --out, --image */
    int format, seeds;       /* CLI_FORMAT_*; --seeds */
    bool steps, interpret, quiet, stats, werror, dump;
    /* sylva terrain: --maps, --cell, --heights, --latitude, --sun-days, --sun-minutes,
     * --wind-from, --wind-distance */
    const char *maps;
    float cell, latitude, sun_minutes, wind_from, wind_distance;
    int sun_days;
    int measures;            /* --measures: SYL_TERRAIN_GIS, _ZAMUDA or _BOTH (0: GIS) */
    double heights[2];
    bool heights_set;
    int fps, frames_per_step; /* sylva animate: --fps, --frames-per-step */
    int snapshots[SYL_ECO_MAX_SNAPSHOTS], nsnapshots, tiles_x, tiles_z; /* sylva ecosystem: --snapshots, --tiles */
    int rebalance, every;    /* --rebalance, --every */
    uint64_t max_plants;     /* --max-plants */
    const char *checkpoint, *resume; /* --checkpoint, --resume */
    int eco_view;            /* sylva ecosystem --view: SylForestView */
    bool glb;                /* sylva ecosystem --glb */
    const char *plants;      /* sylva render --plants */
    bool eco_view_set;       /* sylva render --view bird|walker */
    int lod, billboards;     /* sylva mesh: --lod, --billboards */
    int impostor_grid, impostor_view; /* --impostor-grid, --impostor-view */
    bool impostor;           /* --impostor */
    float wind, wind_dir[2], wind_seconds; /* --wind, --wind-dir, --wind-seconds */
    int wind_levels;         /* --wind-levels */
    int port;                /* sylva view: --port */
    const char *host;        /* --host */
    bool open;               /* --open */
    char **files;            /* the arguments after the options: the models */
    int nfiles;
} CliArgs;

/* Where an option's value goes: a member of one of CliArgs's structs, or of CliArgs. */
typedef enum { CLI_IN_ARGS, CLI_IN_MODEL, CLI_IN_DERIVE, CLI_IN_MESH, CLI_IN_RENDER } CliTarget;
typedef enum {
    CLI_FLAG,    /* bool: true */
    CLI_CHOICE,  /* int: value */
    CLI_TEXT,    /* const char *: the argument */
    CLI_INT,     /* int: a whole number from min to max */
    CLI_COUNT,   /* uint64_t: a whole number from min to max */
    CLI_REAL,    /* float: a number from min to max */
    CLI_SIZE,    /* uint64_t: a size in bytes, 512M or 4G */
    CLI_READ,    /* read(args, argument) reads it */
} CliKind;

/* One option: its names, its argument's name (NULL: none), the help row, what it sets. */
typedef struct CliOption {
    const char *name;  /* --name */
    char letter;       /* -x, or 0 */
    const char *arg;
    const char *help;  /* lines of the row, without the last newline */
    CliKind kind;
    CliTarget in;
    size_t at;         /* offsetof the member in its struct */
    double min, max;   /* CLI_INT, CLI_COUNT, CLI_REAL */
    int value;         /* CLI_CHOICE */
    bool (*read)(CliArgs *a, char *arg); /* CLI_READ; reports the problem and returns false */
} CliOption;

extern const CliOption cli_options[CLI_OPT_COUNT];

/* A command's use of an option, in the order of its --help: the option with the row's text
 * (NULL: the option's own; "": no row, the usage line names it), or a group of uses. A table
 * ends with {0}. */
typedef struct CliUse {
    CliOptionId option;
    const char *help;
    const struct CliUse *group;
} CliUse;

/* Groups that several commands share (their --help rows in this order). */
extern const CliUse cli_limits[];      /* --max-memory, --max-modules, --max-work */
extern const CliUse cli_grow_limits[]; /* --max-metamers, --max-buds */
extern const CliUse cli_derive_uses[]; /* -n, --seed, --set, -j, --age and cli_limits */

#define CLI_EXIT_CODES "Exit codes: 0 ok, 1 the model is wrong, 2 bad command line, 3 limit hit, 4 I/O error.\n"

/* A command: what `sylva --help` says of it, how it runs, and its --help. */
typedef struct CliCommand {
    const char *name;      /* sylva NAME */
    const char *what;      /* its line in `sylva --help` */
    int (*run)(int argc, char **argv);
    const char *usage;     /* after "usage: " */
    const char *about;     /* the paragraph after the usage line */
    const CliUse *options; /* the rows, then --help (never shown) */
    int width;             /* of the rows' first column; 0: 22 */
    const char *epilogue;  /* after the rows, as is */
    void (*more)(FILE *out); /* after the epilogue */
    bool several;          /* one or more models; otherwise exactly one */
    const char *args_error; /* said before the usage when the models are not so many */
} CliCommand;

enum { CLI_RUN = -1 };
/* Read argv's options into a (whose structs the command has set to its defaults) and the
 * models into a->files. CLI_RUN: run the command; otherwise its exit code (after --help, a
 * bad option or value, reported, or a wrong number of models). */
int cli_parse(const CliCommand *cmd, int argc, char **argv, CliArgs *a);
void cli_help(const CliCommand *cmd, FILE *out);
/* Apply one option to a as if given on the command line (arg NULL when it takes none). */
bool cli_apply(CliOptionId id, char *arg, CliArgs *a);
/* Whether cmd takes the option. */
bool cli_takes(const CliCommand *cmd, CliOptionId id);

int cli_format_named(const char *name); /* csv, json: CLI_FORMAT_*; else CLI_FORMAT_NONE */

#endif
