/* sylva compare: metrics of several models side by side (docs/compare.md). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "sylva/metrics.h"
#include "util/json.h"

static void print_metrics(FILE *out) {
    for (int i = 0; i < syl_metrics_count; i++) {
        const SylMetricInfo *mi = &syl_metrics_info[i];
        char name[64];
        snprintf(name, sizeof name, "%s%s%s%s", mi->label, mi->per_order ? " i:i+1" : "", *mi->unit ? ", " : "",
                 mi->unit);
        fprintf(out, "  %-28s %s\n", name, mi->description);
    }
    fputs("\nExit codes: 0 ok, 1 a model is wrong, 2 bad command line, 3 limit hit, 4 I/O error.\n", out);
}

const CliCommand cli_compare_command = {
    .name = "compare",
    .what = "print a table of metrics of several models; --image draws them side by side",
    .run = cmd_compare,
    .usage = "sylva compare FILE[:Model]... [--csv | --json] [--seeds N] [--image OUT.png] [options]",
    .about = "Grow every model and print a table of metrics computed from its skeleton, one column per\n"
             "model and one row per metric (docs/compare.md defines them). The output is the same on\n"
             "every run and with any number of threads.\n",
    .options = (const CliUse[]){
        {.option = CLI_OPT_CSV},
        {.option = CLI_OPT_JSON},
        {.option = CLI_OPT_OUTPUT, .help = "write the table to FILE (default: standard output)"},
        {.option = CLI_OPT_SEEDS},
        {.option = CLI_OPT_IMAGE},
        {.option = CLI_OPT_SIZE, .help = "size of the picture (default 1600x900)"},
        {.option = CLI_OPT_VIEW, .help = "iso, front, side or top (default front)"},
        {.group = cli_derive_uses},
        {0},
    },
    .epilogue = "\n--set applies to every model. Metrics:\n",
    .more = print_metrics,
    .several = true,
    .args_error = "expects one or more model files",
};

/* One model: its runs' metrics. */
typedef struct Column {
    ModelArgs args;
    char name[64];      /* the model's */
    const char *label;  /* the column's: the model's name, or as typed when two share it */
    uint64_t seed0;
    SylMetrics *runs;
    SylMesh *mesh; /* of the first run, for --image */
    double ground;
} Column;

/* One line of the table: a metric, and the order of a per-order one. */
typedef struct Row {
    int metric, order;
    char key[64], label[64];
} Row;

/* Mean and sample standard deviation of the runs where the value exists. */
typedef struct Stat {
    double mean, sd;
    int n;
} Stat;

static Stat stat(const Column *c, int nruns, const Row *r) {
    Stat s = {NAN, NAN, 0};
    double sum = 0;
    for (int i = 0; i < nruns; i++) {
        double v = syl_metrics_value(&c->runs[i], r->metric, r->order);
        if (!isnan(v)) sum += v, s.n++;
    }
    if (!s.n) return s;
    s.mean = sum / s.n;
    bool same = true; /* then exactly that value, and 0 */
    double first = NAN;
    for (int i = 0; i < nruns; i++) {
        double v = syl_metrics_value(&c->runs[i], r->metric, r->order);
        if (isnan(v)) continue;
        if (isnan(first)) first = v;
        else if (v != first) same = false;
    }
    if (same) {
        s.mean = first;
        s.sd = 0;
        return s;
    }
    double ss = 0;
    for (int i = 0; i < nruns; i++) {
        double v = syl_metrics_value(&c->runs[i], r->metric, r->order);
        if (!isnan(v)) ss += (v - s.mean) * (v - s.mean);
    }
    s.sd = s.n > 1 ? sqrt(ss / (s.n - 1)) : 0;
    return s;
}

/* ---- formatting ---- */

static void fmt_text(char *buf, size_t n, double v, bool integer, int digits) {
    if (isnan(v)) snprintf(buf, n, "-");
    else if (v == 0) snprintf(buf, n, "0");
    else if ((integer && v == floor(v)) || (fabs(v) >= 1e4 && fabs(v) < 1e15)) snprintf(buf, n, "%.0f", v);
    else snprintf(buf, n, "%.*g", digits, v);
}

