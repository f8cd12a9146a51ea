/* Shared pieces of the `sylva` subcommands. */
#ifndef SYL_CLI_H
#define SYL_CLI_H
#include <stdbool.h>
#include <stdio.h>

#include "sylva/grow.h"
#include "sylva/mesh.h"
#include "sylva/plant.h"
#include "sylva/render.h"
#include "sylva/skeleton.h"
#include "sylva/sylva.h"
#include "util/outfile.h"

enum { MAX_SETS = 64 };

/* What every command that compiles a model accepts. */
typedef struct ModelArgs {
    const char *spec;  /* FILE or FILE:Model, as typed */
    char path[4096];
    const char *model; /* NULL: the first */
    SylOverride sets[MAX_SETS];
    int nsets;
    uint64_t max_metamers, max_buds; /* --max-metamers, --max-buds (grow blocks, scenes) */
} ModelArgs;

/* Split FILE:Model. */
void cli_model_spec(ModelArgs *m, const char *spec);
/* Parse `name=value` for --set; prints the problem and returns false on error. */
bool cli_set(ModelArgs *m, char *arg);
bool cli_number(const char *opt, const char *arg, double min, double max, double *out);
bool cli_integer(const char *opt, const char *arg, double min, double max, double *out);
bool cli_size(const char *opt, const char *arg, unsigned long long *out); /* 512M, 2G */
SylProgram *cli_compile(ModelArgs *m, int lint, int *status);

/* The resource limits (docs/cli.md, "Resource limits"), each stopping with exit code 3 and a
 * message that names it: CLI_LIMIT_OPTIONS for every command that derives, and
 * CLI_GROW_LIMITS too for those that grow. cli_derive_option applies them all. */
#define CLI_LIMIT_OPTIONS                                                                      \
    {"max-modules", required_argument, 0, 'M'}, {"max-memory", required_argument, 0, 'm'},     \
        {"max-work", required_argument, 0, 'W'}
#define CLI_GROW_LIMITS {"max-metamers", required_argument, 0, 'T'}, {"max-buds", required_argument, 0, 'B'}
#define CLI_LIMIT_HELP                                                                         \
    "  --max-memory SIZE     stop with exit code 3 beyond SIZE of memory for strings, trees,\n" \
    "                        meshes and pictures, e.g. 2G (default: half the machine's\n"       \
    "                        memory, at most 16G)\n"                                            \
    "  --max-modules N       stop with exit code 3 beyond N modules in a string\n"              \
    "                        (default 200000000)\n"                                             \
    "  --max-work N          stop with exit code 3 beyond N modules rewritten by all steps\n"   \
    "                        of a derivation (default 100000000000)\n"
#define CLI_GROW_LIMIT_HELP                                                                    \
    "  --max-metamers N      stop with exit code 3 beyond N metamers (default 20000000)\n"      \
    "  --max-buds N          stop with exit code 3 beyond N buds (default 100000000)\n"
/* Options of every command that derives a model: -n, --seed, --set, -j and the limits. Put
 * CLI_DERIVE_OPTIONS in the getopt_long table, CLI_DERIVE_SHORT in the short options, and
 * hand every option to cli_derive_option. */
#define CLI_DERIVE_OPTIONS                                                                     \
    {"derive", required_argument, 0, 'n'}, {"seed", required_argument, 0, 's'},                \
        {"set", required_argument, 0, 'S'}, {"threads", required_argument, 0, 'j'}, CLI_LIMIT_OPTIONS
#define CLI_DERIVE_SHORT "n:j:"
#define CLI_DERIVE_HELP                                                                        \
    "  -n, --derive N        derivation steps (default: the model's `derive`)\n"               \
    "  --seed S              random seed (default: the model's `seed`)\n"                      \
    "  --set NAME=VALUE      override a `param` of the model (repeatable)\n"                   \
    "  -j, --threads N       threads (default: all cores); the output never depends on N\n"    \
    CLI_LIMIT_HELP
/* 1: c is one of those options and was applied; 0: it is not; -1: bad value (reported). */
int cli_derive_option(int c, char *arg, ModelArgs *m, SylDeriveOptions *d);
/* A progress bar on stderr, shown only when stderr is a terminal and the work has taken
 * more than a second. */
typedef struct Progress {
    const char *label;
    double start, last;
    bool enabled, shown;
} Progress;
void cli_progress_start(Progress *p, const char *label);
void cli_progress(void *progress, double fraction); /* 0..1; 1 clears the line */

/* The whole way from a model to a skeleton and (if mo is not NULL) a mesh: syl_plant_build
 * (sylva/plant.h) with a progress bar per derivation step or year. Free with cli_plant_free. */
typedef struct Plant {
    SylSkeleton *sk;
    SylMesh *mesh;
    size_t modules;
    char name[64];  /* the model's name */
    double derive_s, turtle_s, mesh_s;
    bool grown;          /* a grow block or a scene: see grow */
    SylGrowStats grow;   /* its counts and times (derive_s is then the growth) */
} Plant;
int cli_plant(ModelArgs *m, SylDeriveOptions *d, const SylMeshOptions *mo, Plant *out);
void cli_plant_free(Plant *pl);

/* Outputs through util/outfile: "-" (or NULL) is standard output, FIFOs and devices are
 * written through, files through a temporary file that a signal removes (cli_temp_hooks). */
bool out_open(OutFile *o, const char *path); /* reported when false */
int out_close(OutFile *o, int status);       /* commit when status is SYL_OK; SYL_EIO when writing failed */
extern const OutHooks cli_temp_hooks;        /* main.c: the temporary files a signal removes */

bool cli_view(const char *arg, SylView *v);                 /* --view */
bool cli_picture_size(const char *arg, int *w, int *h);    /* --size WxH */

/* [DIR/]NAME.EXT where NAME is the model named in FILE:Model, else the file's name without
 * its extension (free it). */
char *cli_output_name(const ModelArgs *m, const char *dir, const char *ext);

double cli_now(void);
double cli_peak_mb(void);

int cmd_derive(int argc, char **argv);
int cmd_check(int argc, char **argv);
int cmd_compile(int argc, char **argv);
int cmd_skeleton(int argc, char **argv);
int cmd_mesh(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_plant(int argc, char **argv); /* sylva FILE */
int cmd_grow(int argc, char **argv);
int cmd_compare(int argc, char **argv);

#endif
