/* sylva ecosystem: run an `ecosystem` block (docs/ecosystem.md) and write its plant tables,
 * species counts and cover (CSV and an SVG chart), the terrain's factor maps, and per
 * snapshot a top-down map, a rendered picture of the plants as instances of their species'
 * looks, and (--glb) the scene as a .glb. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "cli/cli.h"
#include "cli/testfaults.h"
#include "sylva/ecosystem.h"
#include "sylva/forest.h"
#include "sylva/render.h"
#include "sylva/stream.h"
#include "sylva/texture.h"

const CliCommand cli_ecosystem_command = {
    .name = "ecosystem",
    .what = "simulate an ecosystem block on its terrain; plant tables, charts, maps",
    .run = cmd_ecosystem,
    .usage = "sylva ecosystem FILE[:Model] -o DIR [options]",
    .about = "Run the model's `ecosystem` block year by year on its terrain (docs/ecosystem.md) and\n"
             "write into DIR: plants-YEAR.csv, map-YEAR.png (top-down) and view-YEAR.png (each\n"
             "species' model meshed once per age class, every plant an instance of it on the\n"
             "terrain, rendered with the sun and shadows) for every snapshot, species.csv and\n"
             "species.svg (counts and cover per year) and maps/FACTOR.png|asc (the terrain's\n"
             "factors). The output never depends on -j nor on --tiles.\n"
             "\n"
             "Under `mpirun -np N` (a build with MPI) the tiles are spread over the N ranks (default\n"
             "tiling: 4N x 1, at most one tile per column), which exchange their borders and seeds\n"
             "every year; rank 0 writes the same files as one process (docs/distributed.md).\n",
    .options = (const CliUse[]){
        {.option = CLI_OPT_OUTPUT, .help = "the directory to write into (made if missing)"},
        {.option = CLI_OPT_ECO_YEARS},
        {.option = CLI_OPT_SNAPSHOTS},
        {.option = CLI_OPT_TILES},
        {.option = CLI_OPT_REBALANCE},
        {.option = CLI_OPT_CHECKPOINT},
        {.option = CLI_OPT_EVERY},
        {.option = CLI_OPT_RESUME},
        {.option = CLI_OPT_SEED},
        {.option = CLI_OPT_SET},
        {.option = CLI_OPT_MAX_MEMORY},
        {.option = CLI_OPT_MAX_PLANTS},
        {.option = CLI_OPT_ALLOW_PATH},
        {.option = CLI_OPT_THREADS, .help = "threads over the tiles (default: all cores); the output\n"
                                            "never depends on N"},
        {.option = CLI_OPT_ECO_VIEW},
        {.option = CLI_OPT_SIZE, .help = "view-YEAR.png's size (default 1280x720)"},
        {.option = CLI_OPT_SAMPLES},
        {.option = CLI_OPT_NO_SHADOWS},
        {.option = CLI_OPT_GLB},
        {.option = CLI_OPT_STATS, .help = "print plant-years, plants per second, memory and each picture's\n"
                                          "camera, instances and time to stderr"},
        {0},
    },
    .width = 24,
    .epilogue = "\nExit codes: 0 ok, 1 the model or its DEM is malformed, 2 bad command line, 3 limit hit,\n"
                "4 I/O error (under mpirun: a rank failed or was killed, or stopped answering for\n"
                "SYLVA_RANK_TIMEOUT seconds, default 600; the job is aborted).\n",
    .args_error = "expects one model file",
};

typedef struct Run {
    const char *dir;
    const SylEcoModel *m;
    const SylTerrain *t;
    SylEcoYear *years;
    int nyears, cap;
    Progress bar;
    int status;
    int rank;
    const char *checkpoint; /* the checkpoint file, or NULL */
    uint64_t hash;
    const SylForest *forest;
    const SylRenderOptions *ro;
    int view;         /* SylForestView */
    bool glb, stats;
} Run;

static char *path_in(const char *dir, const char *fmt, int n) {
    size_t len = strlen(dir) + 64;
    char *p = malloc(len);
    if (!p) return NULL;
    int k = snprintf(p, len, "%s/", dir);
    snprintf(p + k, len - (size_t)k, fmt, n);
    return p;
}

static int make_dir(const char *dir) {
    if (mkdir(dir, 0777) && errno != EEXIST) {
        fprintf(stderr, "sylva: error: cannot make the directory '%s': %s\n", dir, strerror(errno));
        return SYL_EIO;
    }
    return SYL_OK;
}

