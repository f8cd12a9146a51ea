/* libsylva: ecosystems on a terrain — an `ecosystem` block's species spread, compete and die
 * year by year on a DEM's factors (Zamuda 2006; Deussen et al. 1998; Lane & Prusinkiewicz
 * 2002). docs/ecosystem.md lists the directives and the formulas.
 *
 * The terrain is cut into tiles that exchange their border plants (a halo as wide as the
 * largest interaction) and the seedlings that sprout in a neighbour through SylEcoExchange,
 * so a run over N × M tiles, on any number of threads, gives the same plants byte for byte as one
 * tile: every random draw is keyed by (plant id, year, purpose) and every plant id is made
 * from its parent's id or its arrival cell, never from a counter. */
#ifndef SYLVA_ECOSYSTEM_H
#define SYLVA_ECOSYSTEM_H
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "sylva/sylva.h"
#include "sylva/terrain.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { SYL_ECO_MAX_SPECIES = 32, SYL_ECO_MAX_SNAPSHOTS = 64, SYL_ECO_MAX_YEARS = 60000 /* `years`, --years */ };
enum { SYL_ECO_FREE = 0, SYL_ECO_DOMINATED = 1 }; /* SylEcoPlant.state */

/* One plant: 32 bytes. Its altitude is the terrain's at (x, z); its ecological radius is its
 * species' radius_ratio × height. A renderer places the species' model at (x, y, z), scaled
 * to the height. */
typedef struct SylEcoPlant {
    uint64_t id;      /* unique, made from the parent's id or the arrival's cell and year */
    float x, z;       /* position on the terrain */
    float height;     /* metres */
    float vigour;     /* 0..1: how well the site suits the species */
    uint16_t age;     /* years */
    uint8_t species;  /* index into the block's species */
    uint8_t state;    /* SYL_ECO_FREE or SYL_ECO_DOMINATED (last year's competition) */
    uint32_t cell;    /* the terrain cell it stands on, k nx + i (a tile keeps its plants by cell) */
} SylEcoPlant;

typedef struct SylEcoSpecies {
    char name[48], model[64]; /* its name; the Sylva model that is its look ("" : none) */
    double maturity, old_age, max_age;  /* years: seeds from maturity, no growth after old_age,
                                           death at an age drawn in [old_age, max_age] */
    double height_max, growth_rate, start_height; /* Chapman–Richards: h' = v r (H − h) */
    double radius_ratio;     /* ecological radius / height */
    double seeds;            /* seeds a free mature plant makes per year at vigour 1 */
    double dispersal;        /* σ of the Gaussian distance of a seed from its parent, metres;
                                cut off at 3σ */
    double arrivals;         /* seeds arriving at random, per hectare per year */
    double arrive_until;     /* the last year of arrivals (0: every year): a planted stand */
    double shade_tolerance;  /* yearly survival of a dominated plant */
    double stress_mortality; /* yearly death probability at vigour 0 (× (1 − v)) */
    /* tolerance curves by factor (SylTerrainFactor): optimum, range, falloff; set: given */
    double optimum[SYL_TERRAIN_FACTORS], range[SYL_TERRAIN_FACTORS], falloff[SYL_TERRAIN_FACTORS];
    uint8_t set[SYL_TERRAIN_FACTORS];
    int line, col; /* where `species` was written */
} SylEcoSpecies;

typedef enum { SYL_ECO_MEAN, SYL_ECO_PRODUCT, SYL_ECO_MINIMUM } SylEcoCombine;
typedef enum { SYL_ECO_GIS, SYL_ECO_ZAMUDA } SylEcoMeasures; /* `measures` */
typedef enum { SYL_ECO_STRESS, SYL_ECO_PER_FACTOR } SylEcoMortality; /* `mortality stress|zamuda` */

/* Why plants died (SylEcoYear.deaths): their age, domination, and then (mortality stress) the
 * site's stress, or (mortality zamuda, Zamuda 2006's generators of death) each factor that
 * does not suit them; the water, sun and wind causes are the measures' (wetness or humidity,
 * insolation or sunniness, wind or windiness). */
#define SYL_ECO_DEATH_LIST(X) X(AGE, "age") X(DOMINANCE, "dominance") X(STRESS, "stress") X(ALTITUDE, "altitude") \
    X(SLOPE, "slope") X(ASPECT, "aspect") X(HUMIDITY, "humidity") X(SUNNINESS, "sunniness") X(WINDINESS, "windiness")