/* "mean ± sd": the mean to 4 significant digits, the deviation to the same decimals. */
static void fmt_mean_sd(char *buf, size_t n, double mean, double sd) {
    char m[32], d[32];
    if (sd == 0 && mean == floor(mean) && fabs(mean) < 1e15) {
        snprintf(m, sizeof m, "%.0f", mean);
        snprintf(d, sizeof d, "0");
    } else if (fabs(mean) >= 1e-3 && fabs(mean) < 1e4) {
        int decimals = 3 - (int)floor(log10(fabs(mean)));
        if (decimals < 0) decimals = 0;
        snprintf(m, sizeof m, "%.*f", decimals, mean);
        snprintf(d, sizeof d, "%.*f", decimals, sd);
    } else if (fabs(mean) >= 1e4 && fabs(mean) < 1e15) { /* whole numbers, the deviation too */
        snprintf(m, sizeof m, "%.0f", mean);
        snprintf(d, sizeof d, "%.0f", sd);
    } else {
        fmt_text(m, sizeof m, mean, false, 4);
        fmt_text(d, sizeof d, sd, false, 2);
    }
    snprintf(buf, n, "%s ± %s", m, d);
}

static void fmt_number(char *buf, size_t n, double v, bool integer) {
    if (isnan(v)) buf[0] = 0;
    else if (v == 0) snprintf(buf, n, "0");
    else if (integer && v == floor(v) && fabs(v) < 1e15) snprintf(buf, n, "%.0f", v);
    else snprintf(buf, n, "%.6g", v);
}

static size_t width(const char *s) { /* characters of UTF-8 text */
    size_t w = 0;
    for (; *s; s++) w += ((unsigned char)*s & 0xC0) != 0x80;
    return w;
}

static void pad(FILE *out, size_t n) {
    while (n--) fputc(' ', out);
}

static void csv_field(FILE *out, const char *s) {
    if (!strpbrk(s, ",\"\n\r")) {
        fputs(s, out);
        return;
    }
    fputc('"', out);
    for (; *s; s++) {
        if (*s == '"') fputc('"', out);
        fputc(*s, out);
    }
    fputc('"', out);
}

static void json_number(FILE *out, double v, bool integer) {
    char buf[64];
    fmt_number(buf, sizeof buf, v, integer);
    fputs(*buf ? buf : "null", out);
}

/* Mean and sample standard deviation of v[0..n) (n >= 1). */
static Stat stat_of(const double *v, int n) {
    Stat s = {0, 0, n};
    for (int i = 0; i < n; i++) s.mean += v[i];
    s.mean /= n;
    for (int i = 0; i < n; i++) s.sd += (v[i] - s.mean) * (v[i] - s.mean);
    s.sd = n > 1 ? sqrt(s.sd / (n - 1)) : 0;
    return s;
}

/* A count over the runs: the number itself for one run, else {"mean": …, "sd": …}. */
static void json_count(FILE *out, const double *v, int n) {
    Stat s = stat_of(v, n);
    if (n == 1) {
        json_number(out, v[0], true);
        return;
    }
    fputs("{\"mean\": ", out);
    json_number(out, s.mean, false);
    fputs(", \"sd\": ", out);
    json_number(out, s.sd, false);
    fputc('}', out);
}

/* The counts a user can check on the plant: stems of each branch order, and leaves. */
static void json_counts(FILE *out, const Column *c, int nruns) {
    double v[nruns > 0 ? nruns : 1];
    int orders = 0;
    for (int i = 0; i < nruns; i++)
        if (c->runs[i].stem_orders > orders) orders = c->runs[i].stem_orders;
    fputs(",\n      \"stems_by_order\": [", out);
    for (int k = 0; k < orders; k++) {
        for (int i = 0; i < nruns; i++) v[i] = c->runs[i].stems_by_order[k];
        if (k) fputs(", ", out);
        json_count(out, v, nruns);
    }
    fputs("], \"leaves\": ", out);
    for (int i = 0; i < nruns; i++) v[i] = c->runs[i].leaves;
    json_count(out, v, nruns);
}

/* ---- the three formats ---- */