static void on_year(void *user, const SylEcoYear *y) {
    Run *r = user;
    if (r->nyears == r->cap) {
        int cap = r->cap ? 2 * r->cap : 256;
        SylEcoYear *v = realloc(r->years, (size_t)cap * sizeof *v);
        if (!v) {
            r->status = SYL_ELIMIT;
            return;
        }
        r->years = v;
        r->cap = cap;
    }
    r->years[r->nyears++] = *y;
    cli_test_fault_year(r->rank, y->year);
}

static int on_checkpoint(void *user, int year, const SylEcoPlant *plants, size_t n) {
    Run *r = user;
    if (r->nyears != year) return SYL_ELIMIT; /* the counts of every year so far go with it */
    SylEcoCheckpoint c = {.model_hash = r->hash, .year = year, .years = r->years,
                          .plants = (SylEcoPlant *)plants, .nplants = n};
    int st = syl_ecosystem_checkpoint_write(r->checkpoint, &c, &cli_sink);
    if (!st) printf("%s\n", r->checkpoint);
    return st;
}

/* map-YEAR.png (syl_ecosystem_draw_map) */
static int write_map(Run *r, int year, const SylEcoPlant *plants, size_t n) {
    SylPicture pic = {0};
    char *path = path_in(r->dir, "map-%d.png", year);
    int st = path ? syl_ecosystem_draw_map(r->m, r->t, plants, n, NULL, &pic) : SYL_ELIMIT;
    if (!st) st = syl_png_write(path, pic.rgb, pic.width, pic.height, &cli_sink);
    if (!st) printf("%s\n", path);
    syl_picture_free(&pic);
    free(path);
    return st;
}

static int write_table(Run *r, int year, const SylEcoPlant *plants, size_t n) {
    char *path = path_in(r->dir, "plants-%d.csv", year);
    if (!path) return SYL_ELIMIT;
    OutFile o;
    if (!out_open(&o, path)) {
        free(path);
        return SYL_EIO;
    }
    fprintf(o.f, "%s\n", syl_ecosystem_table_header);
    for (size_t j = 0; j < n; j++) syl_ecosystem_table_write_row(o.f, r->m, r->t, &plants[j]);
    int st = out_close(&o, SYL_OK);
    if (!st) printf("%s\n", path);
    free(path);
    return st;
}

/* A field of /proc/self/status in kB (VmRSS: resident now; VmHWM: its high-water mark), -1 if
 * not there. */
static long status_kb(const char *field) {
    FILE *f = fopen("/proc/self/status", "r");
    if (!f) return -1;
    char line[256];
    long kb = -1;
    size_t n = strlen(field);
    while (kb < 0 && fgets(line, sizeof line, f))
        if (!strncmp(line, field, n) && line[n] == ':') kb = strtol(line + n + 1, NULL, 10);
    fclose(f);
    return kb;
}

/* Resets the high-water mark of resident memory (Linux's clear_refs 5), so that VmHWM after
 * the simulation less VmRSS before it is the simulation's own peak. */
static bool reset_peak(void) {
    FILE *f = fopen("/proc/self/clear_refs", "w");
    if (!f) return false;
    bool ok = fputs("5", f) >= 0;
    return fclose(f) == 0 && ok;
}

static void progress(void *user, double fraction) { cli_progress(&((Run *)user)->bar, fraction); }