#define SYL_ECO_DEATH_ENUM(id, name) SYL_ECO_DEATH_##id,
typedef enum { SYL_ECO_DEATH_LIST(SYL_ECO_DEATH_ENUM) SYL_ECO_DEATH_CAUSES } SylEcoDeath;
#undef SYL_ECO_DEATH_ENUM
const char *syl_ecosystem_death_name(SylEcoDeath cause); /* "age", "dominance", ... */
/* The cause of death a factor's suitability stands for (-1: none, the flow). */
int syl_ecosystem_death_of(SylTerrainFactor f);

/* An ecosystem block read from its directives. */
typedef struct SylEcoModel {
    char terrain[1024];           /* the DEM's path, relative to the program's file */
    double cell, height_lo, height_hi, latitude;
    int latitude_set;
    int years;
    int snapshots[SYL_ECO_MAX_SNAPSHOTS], nsnapshots;
    uint64_t seed;
    SylEcoCombine combine;
    SylEcoSpecies species[SYL_ECO_MAX_SPECIES];
    int nspecies;
    SylEcoMeasures measures;   /* which terrain measures the species' curves read */
    SylEcoMortality mortality;
    double wind_from;          /* degrees: where the wind blows from (default 270) */
    int wind_set;
} SylEcoModel;

/* Read (and check) an ecosystem block: returns the number of errors, each a record with
 * file, line and column (the source line and a caret) to p's sink, else to sink (NULL:
 * nowhere; {syl_diagnostic_print, stderr} prints them as `sylva` does). syl_ecosystem_validate
 * is the same check for syl_compile's hook (`sylva check`). */
int syl_ecosystem_read(const SylProgram *p, SylEcoModel *m, const SylSink *sink);
int syl_ecosystem_validate(const SylProgram *p, const SylSink *sink);
/* Read an ecosystem block's DEM as the run will (not its factors), for `sylva check`: 0, or 1
 * when it lies outside the folders the model may read or is malformed (reported to p's sink,
 * else sink); one that cannot be read is a warning (it may yet be made). */
int syl_ecosystem_check_terrain(const SylProgram *p, const SylSink *sink);

/* How tiles talk: a tile posts plants to another tile (its border plants, for the other's
 * halo, or the seedlings that sprouted there, germinated by the sender) and, after a
 * barrier, takes what was posted to it. An MPI transport implements the same three calls; syl_ecosystem_run uses an in-process one
 * when SylEcoOptions.exchange is NULL. Between two barriers, post may be called from several
 * threads, each for its own `from` tile; the posted plants stay valid until the barrier after
 * the receiver's take (a transport may keep the pointer instead of copying). */
enum { SYL_ECO_HALO = 0, SYL_ECO_SEEDS = 1, SYL_ECO_MOVE = 2 /* a tile's plants to its new owner */ };
typedef struct SylEcoExchange {
    void (*post)(void *ctx, int channel, int from, int to, const SylEcoPlant *p, size_t n);
    void (*barrier)(void *ctx);
    /* what `from` posted to `to` on the channel since the barrier before last */
    const SylEcoPlant *(*take)(void *ctx, int channel, int to, int from, size_t *n);
    /* The rest is for a transport over processes (each NULL in one process). owns: whether
     * this process runs the tile. sum: adds v over the processes, in place. gather: every
     * process's plants into *all (malloc'ed) on the one that writes, *all = NULL elsewhere.
     * rebalance: at the end of `year`, given every tile's plants, whether tiles change owner
     * (posts on SYL_ECO_MOVE then go to the new owner, who owns them after the barrier). */
    int (*owns)(void *ctx, int tile);
    void (*sum)(void *ctx, int64_t *v, size_t n);
    int (*gather)(void *ctx, const SylEcoPlant *p, size_t n, SylEcoPlant **all, size_t *nall);
    int (*rebalance)(void *ctx, int year, const int64_t *plants_per_tile, int ntiles);
    void *ctx;
} SylEcoExchange;

typedef struct SylEcoYear {
    int year;
    uint32_t count[SYL_ECO_MAX_SPECIES];  /* living plants at the end of the year */
    double cover[SYL_ECO_MAX_SPECIES];    /* their crowns' area (π r²) over the terrain's area */
    double mean_height[SYL_ECO_MAX_SPECIES];
    uint32_t deaths[SYL_ECO_MAX_SPECIES][SYL_ECO_DEATH_CAUSES]; /* plants that died in the year, by cause */
} SylEcoYear;

