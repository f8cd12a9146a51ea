/* `sylva view`: a local web server (libmicrohttpd) that shows a model file in the browser
 * and follows its edits. cmd_view.c starts it, view_http.c answers the requests, view_build.c
 * turns a request into the bytes `sylva mesh`, `check`, `skeleton` and `render` would write,
 * view_watch.c follows the files with inotify. docs/view.md describes the page. */
#ifndef SYL_CLI_VIEW_H
#define SYL_CLI_VIEW_H
#include <pthread.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cli/cli.h"
#include "sylva/stream.h"

enum { VIEW_CACHE = 8, VIEW_TOKEN = 32, VIEW_TABS = 16 };

/* What the page asks for: a model of the file, with --set values, a seed, a derivation
 * length (the time slider) and the mesh options of `sylva mesh`. */
typedef struct ViewRequest {
    char model[128];       /* "": the file's first model (its scene, when it has one) */
    char names[MAX_SETS][64];
    SylOverride sets[MAX_SETS];
    int nsets;
    bool use_seed;
    uint64_t seed;
    int steps;             /* < 0: the model's `derive` (years of a grow block) */
    int lod;               /* < 0: the model's `lod` setting */
    int leaves;            /* < 0: the mesher's default; else SYL_LEAVES_* */
    float wind;            /* > 0: skinned, swaying (sylva mesh --wind) */
    bool impostor;         /* the last level: an impostor's crossed billboards (--billboards 3) */
    bool preview;          /* a lighter picture first (view_preview.c): not what is exported */
    uint64_t tab;          /* the page that asks (0: none) and its request's number: not part */
    unsigned seq;          /* of what is built, only of whether it is still wanted */
    int width, height;     /* of a picture (export png) */
    const char *text;      /* NULL: the file as it is on disk; else the page's edited text of it
                              (plants placed by clicks), built as if it were the file's */
    size_t text_len;
} ViewRequest;

/* One model built: the .glb, the messages, the figures of --stats, the skeleton. */
typedef struct ViewBuild {
    unsigned id;           /* the page fetches the parts by it; 0: free slot */
    unsigned gen;          /* of the files it was built from */
    char key[2048];        /* the request, as a canonical query */
    int status;            /* SYL_* */
    char *diag;            /* compile and build messages, as `sylva check` prints them */
    char *glb;
    size_t glb_len;
    char *csv;             /* the skeleton (sylva skeleton's CSV) */
    size_t csv_len;
    char *lines;           /* a preview of a big plant: its segments (view_preview.c), no .glb */
    size_t lines_len;
    char *obstacles;       /* a scene's obstacles as a .glb, one node each (NULL: none) */
    size_t obstacles_len;
    char *stats;           /* a JSON object */
    char *metrics;         /* what `sylva compare` measures, as JSON (made when first asked for) */
    double used;           /* when last asked for, for the cache's order */
} ViewBuild;

typedef struct ViewEco ViewEco; /* an ecosystem's run, its years kept (view_eco.c) */

/* A build's plant kept after it (view_metrics.c) */
typedef struct ViewKept {
    SylPlant pl;
    SylBudget *budget; /* what its arrays are counted against */
    unsigned id;       /* its build's */
    int refs;          /* metrics measuring it */
    bool dropped;      /* replaced: freed by the last reference */
} ViewKept;

typedef struct View {
    char path[4096];       /* the model file, as given */
    char dir[4096];        /* its directory */
    char web[4096];        /* the page's files: web/ (and web/node_modules/three) */
    char token[VIEW_TOKEN + 1];
    int threads;
    uint64_t max_memory, max_modules;
    /* Builds are one at a time (the engines use every core already). */
    pthread_mutex_t lock;
    ViewBuild cache[VIEW_CACHE];
    unsigned next_id;
    ViewEco *eco;          /* the last ecosystem run (NULL: none) */
    /* The last build's plant, for its metrics and skeleton: replaced under lock and
     * keep_lock; the metrics hold a reference (under keep_lock) while they measure it beside
     * the next build, which does not wait for them. */
    pthread_mutex_t keep_lock;
    ViewKept *kept;
    SylTextureCache *textures; /* the .glb's procedural textures, encoded once (under lock) */
    /* Each tab's newest request (under gen_lock, on arrival, before the build lock): a full
     * build of an older one stops at its next stage and is not kept — the page moved on. */
    struct { uint64_t tab; unsigned seq; double seen; } tabs[VIEW_TABS];
    /* Changes: gen counts them; waiters (the pages' event streams) are woken at each. */
    pthread_mutex_t gen_lock;
    pthread_cond_t changed;
    unsigned gen;
    unsigned builds, stopped; /* builds begun, and stopped before their end (VIEW_SUPERSEDED) */
    bool stopping;
    /* The first build asked for since the files' last change (under gen_lock): built again at
     * the next change before a page asks (view_prebuild.c). */
    struct { ViewRequest rq; char key[2048]; unsigned gen; bool any, have; } first;
} View;