static double cpu_now(void) { /* every thread's processor time */
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* view-YEAR.png: the plants as instances over the terrain, from the chosen camera. */
static int write_view(Run *r, int year, const SylEcoPlant *plants, size_t n) {
    SylRenderOptions ro = *r->ro;
    if (!ro.width) ro.width = 1280, ro.height = 720;
    SylRenderCamera cam;
    syl_forest_camera(r->forest, (SylForestView)r->view, ro.width, ro.height, &cam);
    uint8_t *rgb = malloc((size_t)ro.width * (size_t)ro.height * 3);
    char *path = path_in(r->dir, "view-%d.png", year);
    SylRenderCounts counts;
    double t0 = cli_now(), c0 = cpu_now();
    int st = rgb && path ? syl_forest_render(r->forest, plants, n, &cam, &ro, NULL, 0, rgb, &counts) : SYL_ELIMIT;
    double wall = cli_now() - t0, cpu = cpu_now() - c0;
    if (!st) st = syl_png_write(path, rgb, ro.width, ro.height, &cli_sink);
    if (!st) printf("%s\n", path);
    if (!st && r->stats)
        fprintf(stderr, "view %d: camera %.3f %.3f %.3f target %.3f %.3f %.3f fov %.3f size %d %d\n"
                        "view %d: %zu instances drawn (%zu coarse), %zu culled; %.3f s wall, %.3f s cpu\n",
                year, cam.eye[0], cam.eye[1], cam.eye[2], cam.target[0], cam.target[1], cam.target[2], cam.fov,
                ro.width, ro.height, year, counts.drawn, counts.coarse, counts.culled, wall, cpu);
    free(rgb), free(path);
    return st;
}

static int write_glb(Run *r, int year, const SylEcoPlant *plants, size_t n) {
    char *path = path_in(r->dir, "forest-%d.glb", year);
    int st = path ? syl_forest_write_glb(r->forest, plants, n, 0, path, &cli_sink) : SYL_ELIMIT;
    if (!st) printf("%s\n", path);
    free(path);
    return st;
}

static int on_snapshot(void *user, int year, const SylEcoPlant *plants, size_t n) {
    Run *r = user;
    int st = write_table(r, year, plants, n);
    if (!st) st = write_map(r, year, plants, n);
    if (!st) st = write_view(r, year, plants, n);
    if (!st && r->glb) st = write_glb(r, year, plants, n);
    return st;
}

static int write_species_csv(Run *r) {
    char *path = path_in(r->dir, "species.csv", 0);
    OutFile o;
    if (!path || !out_open(&o, path)) {
        free(path);
        return path ? SYL_EIO : SYL_ELIMIT;
    }
    /* mortality zamuda: the year's deaths by cause too (stress is not one of his) */
    bool by_cause = r->m->mortality == SYL_ECO_PER_FACTOR;
    fprintf(o.f, "year,species,count,cover,mean_height");
    for (int c = 0; by_cause && c < SYL_ECO_DEATH_CAUSES; c++)
        if (c != SYL_ECO_DEATH_STRESS) fprintf(o.f, ",died_%s", syl_ecosystem_death_name((SylEcoDeath)c));
    fputc('\n', o.f);
    for (int y = 0; y < r->nyears; y++)
        for (int s = 0; s < r->m->nspecies; s++) {
            fprintf(o.f, "%d,", r->years[y].year);
            syl_ecosystem_write_csv_text(o.f, r->m->species[s].name);
            fprintf(o.f, ",%u,%.6f,%.3f", r->years[y].count[s], r->years[y].cover[s], r->years[y].mean_height[s]);
            for (int c = 0; by_cause && c < SYL_ECO_DEATH_CAUSES; c++)
                if (c != SYL_ECO_DEATH_STRESS) fprintf(o.f, ",%u", r->years[y].deaths[s][c]);
            fputc('\n', o.f);
        }
    int st = out_close(&o, SYL_OK);
    if (!st) printf("%s\n", path);
    free(path);
    return st;
}

/* species.svg (syl_ecosystem_draw_chart) */
static int write_chart(Run *r) {
    char *svg = NULL, *path = path_in(r->dir, "species.svg", 0);
    size_t len = 0;
    OutFile o;
    int st = path ? syl_ecosystem_draw_chart(r->m, r->years, r->nyears, NULL, &svg, &len) : SYL_ELIMIT;
    if (!st && out_open(&o, path)) {
        fwrite(svg, 1, len, o.f);
        st = out_close(&o, SYL_OK);
    } else if (!st)
        st = SYL_EIO;
    if (!st) printf("%s\n", path);
    free(path), free(svg);
    return st;
}

static int write_maps(const SylTerrain *t, const char *dir) {
    char *maps = path_in(dir, "maps", 0);
    int st = maps ? make_dir(maps) : SYL_ELIMIT;
    for (int f = 0; !st && f < SYL_TERRAIN_FACTORS; f++)
        for (int e = 0; !st && e < 2 && t->factor[f]; e++) {
            size_t len = strlen(maps) + 32;
            char *path = malloc(len);
            if (!path) {
                st = SYL_ELIMIT;
                break;
            }
            snprintf(path, len, "%s/%s.%s", maps, syl_terrain_factor_name((SylTerrainFactor)f), e ? "asc" : "png");
            st = syl_terrain_write_map(t, (SylTerrainFactor)f, path, &cli_sink);
            if (!st) printf("%s\n", path);
            free(path);
        }
    free(maps);
    return st;
}

int cmd_ecosystem(int argc, char **argv) {
    ModelArgs m = {0};
    SylDeriveOptions d = {0};
    SylRenderOptions ro = {0};
    CliArgs a = {.m = &m, .d = &d, .ro = &ro};
    int done = cli_parse(&cli_ecosystem_command, argc, argv, &a);
    if (done != CLI_RUN) return done;
    if (!a.output) {
        fprintf(stderr, "sylva: error: ecosystem needs -o DIR, the directory to write into\n");
        return SYL_EUSAGE;
    }
    cli_model_spec(&m, a.files[0]);
    int st;
    SylProgram *p = cli_compile(&m, 1, &st);
    if (!p) return st;
    if (syl_program_kind(p) != SYL_MODEL_ECOSYSTEM) {
        fprintf(stderr, "sylva: error: '%s' is a %s, not an ecosystem block (name one: FILE:Model)\n",
                syl_program_name(p), syl_model_kind_name(syl_program_kind(p)));
        syl_program_free(p);
        return SYL_EUSAGE;
    }
    static SylEcoModel model; /* 14 kB: off the stack */
    SylEcoMpi *mpi = syl_ecosystem_mpi_start(NULL, NULL, &cli_sink); /* NULL: one process */
    int rank = syl_ecosystem_mpi_rank(mpi), nranks = syl_ecosystem_mpi_size(mpi);
    bool writer = rank == 0;
    ro.threads = d.threads;
    ro.diag = stderr;
    Run r = {.dir = a.output, .m = &model, .rank = rank, .ro = &ro, .view = a.eco_view, .glb = a.glb, .stats = a.stats};
    SylEcoOptions o = {.years = d.steps, .snapshots = a.nsnapshots ? a.snapshots : NULL, .nsnapshots = a.nsnapshots,
                       .tiles_x = a.tiles_x, .tiles_z = a.tiles_z, .threads = d.threads, .use_seed = d.use_seed,
                       .seed = d.seed, .on_year = on_year, .on_snapshot = on_snapshot, .progress = writer ? progress : NULL,
                       .user = &r, .diag = stderr, .max_plants = a.max_plants ? a.max_plants : 100000000};
    SylBudget *budget = o.budget = syl_budget_new(d.max_memory); /* the DEM, its grids and the plants */
    SylTerrain *t = NULL;
    SylEcoStats stats = {0};
    SylEcoCheckpoint ck = {0};
    char *ck_path = NULL;
    double rss_delta = -1; /* bytes: the simulation's peak resident memory beyond what was there */
    /* the block and its DEM are read before the directory is made: a bad one makes none */
    st = budget ? syl_ecosystem_load(p, &o, &model, &t) : SYL_ELIMIT;
    r.t = t;
    if (!st) r.hash = syl_ecosystem_hash(&model, t, d.use_seed ? d.seed : model.seed);
    int years = o.years > 0 ? o.years : model.years;
    const int *snaps = a.nsnapshots ? a.snapshots : model.snapshots;
    for (int i = a.nsnapshots ? a.nsnapshots : model.nsnapshots; !st && writer && i-- > 0 && snaps[i] > years;)
        fprintf(stderr, "sylva: warning: the snapshot of year %d is past the run's last year (%d): it is not written\n",
                snaps[i], years);
    if (!st && a.resume) {
        char *path = path_in(a.resume, "ecosystem.ckpt", 0);
        st = path ? syl_ecosystem_checkpoint_read(path, &ck, writer ? &cli_sink : NULL) : SYL_ELIMIT;
        if (!st && ck.model_hash != r.hash) {
            if (writer) fprintf(stderr, "sylva: error: the checkpoint '%s' was made from another model, terrain or seed\n", path);
            st = SYL_EUSAGE;
        } else if (!st && ck.year >= years) {
            if (writer) fprintf(stderr, "sylva: error: the checkpoint '%s' is at year %d, the run ends at %d\n", path, ck.year, years);
            st = SYL_EUSAGE;
        }
        if (!st) st = syl_ecosystem_checkpoint_check(&ck, &model, t, path, writer ? &cli_sink : NULL); /* as the run makes them */
        free(path);
        if (!st) {
            r.years = ck.years, r.nyears = r.cap = ck.year; /* the counts so far */
            ck.years = NULL;
            o.start_year = ck.year, o.start = ck.plants, o.nstart = ck.nplants;
        }
    }
    if (!st && a.checkpoint) {
        o.every = a.every > 0 ? a.every : 10;
        o.on_checkpoint = on_checkpoint;
        r.checkpoint = ck_path = path_in(a.checkpoint, "ecosystem.ckpt", 0);
        struct stat sb;
        if (!ck_path) st = SYL_ELIMIT;
        else if (writer && !(st = make_dir(a.checkpoint)) && (stat(a.checkpoint, &sb) || !S_ISDIR(sb.st_mode))) {
            fprintf(stderr, "sylva: error: --checkpoint expects a directory, and '%s' is not one\n", a.checkpoint);
            st = SYL_EUSAGE; /* before the run, not at its first checkpoint */
        }
    }
    if (mpi) { /* the tiles over the ranks; a rank that failed above still joins the check below */
        if (!st && !o.tiles_x) {
            o.tiles_x = 4 * nranks < t->nx ? 4 * nranks : t->nx;
            o.tiles_z = 1;
        }
        int ntiles = o.tiles_x * (o.tiles_z > 0 ? o.tiles_z : 1);
        if (!st && ntiles < nranks) {
            if (writer) fprintf(stderr, "sylva: error: %d tiles for %d ranks: give --tiles at least one per rank\n", ntiles, nranks);
            st = SYL_EUSAGE;
        }
        o.exchange = syl_ecosystem_mpi_exchange(mpi, st ? nranks : ntiles, a.rebalance);
    }
    SylForest *forest = NULL; /* the pictures are the writer's */
    /* the run's: every year's .glb copies the same procedural textures (NULL: made each time) */
    SylTextureCache *textures = writer && a.glb ? syl_texture_cache_new() : NULL;
    if (!st && writer)
        st = syl_forest_new(p, &model, t,
                            &(SylForestOptions){.threads = d.threads, .diag = stderr, .textures = textures}, &forest);
    r.forest = forest;
    if (!st && writer) st = make_dir(a.output);
    if (!st && writer && !a.resume) st = write_maps(t, a.output);
    if (o.exchange) { /* every rank goes on, or none (a rank whose files differ stops them all) */
        int64_t e = st != SYL_OK;
        o.exchange->sum(o.exchange->ctx, &e, 1);
        if (e && !st) st = SYL_EIO;
    }
    if (!st) {
        if (writer) cli_progress_start(&r.bar, "years");
        long before = a.stats && reset_peak() ? status_kb("VmRSS") : -1;
        st = syl_ecosystem_simulate(&model, t, &o, &stats);
        long peak = before >= 0 ? status_kb("VmHWM") : -1;
        rss_delta = before >= 0 && peak >= 0 ? (double)(peak - before) * 1024 : -1;
        if (writer) cli_progress(&r.bar, 1);
    }
    if (!st) st = r.status;
    if (!st && writer) st = write_species_csv(&r);
    if (!st && writer) st = write_chart(&r);
    if (!st && a.stats && writer) {
        fprintf(stderr, "plant-years: %llu\npeak plants: %zu\nbytes per plant: %zu\n",
                (unsigned long long)stats.plant_years, stats.peak_plants, stats.bytes_per_plant);
        if (rss_delta >= 0 && stats.peak_plants)
            fprintf(stderr, "peak memory delta: %.2f MB, %.0f bytes per plant\n", rss_delta / 1048576,
                    rss_delta / stats.peak_plants);
        fprintf(stderr, "simulation: %.3f s wall, %.3f s cpu\nplant-years per second: %.0f\n", stats.seconds,
                stats.cpu_seconds, stats.seconds > 0 ? stats.plant_years / stats.seconds : 0);
    }
    if (!st && a.stats && mpi) { /* each rank its own traffic, for bench/run */
        uint64_t sent, bytes, halo, moved, barriers;
        syl_ecosystem_mpi_traffic(mpi, &sent, &bytes, &halo, &moved, &barriers);
        fprintf(stderr, "rank %d: plants sent %llu, bytes sent %llu, halo plants received %llu, plants moved in %llu, cpu %.3f s\n",
                rank, (unsigned long long)sent, (unsigned long long)bytes, (unsigned long long)halo,
                (unsigned long long)moved, stats.cpu_seconds);
    }
    syl_ecosystem_checkpoint_free(&ck);
    free(ck_path);
    free(r.years);
    syl_forest_free(forest);
    syl_texture_cache_free(textures);
    syl_terrain_free(t);
    syl_budget_free(budget);
    syl_program_free(p);
    syl_ecosystem_mpi_end(mpi);
    return st;
}
