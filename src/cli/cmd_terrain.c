/* sylva terrain: read a DEM, compute its factors (docs/terrain.md), print their ranges or
 * write them as maps. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "cli/cli.h"
#include "sylva/texture.h"
#include "sylva/terrain.h"

const CliCommand cli_terrain_command = {
    .name = "terrain",
    .what = "a DEM's factors: altitude, slope, aspect, flow, wetness, sun, wind",
    .run = cmd_terrain,
    .usage = "sylva terrain DEM.{png,asc,obj,dmr} [--maps DIR] [options]",
    .about = "Read a digital elevation model — a greyscale PNG (8 or 16 bits), an ESRI ASCII grid or an\n"
             "OBJ terrain mesh — and compute its factors as GIS does (docs/terrain.md): altitude,\n"
             "slope and aspect (Horn), D8 flow accumulation after priority-flood filling, the\n"
             "topographic wetness index, a year's insolation with the terrain's shadows, and\n"
             "Winstral's wind shelter Sx; or with --measures zamuda (or both) Zamuda's (2006) runoff\n"
             "humidity, sunniness and lee-angle windiness as his thesis computes them. Prints each\n"
             "factor's range, or with --maps writes them.\n",
    .options = (const CliUse[]){
        {.option = CLI_OPT_MAPS},
        {.option = CLI_OPT_CELL},
        {.option = CLI_OPT_HEIGHTS},
        {.option = CLI_OPT_LATITUDE},
        {.option = CLI_OPT_SUN_DAYS},
        {.option = CLI_OPT_SUN_MINUTES},
        {.option = CLI_OPT_WIND_FROM},
        {.option = CLI_OPT_WIND_DISTANCE},
        {.option = CLI_OPT_MEASURES},
        {.option = CLI_OPT_THREADS, .help = "threads (default: all cores); the maps never depend on N"},
        {.option = CLI_OPT_MAX_MEMORY, .help = "stop with exit code 3 beyond SIZE of memory for the grids,\n"
                                               "e.g. 2G (default: half the least of the machine's memory,\n"
                                               "RLIMIT_AS, RLIMIT_DATA and the cgroup's limit, at most 16G)"},
        {.option = CLI_OPT_STATS, .help = "print the grid's size and each factor's time to stderr"},
        {0},
    },
    .width = 24,
    .epilogue = "\nExit codes: 0 ok, 1 the DEM is malformed, 2 bad command line, 3 limit hit, 4 I/O error.\n",
    .args_error = "expects one DEM file",
};

static void summary(const SylTerrain *t) {
    printf("cells: %d x %d of %g\n", t->nx, t->nz, t->cell);
    printf("%-10s %12s %12s %12s\n", "factor", "min", "mean", "max");
    size_t n = (size_t)t->nx * (size_t)t->nz;
    for (int f = 0; f < SYL_TERRAIN_FACTORS; f++) {
        const float *g = t->factor[f];
        if (!g) continue; /* not among the measures asked for */
        double lo = INFINITY, hi = -INFINITY, sum = 0;
        size_t m = 0;
        for (size_t c = 0; c < n; c++) {
            if (!t->valid[c]) continue;
            if (g[c] < lo) lo = g[c];
            if (g[c] > hi) hi = g[c];
            sum += g[c];
            m++;
        }
        printf("%-10s %12.6g %12.6g %12.6g\n", syl_terrain_factor_name((SylTerrainFactor)f), lo,
               m ? sum / (double)m : 0, hi);
    }
}

static int make_dir(const char *dir) {
    if (mkdir(dir, 0777) && errno != EEXIST) {
        fprintf(stderr, "sylva: error: cannot make the directory '%s': %s\n", dir, strerror(errno));
        return SYL_EIO;
    }
    return SYL_OK;
}

static int write_maps(const SylTerrain *t, const char *dir) {
    static const char *const ext[] = {"png", "asc"};
    for (int f = 0; f < SYL_TERRAIN_FACTORS; f++)
        for (int e = 0; e < 2 && t->factor[f]; e++) {
            size_t len = strlen(dir) + 32;
            char *path = malloc(len);
            if (!path) {
                fprintf(stderr, "sylva: error: out of memory\n");
                return SYL_ELIMIT;
            }
            snprintf(path, len, "%s/%s.%s", dir, syl_terrain_factor_name((SylTerrainFactor)f), ext[e]);
            int st = syl_terrain_write_map(t, (SylTerrainFactor)f, path, &cli_sink);
            if (!st) printf("%s\n", path);
            free(path);
            if (st) return st;
        }
    return SYL_OK;
}

