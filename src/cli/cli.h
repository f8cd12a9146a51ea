/* Shared pieces of the `sylva` subcommands. */
#ifndef SYL_CLI_H
#define SYL_CLI_H
#include <stdbool.h>
#include <stdio.h>

#include "cli/options.h"
#include "sylva/grow.h"
#include "sylva/mesh.h"
#include "sylva/plant.h"
#include "sylva/render.h"
#include "sylva/skeleton.h"
#include "sylva/sylva.h"
#include "util/diag.h"
#include "util/outfile.h"

enum { MAX_SETS = 64, MAX_ALLOW_PATHS = 64 };

/* What every command that compiles a model accepts. */
typedef struct ModelArgs {
    const char *spec;  /* FILE or FILE:Model, as typed */
    char path[4096];
    const char *model; /* NULL: the first */
    SylOverride sets[MAX_SETS];
    int nsets;
    uint64_t max_metamers, max_buds; /* --max-metamers, --max-buds (grow blocks, scenes) */
    float age;         /* --age (strands blocks); 0: full grown */
    int levels;        /* --levels (weber blocks); 0: the block's Levels */
    bool warned;       /* its warnings were printed (cli_compile) */
    const char *allow[MAX_ALLOW_PATHS]; /* --allow-path: more folders the files it names may be in */
    int nallow;
} ModelArgs;

/* The sink the commands give the library: its records printed on stderr as text. */
extern const SylSink cli_sink;
/* The text sink of a stream (NULL: none), for a call that reports to a sink; it lives in the
 * block where it is named. */
#define cli_text_sink(f) diag_sink(&(SylSink){0}, (f), NULL)

/* Split FILE:Model. */
void cli_model_spec(ModelArgs *m, const char *spec);
/* Parse `name=value` for --set; prints the problem and returns false on error. */
bool cli_set(ModelArgs *m, char *arg);
bool cli_number(const char *opt, const char *arg, double min, double max, double *out);
bool cli_integer(const char *opt, const char *arg, double min, double max, double *out);
bool cli_size(const char *opt, const char *arg, unsigned long long *out); /* 512M, 2G */
/* Compile with the warnings warn (SYL_WARN_*), printed the first time only. */
SylProgram *cli_compile(ModelArgs *m, int warn, int *status);

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
    SylMesh **parts; /* a scene's objects (SylPlant's) */
    int nparts;
    size_t modules;
    char name[64];  /* the model's name */
    double derive_s, turtle_s, mesh_s;
    double derive_cpu_s; /* SylPlant's: the derivation's, growth's or tree's processor time */
    double mesh_cpu_s;   /* SylPlant's: the mesher's */
    bool grown;          /* a grow block or a scene: see grow */
    SylGrowStats grow;   /* its counts and times (derive_s is then the growth) */
    int lod;             /* the model's `lod` setting (0: none) */
} Plant;
int cli_plant(ModelArgs *m, SylDeriveOptions *d, const SylMeshOptions *mo, Plant *out);
void cli_plant_free(Plant *pl);

/* Outputs through util/outfile: "-" (or NULL) is standard output, FIFOs and devices are
 * written through, files through a temporary file that a signal removes (cli_temp_hooks). */
bool out_open(OutFile *o, const char *path); /* reported when false */
int out_close(OutFile *o, int status);       /* commit when status is SYL_OK; SYL_EIO when writing failed */
extern const OutHooks cli_temp_hooks;        /* main.c: the temporary files a signal removes */
/* ffmpeg.c: the child running now (ffmpeg), which main.c's signal handler stops and waits
 * for before removing the temporary files: noted, forgotten, and taken (0: none). */
void cli_child_started(int pid);
void cli_child_gone(void);
int cli_child_take(void); /* async-signal-safe */
/* A signal that came while ffmpeg was being started: kept (true), acted on by the function
 * main.c gives (stop the child, remove the temporary files, die of it) once the pid is
 * noted; false: none is being started. */
bool cli_child_defer(int sig); /* async-signal-safe */
void cli_child_on_signal(void (*stop)(int sig));

bool cli_view(const char *arg, SylView *v);                 /* --view */
bool cli_view_or(const char *arg, SylView *v, const char *also); /* the same, naming other views */
bool cli_picture_size(const char *arg, int *w, int *h);    /* --size WxH */

/* [DIR/]NAME.EXT where NAME is the model named in FILE:Model, else the file's name without
 * its extension (free it). */
char *cli_output_name(const ModelArgs *m, const char *dir, const char *ext);

double cli_now(void);
/* Processor time of the whole process (every thread), for figures a loaded machine skews. */
double cli_cpu_now(void);
double cli_peak_mb(void);

int cmd_derive(int argc, char **argv);
int cmd_check(int argc, char **argv);
int cmd_compile(int argc, char **argv);
int cmd_describe(int argc, char **argv);
int cmd_skeleton(int argc, char **argv);
int cmd_mesh(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_plant(int argc, char **argv); /* sylva FILE */
int cmd_grow(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_convert(int argc, char **argv);
int cmd_terrain(int argc, char **argv);
int cmd_ecosystem(int argc, char **argv);
int cmd_view(int argc, char **argv);
/* sylva render FILE --plants CSV (snapshot.c): a saved ecosystem snapshot, split over MPI ranks */
int cli_render_snapshot(CliArgs *a, ModelArgs *m, SylDeriveOptions *d, SylRenderOptions *ro);

/* Each command's options and --help (cli/options.h), beside its cmd_ function. */
extern const CliCommand cli_derive_command, cli_check_command, cli_compile_command, cli_skeleton_command,
    cli_mesh_command, cli_render_command, cli_grow_command, cli_compare_command,
    cli_convert_command, cli_terrain_command, cli_animate_command, cli_ecosystem_command, cli_describe_command;
extern const CliCommand cli_view_command; /* sylva view (cmd_view.c) */
extern const CliCommand cli_plant_command; /* sylva FILE */
/* The commands, in the order `sylva --help` lists them; NULL ends the list. */
extern const CliCommand *const cli_commands[];

#endif