static bool write_text(FILE *out, const Column *cols, int ncols, int nruns, const Row *rows, int nrows) {
    enum { CELL = 96 };
    char *cells = calloc((size_t)(nrows + 1) * (size_t)(ncols + 1), CELL);
    size_t *w = calloc((size_t)ncols + 1, sizeof *w);
    if (!cells || !w) {
        free(cells);
        free(w);
        return false;
    }
#define CELLP(r, c) (cells + ((size_t)(r) * (size_t)(ncols + 1) + (size_t)(c)) * CELL)
    for (int r = 0; r < nrows; r++) {
        const SylMetricInfo *mi = &syl_metrics_info[rows[r].metric];
        if (*mi->unit) snprintf(CELLP(r + 1, 0), CELL, "%s (%s)", rows[r].label, mi->unit);
        else snprintf(CELLP(r + 1, 0), CELL, "%s", rows[r].label);
        for (int c = 0; c < ncols; c++) {
            Stat s = stat(&cols[c], nruns, &rows[r]);
            if (nruns > 1 && s.n) fmt_mean_sd(CELLP(r + 1, c + 1), CELL, s.mean, s.sd);
            else fmt_text(CELLP(r + 1, c + 1), CELL, s.mean, mi->integer, 4);
        }
    }
    /* The first row names the columns: metric, then each model as it was typed. */
    const char *head = "metric";
    w[0] = width(head);
    for (int c = 0; c < ncols; c++) w[c + 1] = width(cols[c].label);
    for (int r = 1; r <= nrows; r++)
        for (int c = 0; c <= ncols; c++)
            if (width(CELLP(r, c)) > w[c]) w[c] = width(CELLP(r, c));
    for (int r = 0; r <= nrows; r++) {
        const char *first = r ? CELLP(r, 0) : head;
        fputs(first, out);
        pad(out, w[0] - width(first));
        for (int c = 1; c <= ncols; c++) {
            const char *cell = r ? CELLP(r, c) : cols[c - 1].label;
            pad(out, 2 + w[c] - width(cell));
            fputs(cell, out);
        }
        fputc('\n', out);
    }
#undef CELLP
    free(cells);
    free(w);
    return true;
}

static void write_csv(FILE *out, const Column *cols, int ncols, int nruns, const Row *rows, int nrows) {
    fputs("metric,unit", out);
    for (int c = 0; c < ncols; c++) {
        char h[4200];
        fputc(',', out);
        snprintf(h, sizeof h, nruns > 1 ? "%s mean" : "%s", cols[c].label);
        csv_field(out, h);
        if (nruns > 1) {
            fputc(',', out);
            snprintf(h, sizeof h, "%s sd", cols[c].label);
            csv_field(out, h);
        }
    }
    fputc('\n', out);
    for (int r = 0; r < nrows; r++) {
        const SylMetricInfo *mi = &syl_metrics_info[rows[r].metric];
        fprintf(out, "%s,%s", rows[r].key, mi->unit);
        for (int c = 0; c < ncols; c++) {
            Stat s = stat(&cols[c], nruns, &rows[r]);
            char buf[64];
            fmt_number(buf, sizeof buf, s.mean, mi->integer);
            fprintf(out, ",%s", buf);
            if (nruns > 1) {
                fmt_number(buf, sizeof buf, s.sd, false);
                fprintf(out, ",%s", buf);
            }
        }
        fputc('\n', out);
    }
}