/* view_build.c */
void view_request_init(ViewRequest *rq);
/* One argument of the page's query (model, seed, n, lod, impostor, leaves, wind, size, set=NAME=VALUE);
 * false with the reason in err. Other names are not the model's and are passed over. */
bool view_request_arg(ViewRequest *rq, const char *key, const char *value, char *err, size_t n);
/* Build (or find in the cache) what rq asks for; returns the entry (v->lock held by the
 * caller). */
ViewBuild *view_build(View *v, const ViewRequest *rq, const char *key);
/* An export through the CLI's writers: format "glb", "obj", "png", "csv". *out malloc'ed;
 * SYL_* status with the messages in *diag (malloc'ed). */
int view_export(View *v, const ViewRequest *rq, const char *format, char **out, size_t *len, char **diag);
/* `"caps":{"rules":false,...}`, every capability the library names (syl_model_cap_name) and
 * whether kind k has it: what the page asks of a build's kind instead of its name. */
void view_caps_json(FILE *f, SylModelKind k);
/* The models of the file as a JSON array text (malloc'ed). */
char *view_models_json(View *v);
/* The parameters of the file's models (syl_describe_json), malloc'ed; NULL with *diag set. */
char *view_describe_json(View *v, const ViewRequest *rq, char **diag);
void view_cache_free(View *v);
/* As open_memstream, for the big outputs (a .glb of many MB): the buffer grows by realloc
 * (no copy of what is there, no zero-filling), *buf and *len are set at fclose. */
FILE *view_bytes_open(char **buf, size_t *len);
/* A library writer that takes a path, into out: written in a private temporary directory as
 * NAME, read back, the directory removed (with what the writer put beside the file). */
typedef int (*ViewPathWriter)(void *ctx, const char *path, FILE *diag);
int view_write_via_file(ViewPathWriter write, void *ctx, const char *name, FILE *out, FILE *diag);

/* view_preview.c: what a preview build changes in the mesh options (fewer sides, leaves as
 * instanced cards); whether a skeleton of that many nodes and leaves is sent as its segments instead of a
 * mesh; those segments (6 floats each, then a byte of branch order each) into *buf (malloc'ed,
 * *len bytes). */
void view_preview_mesh_options(SylMeshOptions *mo);
bool view_preview_as_lines(const SylSkeleton *sk);
int view_preview_lines(const SylSkeleton *sk, bool join, char **buf, size_t *len);
/* The status of a build stopped because the files changed under it or its page moved on
 * (View.tabs): not a SYL_* code */
enum { VIEW_SUPERSEDED = 100 };
/* rq's page asks: its newest request number kept; whether rq is older than its page's newest */
void view_tab_saw(View *v, const ViewRequest *rq);
bool view_tab_moved_on(View *v, const ViewRequest *rq);

/* view_eco.c: an ecosystem block (p, taken over) into slot: the forest .glb of the year
 * rq->steps (< 0: the last; else the nearest kept), the figures as JSON in slot->stats. The
 * run is kept in v->eco for the other years. */
int view_eco_build(View *v, const ViewRequest *rq, SylProgram *p, unsigned gen, FILE *diag, ViewBuild *slot);
/* The PNG of a factor's map (syl_terrain_write_map) of the last ecosystem run. */
int view_eco_map(View *v, const char *name, char **png, size_t *len);
void view_eco_free(ViewEco *e);
/* The .glb of look k's impostor (its crossed billboards) of the last ecosystem run, owned by
 * the run (*glb valid under v->lock until the next run). */
int view_eco_impostor(View *v, int look, const char **glb, size_t *len);

/* view_metrics.c: keep pl and the budget its arrays are counted against (both taken over,
 * zeroed) as build id's plant, the previous one freed */
void view_keep(View *v, unsigned id, SylPlant *pl, SylBudget **budget);
void view_keep_free(View *v);
/* The JSON of the metrics of `sylva compare` (syl_metrics_compute) of build id, malloc'ed (kept in
 * its cache entry too); NULL when its plant is no longer kept or the metrics failed (*diag
 * says why, malloc'ed). Called without v->lock: a build may run beside it. */
char *view_metrics(View *v, unsigned id, char **diag);

/* view_prebuild.c: rq (its key) is a page's build request: kept when it is the first since the
 * last change; a thread that builds the kept one at each change (stops when v->stopping is set
 * and v->changed broadcast) */
void view_first_request(View *v, const ViewRequest *rq, const char *key);
bool view_prebuild_start(View *v, pthread_t *thread);

/* view_watch.c: follow the file and every file it names; bump v->gen at each change. */
bool view_watch_start(View *v, pthread_t *thread, int *stop_fd);
void view_watch_stop(pthread_t thread, int stop_fd);
void view_changed(View *v); /* gen++ and wake the streams */

/* view_http.c */
struct MHD_Daemon;
struct MHD_Daemon *view_http_start(View *v, const char *host, int port, int *bound_port);

#endif