typedef struct SylEcoOptions {
    int years;             /* 0: the block's */
    const int *snapshots;  /* NULL: the block's */
    int nsnapshots;
    int tiles_x, tiles_z;  /* 0: 1 × 1 */
    int threads;           /* <= 0: all cores; the output never depends on it */
    int use_seed;
    uint64_t seed;
    const SylEcoExchange *exchange; /* NULL: in-process */
    uint64_t max_plants;   /* SYL_ELIMIT when more live at once (0: no limit) */
    SylBudget *budget;     /* the plants' buffers are counted against it (NULL: none); beyond
                              it the run stops with SYL_ELIMIT, naming the year */
    /* called after every year, and with the year's plants (sorted by id) at each snapshot */
    void (*on_year)(void *user, const SylEcoYear *y);
    int (*on_snapshot)(void *user, int year, const SylEcoPlant *plants, size_t n); /* non-0 stops */
    void (*progress)(void *user, double fraction);
    void *user;
    FILE *diag;
    const SylSink *sink;   /* or as records to this sink instead (sylva.h); NULL: diag */
    /* a resumed run (sylva ecosystem --resume): start after start_year with these plants,
     * sorted by id (the state at that year's end) */
    int start_year;
    const SylEcoPlant *start;
    size_t nstart;
    /* every `every` years, on_checkpoint gets the year's plants (sorted by id): a saved state */
    int every;
    int (*on_checkpoint)(void *user, int year, const SylEcoPlant *plants, size_t n); /* non-0 stops */
} SylEcoOptions;

typedef struct SylEcoStats {
    uint64_t plant_years;  /* plants alive at the start of a year, summed over the years */
    size_t peak_plants;
    size_t bytes_per_plant; /* memory the simulation holds per plant beyond the terrain */
    double seconds, cpu_seconds;
} SylEcoStats;

/* Read the block, its terrain (computing its factors), and run it. *terrain_out (when not
 * NULL) receives the terrain, to be freed with syl_terrain_free. SYL_OK, SYL_EMODEL (a bad
 * block or DEM), SYL_EUSAGE, SYL_EIO, SYL_ELIMIT, or what on_snapshot returned. */
int syl_ecosystem_run(const SylProgram *p, const SylEcoOptions *o, SylEcoModel *model_out,
                      SylTerrain **terrain_out, SylEcoStats *stats);
/* Only the reading: the block into *m and its terrain, factors computed, into *terrain
 * (free with syl_terrain_free). */
int syl_ecosystem_load(const SylProgram *p, const SylEcoOptions *o, SylEcoModel *m, SylTerrain **terrain);
/* The same on a model and terrain already read (the terrain's factors computed). */
int syl_ecosystem_simulate(const SylEcoModel *m, const SylTerrain *t, const SylEcoOptions *o,
                           SylEcoStats *stats);
/* A saved state (docs/distributed.md, "Checkpoints"): the plants at the end of `year`, the
 * years' counts so far (years[0 .. year)), and the hash of what they came from. */
typedef struct SylEcoCheckpoint {
    uint64_t model_hash; /* syl_ecosystem_hash of the model, terrain and seed */
    int year;
    SylEcoYear *years;   /* year entries */
    SylEcoPlant *plants; /* sorted by id */
    size_t nplants;
} SylEcoCheckpoint;
/* What a run depends on besides its options: the block's values, the terrain, the seed. */
uint64_t syl_ecosystem_hash(const SylEcoModel *m, const SylTerrain *t, uint64_t seed);
/* Write c to path atomically (util/outfile.h): SYL_OK or SYL_EIO (reported to sink). */
int syl_ecosystem_checkpoint_write(const char *path, const SylEcoCheckpoint *c, const SylSink *sink);
/* Read a checkpoint from bytes / a file: SYL_OK, or SYL_EMODEL for a corrupt, truncated or
 * foreign one (SYL_EIO: unreadable), reported to sink as "sylva: error: checkpoint 'NAME': ..." */
int syl_ecosystem_checkpoint_parse(const void *buf, size_t len, const char *name, SylEcoCheckpoint *c, const SylSink *sink);
int syl_ecosystem_checkpoint_read(const char *path, SylEcoCheckpoint *c, const SylSink *sink);
/* Whether c's plants are a state the simulation of m on t could have made (the checksum
 * only says the file is whole): each of a species of m, standing on a cell of t with data,
 * its cell that one, no taller than its species' height_max, no older than its max_age or
 * the checkpoint's year. SYL_OK, or SYL_EMODEL reported with the first plant that is not. */