static void write_json(FILE *out, const Column *cols, int ncols, int nruns, const Row *rows, int nrows) {
    fprintf(out, "{\n  \"seeds\": %d,\n  \"metrics\": [\n", nruns);
    for (int r = 0; r < nrows; r++) {
        const SylMetricInfo *mi = &syl_metrics_info[rows[r].metric];
        fputs("    {\"key\": ", out);
        json_string_file(out, rows[r].key);
        fputs(", \"label\": ", out);
        json_string_file(out, rows[r].label);
        fputs(", \"unit\": ", out);
        json_string_file(out, mi->unit);
        fputs(", \"description\": ", out);
        json_string_file(out, mi->description);
        fprintf(out, "}%s\n", r + 1 < nrows ? "," : "");
    }
    fputs("  ],\n  \"models\": [\n", out);
    for (int c = 0; c < ncols; c++) {
        fputs("    {\"model\": ", out);
        json_string_file(out, cols[c].args.spec);
        fputs(", \"name\": ", out);
        json_string_file(out, cols[c].name);
        fputs(", \"seeds\": [", out);
        for (int i = 0; i < nruns; i++)
            fprintf(out, "%s%llu", i ? ", " : "", (unsigned long long)(cols[c].seed0 + (uint64_t)i));
        fputs("],\n      \"values\": {", out);
        for (int r = 0; r < nrows; r++) {
            const SylMetricInfo *mi = &syl_metrics_info[rows[r].metric];
            Stat s = stat(&cols[c], nruns, &rows[r]);
            fputs(r ? ",\n        " : "\n        ", out);
            json_string_file(out, rows[r].key);
            fputs(": ", out);
            if (nruns > 1 && s.n) {
                fputs("{\"mean\": ", out);
                json_number(out, s.mean, false);
                fputs(", \"sd\": ", out);
                json_number(out, s.sd, false);
                fputc('}', out);
            } else json_number(out, s.mean, mi->integer);
        }
        fputs("\n      }", out);
        json_counts(out, &cols[c], nruns);
        fprintf(out, "}%s\n", c + 1 < ncols ? "," : "");
    }
    fputs("  ]\n}\n", out);
}

/* ---- running ---- */

/* Rows: every metric, the per-order ones from order 1 to the highest Strahler order - 1. */
static Row *make_rows(const Column *cols, int ncols, int nruns, int *nrows) {
    int top = 0;
    for (int c = 0; c < ncols; c++)
        for (int i = 0; i < nruns; i++)
            if (cols[c].runs[i].strahler > top) top = (int)cols[c].runs[i].strahler;
    Row *rows = calloc((size_t)syl_metrics_count + (size_t)top + 1, sizeof *rows);
    int n = 0;
    if (!rows) return NULL;
    for (int m = 0; m < syl_metrics_count; m++) {
        const SylMetricInfo *mi = &syl_metrics_info[m];
        if (!mi->per_order) {
            rows[n] = (Row){.metric = m};
            snprintf(rows[n].key, sizeof rows[n].key, "%s", mi->key);
            snprintf(rows[n++].label, sizeof rows[0].label, "%s", mi->label);
            continue;
        }
        for (int o = 1; o < top; o++) {
            rows[n] = (Row){.metric = m, .order = o};
            snprintf(rows[n].key, sizeof rows[n].key, "%s_%d", mi->key, o);
            snprintf(rows[n++].label, sizeof rows[0].label, "%s %d:%d", mi->label, o, o + 1);
        }
    }
    *nrows = n;
    return rows;
}

/* Grow a column's model nruns times and measure each plant. */
static int run_column(Column *col, const SylDeriveOptions *base, bool seeded, int nruns, bool keep_mesh) {
    int status;
    SylProgram *p = cli_compile(&col->args, SYL_WARN_MISTAKES | SYL_WARN_DRAWS, &status);
    if (!p) return status;
    snprintf(col->name, sizeof col->name, "%s", syl_program_name(p));
    col->seed0 = seeded ? base->seed : syl_program_seed(p);
    syl_program_free(p);
    for (int i = 0; i < nruns; i++) {
        SylDeriveOptions d = *base;
        d.use_seed = 1;
        d.seed = col->seed0 + (uint64_t)i;
        SylMeshOptions mo = {.threads = d.threads, .diag = stderr};
        Plant pl;
        status = cli_plant(&col->args, &d, &mo, &pl);
        if (status) return status;
        SylMetricsOptions o = {.mesh = pl.mesh, .threads = d.threads, .diag = stderr};
        status = syl_metrics_compute(pl.sk, &o, &col->runs[i]);
        if (!status && i == 0 && keep_mesh) {
            col->mesh = pl.mesh;
            col->ground = col->runs[0].ground;
            pl.mesh = NULL;
        }
        cli_plant_free(&pl);
        if (status) return status;
    }
    return SYL_OK;
}