/* DIR/NAME-colour.png, every factor computed in colour (syl_terrain_draw_colour_map) */
static int colour_maps(const SylTerrain *t, const char *dir) {
    int st = SYL_OK;
    for (int f = 0; f < SYL_TERRAIN_FACTORS && !st; f++) {
        if (!t->factor[f]) continue; /* not among the measures asked for */
        size_t len = strlen(dir) + 48;
        char *path = malloc(len);
        SylPicture pic = {0};
        if (path) snprintf(path, len, "%s/%s-colour.png", dir, syl_terrain_factor_name((SylTerrainFactor)f));
        st = path ? syl_terrain_draw_colour_map(t, (SylTerrainFactor)f, NULL, &pic) : SYL_ELIMIT;
        if (!st) st = syl_png_write(path, pic.rgb, pic.width, pic.height, &cli_sink);
        if (!st) printf("%s\n", path);
        syl_picture_free(&pic);
        free(path);
    }
    return st;
}

int cmd_terrain(int argc, char **argv) {
    SylDeriveOptions d = {0};
    CliArgs a = {.d = &d, .latitude = 46, .sun_days = 12, .sun_minutes = 60, .wind_from = 270, .wind_distance = 300};
    int done = cli_parse(&cli_terrain_command, argc, argv, &a);
    if (done != CLI_RUN) return done;
    double t0 = cli_now();
    SylBudget *budget = syl_budget_new(d.max_memory);
    if (!budget) {
        fprintf(stderr, "sylva: error: out of memory\n");
        return SYL_ELIMIT;
    }
    SylTerrainOptions o = {
        .cell = a.cell, .height_lo = a.heights_set ? a.heights[0] : 0, .height_hi = a.heights_set ? a.heights[1] : 1,
        .latitude = a.latitude, .sun_days = a.sun_days, .sun_minutes = a.sun_minutes, .sun_set = 1,
        .wind_from = a.wind_from, .wind_distance = a.wind_distance, .wind_set = 1, .measures = a.measures,
        .threads = d.threads, .budget = budget, .diag = stderr,
    };
    SylTerrain *t = NULL;
    int st = syl_terrain_read(a.files[0], &o, &t);
    double read_s = cli_now() - t0;
    size_t plen = strlen(a.files[0]);
    if (!st && !a.heights_set && plen > 4 && !strcasecmp(a.files[0] + plen - 4, ".png"))
        fprintf(stderr, "%s: warning: no --heights: black is 0 m and white 1 m; give the heights of black and "
                        "white, e.g. --heights 0,400\n", a.files[0]);
    /* Once the DEM is read (a bad one makes no directory), before the work of the factors. */
    if (!st && a.maps) st = make_dir(a.maps);
    if (!st) st = syl_terrain_compute(t, &o);
    double t1 = cli_now();
    if (!st) {
        if (a.maps) st = write_maps(t, a.maps);
        if (a.maps && !st) st = colour_maps(t, a.maps);
        else summary(t);
    }
    if (!st && a.stats) {
        fprintf(stderr, "cells: %d x %d\ncell size: %g\nread time: %.6f s\n", t->nx, t->nz, t->cell, read_s);
        double sum = 0, cpu = 0;
        for (int f = SYL_TERRAIN_SLOPE; f < SYL_TERRAIN_FACTORS; f++) {
            if (f == SYL_TERRAIN_ASPECT || !t->factor[f]) continue; /* computed with the slope; not asked for */
            fprintf(stderr, "%s time: %.6f s (cpu %.6f s)\n",
                    f == SYL_TERRAIN_SLOPE ? "slope and aspect" : syl_terrain_factor_name((SylTerrainFactor)f),
                    t->seconds[f], t->cpu_seconds[f]);
            sum += t->seconds[f], cpu += t->cpu_seconds[f];
        }
        fprintf(stderr, "insolation rays: %llu of %llu (cell, sun) pairs facing the sun\n",
                (unsigned long long)t->rays, (unsigned long long)t->sun_pairs);
        fprintf(stderr, "factors time: %.6f s (cpu %.6f s)\nwrite time: %.6f s\npeak memory: %.1f MB\n", sum, cpu,
                cli_now() - t1, cli_peak_mb());
    }
    syl_terrain_free(t);
    syl_budget_free(budget);
    return st;
}