int syl_ecosystem_checkpoint_check(const SylEcoCheckpoint *c, const SylEcoModel *m, const SylTerrain *t, const char *name,
                                   const SylSink *sink);
void syl_ecosystem_checkpoint_free(SylEcoCheckpoint *c);

/* plants-YEAR.csv (src/eco/table.c), a snapshot's plants one row each under the header
 * syl_ecosystem_table_header: x, z and height with the decimals that read back the same
 * float. parse/read: strict, the first bad row reported as FILE:LINE:COL with a caret on
 * diag; SYL_OK (*plants malloc'ed, in the table's order: by increasing id), SYL_EMODEL (a
 * bad table), SYL_EIO (unreadable), SYL_ELIMIT. */
extern const char syl_ecosystem_table_header[];
void syl_ecosystem_table_write_row(FILE *f, const SylEcoModel *m, const SylTerrain *t, const SylEcoPlant *p);
/* A text field of a CSV file as RFC 4180 writes it: quoted when it holds a comma, a quote or a
 * line end (a species' name in the plant table and species.csv). */
void syl_ecosystem_write_csv_text(FILE *f, const char *s);
int syl_ecosystem_table_parse(const char *text, size_t len, const char *name, const SylEcoModel *m,
                              const SylTerrain *t, SylEcoPlant **plants, size_t *nplants, const SylSink *sink);
int syl_ecosystem_table_read(const char *path, const SylEcoModel *m, const SylTerrain *t, SylEcoPlant **plants,
                             size_t *nplants, const SylSink *sink);

/* Ranks of an MPI job (src/eco/mpi.c; built with MPI=1). start: NULL when the build has no
 * MPI or the program was not launched by mpirun (one process); else MPI is initialised, and
 * an MPI error, a rank that stops answering (SYLVA_RANK_TIMEOUT) or running out of memory
 * ends the job with exit code SYL_EIO and a message to diag (NULL: none). exchange: the transport over tiles_x × tiles_z tiles,
 * spread over the ranks, re-balanced every `rebalance` years (0: never). */
typedef struct SylEcoMpi SylEcoMpi;
SylEcoMpi *syl_ecosystem_mpi_start(int *argc, char ***argv, const SylSink *sink);
int syl_ecosystem_mpi_rank(const SylEcoMpi *mpi);
int syl_ecosystem_mpi_size(const SylEcoMpi *mpi);
const SylEcoExchange *syl_ecosystem_mpi_exchange(SylEcoMpi *mpi, int ntiles, int rebalance);
/* Traffic so far, this rank: plants and bytes sent, halo plants received, plants received
 * with a tile that re-balancing gave it, barriers. */
void syl_ecosystem_mpi_traffic(const SylEcoMpi *mpi, uint64_t *plants_sent, uint64_t *bytes_sent,
                         uint64_t *halo_received, uint64_t *plants_moved, uint64_t *barriers);
void syl_ecosystem_mpi_end(SylEcoMpi *mpi); /* MPI_Finalize */

/* Pictures of a run (src/eco/pictures.c), in one palette of species' colours. map: a
 * snapshot seen from above, north up, its plants as discs of their crowns (the dominated
 * ones darker, the tallest on top) over the terrain's hillshade (syl_terrain_draw_hillshade, of the
 * same size), the species' names in a legend: `sylva ecosystem`'s map-YEAR.png. SYL_OK or
 * SYL_ELIMIT. chart: an SVG of each species' cover (crown area / terrain area) over the years
 * given (species.svg), into *svg (malloc'ed, NUL-ended, *len bytes). SYL_OK or SYL_ELIMIT. */
int syl_ecosystem_draw_map(const SylEcoModel *m, const SylTerrain *t, const SylEcoPlant *plants, size_t n,
                           const SylMapOptions *o, SylPicture *out);
typedef struct SylChartOptions {
    double width, height; /* pixels (0: 640 x 360) */
} SylChartOptions;
int syl_ecosystem_draw_chart(const SylEcoModel *m, const SylEcoYear *years, int nyears, const SylChartOptions *o,
                             char **svg, size_t *len);

/* A species' vigour at (x, z): its suitabilities combined as the block says. */
double syl_ecosystem_vigour(const SylEcoModel *m, int species, const SylTerrain *t, double x, double z);

#ifdef __cplusplus
}
#endif
#endif