static int write_image(const Column *cols, int ncols, const char *path, SylRenderOptions *ro) {
    const SylMesh **meshes = calloc((size_t)ncols, sizeof *meshes);
    double *ground = calloc((size_t)ncols, sizeof *ground);
    SylMesh *all = NULL;
    int status = SYL_ELIMIT;
    const char **names = calloc((size_t)ncols, sizeof *names);
    if (meshes && ground && names) {
        for (int c = 0; c < ncols; c++) meshes[c] = cols[c].mesh, ground[c] = cols[c].ground, names[c] = cols[c].name;
        all = syl_metrics_build_lineup(meshes, ground, names, ncols);
    }
    if (!all) fprintf(stderr, "sylva: error: out of memory\n");
    else {
        Progress prog;
        cli_progress_start(&prog, "rendering");
        ro->progress = cli_progress;
        ro->user = &prog;
        status = syl_render_write_png(all, ro, path);
    }
    syl_mesh_free(all);
    free(meshes);
    free(ground);
    free(names);
    return status;
}

int cmd_compare(int argc, char **argv) {
    ModelArgs m = {0};
    SylDeriveOptions d = {.steps = -1, .diag = stderr};
    SylRenderOptions ro = {.diag = stderr, .view = SYL_VIEW_FRONT, .width = 1600, .height = 900};
    CliArgs a = {.m = &m, .d = &d, .ro = &ro, .seeds = 1};
    int done = cli_parse(&cli_compare_command, argc, argv, &a);
    if (done != CLI_RUN) return done;
    const char *output = a.output, *image = a.image;
    int format = a.format, nruns = a.seeds, ncols = a.nfiles;
    ro.threads = d.threads;
    Column *cols = calloc((size_t)ncols, sizeof *cols);
    int status = cols ? SYL_OK : SYL_ELIMIT;
    for (int i = 0; i < ncols && !status; i++) {
        cli_model_spec(&cols[i].args, a.files[i]);
        if (!strcmp(cols[i].args.path, "-")) { /* read more than once: it must be a file */
            fprintf(stderr, "sylva compare: reads models from files, not from standard input\n");
            status = SYL_EUSAGE;
            break;
        }
        memcpy(cols[i].args.sets, m.sets, sizeof m.sets);
        cols[i].args.nsets = m.nsets;
        cols[i].args.age = m.age; /* --age: every strands block of the line-up */
        cols[i].args.levels = m.levels; /* --levels: every weber block's */
        cols[i].runs = calloc((size_t)nruns, sizeof *cols[i].runs);
        if (!cols[i].runs) status = SYL_ELIMIT;
    }
    if (status == SYL_ELIMIT) fprintf(stderr, "sylva: error: out of memory\n");
    for (int i = 0; i < ncols && !status; i++) status = run_column(&cols[i], &d, d.use_seed, nruns, image != NULL);
    for (int i = 0; i < ncols && !status; i++) {
        cols[i].label = cols[i].name;
        for (int j = 0; j < ncols; j++)
            if (j != i && !strcmp(cols[i].name, cols[j].name)) cols[i].label = cols[i].args.spec;
    }
    int nrows = 0;
    Row *rows = status ? NULL : make_rows(cols, ncols, nruns, &nrows);
    if (!status && !rows) {
        fprintf(stderr, "sylva: error: out of memory\n");
        status = SYL_ELIMIT;
    }
    if (!status && image) status = write_image(cols, ncols, image, &ro);
    if (!status) {
        OutFile out; /* after the picture: a table means that everything was done */
        if (!out_open(&out, output)) status = SYL_EIO;
        else {
            if (format == CLI_FORMAT_CSV) write_csv(out.f, cols, ncols, nruns, rows, nrows);
            else if (format == CLI_FORMAT_JSON) write_json(out.f, cols, ncols, nruns, rows, nrows);
            else if (!write_text(out.f, cols, ncols, nruns, rows, nrows)) {
                fprintf(stderr, "sylva: error: out of memory\n");
                status = SYL_ELIMIT;
            }
            status = out_close(&out, status);
        }
    }
    free(rows);
    for (int i = 0; cols && i < ncols; i++) {
        free(cols[i].runs);
        syl_mesh_free(cols[i].mesh);
    }
    free(cols);
    return status;
}
