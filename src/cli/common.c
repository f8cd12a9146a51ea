/* Shared pieces of the subcommands: model arguments, numeric readers, progress, the plant, output files. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli/cli.h"
#include "lang/kinds.h"
#include "sylva/lod.h"

static void print_record(void *user, const SylDiagnostic *d) {
    (void)user;
    syl_diagnostic_write(d, stderr);
}
const SylSink cli_sink = {print_record, NULL};

void cli_model_spec(ModelArgs *m, const char *spec) {
    struct stat st;
    m->spec = spec;
    snprintf(m->path, sizeof m->path, "%s", spec);
    m->model = NULL;
    char *colon = strrchr(m->path, ':');
    if (colon && colon[1] && stat(m->path, &st) != 0) {
        *colon = 0;
        m->model = colon + 1;
    }
}

/* The one reader of numbers on the command line. false when arg is not a number at all; a
 * number too large for a double is +-inf (so out of any range), one too small to tell from 0
 * is what strtod makes of it (0 or a denormal, with ERANGE), and is accepted. end: where
 * the number stops (NULL: it must take the whole argument). */
static bool read_number(const char *arg, double *v, char **end) {
    char *stop;
    errno = 0;
    *v = strtod(arg, &stop);
    if (stop == arg || isnan(*v) || (!end && *stop)) return false;
    for (const char *c = arg; c < stop; c++) /* decimal only: 0x10 is no count, nor 0x5 a size */
        if (*c == 'x' || *c == 'X' || *c == 'p' || *c == 'P') return false;
    if (end) *end = stop;
    return true;
}

static bool out_of_range(const char *opt, const char *arg, double v, double min, double max, const char *unit) {
    if (v >= min && v <= max) return false;
    fprintf(stderr, "sylva: error: %s '%s' is out of range (%s %.16g%s)\n", opt, arg, v > max ? "at most" : "at least",
            v > max ? max : min, unit);
    return true;
}

bool cli_number(const char *opt, const char *arg, double min, double max, double *out) {
    double v;
    if (!read_number(arg, &v, NULL)) {
        fprintf(stderr, "sylva: error: %s expects a number from %g to %g, not '%s'\n", opt, min, max, arg);
        return false;
    }
    if (out_of_range(opt, arg, v, min, max, "")) return false;
    *out = v;
    return true;
}

bool cli_integer(const char *opt, const char *arg, double min, double max, double *out) {
    double v;
    if (!read_number(arg, &v, NULL) || (isfinite(v) && v != floor(v))) {
        fprintf(stderr, "sylva: error: %s expects a whole number from %.0f to %.0f, not '%s'\n", opt, min, max, arg);
        return false;
    }
    if (out_of_range(opt, arg, v, min, max, "")) return false;
    *out = v;
    return true;
}

bool cli_size(const char *opt, const char *arg, unsigned long long *out) {
    double v, unit = 1;
    char *end;
    bool ok = read_number(arg, &v, &end);
    if (ok && (*end == 'k' || *end == 'K')) unit = 1024.0, end++;
    else if (ok && (*end == 'm' || *end == 'M')) unit = 1024.0 * 1024, end++;
    else if (ok && (*end == 'g' || *end == 'G')) unit = 1024.0 * 1024 * 1024, end++;
    if (ok && (*end == 'B' || *end == 'b')) end++;
    if (!ok || *end) {
        fprintf(stderr, "sylva: error: %s expects a size such as 512M or 4G, not '%s'\n", opt, arg);
        return false;
    }
    if (!(v > 0)) {
        fprintf(stderr, "sylva: error: %s '%s' is out of range (more than 0 bytes)\n", opt, arg);
        return false;
    }
    if (out_of_range(opt, arg, v * unit, 1, 1e18, " bytes")) return false;
    *out = (unsigned long long)(v * unit);
    return true;
}

bool cli_set(ModelArgs *m, char *arg) {
    char *eq = strchr(arg, '=');
    if (!eq || eq == arg) {
        fprintf(stderr, "sylva: error: --set expects name=value, not '%s'\n", arg);
        return false;
    }
    if (m->nsets == MAX_SETS) {
        fprintf(stderr, "sylva: error: at most %d --set options\n", MAX_SETS);
        return false;
    }
    double v;
    if (!cli_number("--set", eq + 1, -1e300, 1e300, &v)) return false;
    *eq = 0; /* the name stays in argv: nothing to free */
    m->sets[m->nsets].name = arg;
    m->sets[m->nsets++].value = v;
    return true;
}

SylProgram *cli_compile(ModelArgs *m, int warn, int *status) {
    SylCompileOptions opt = {.model = m->model, .overrides = m->sets, .noverrides = m->nsets,
                             .diag = stderr, .warn = m->warned ? 0 : warn, .validate = syl_validate,
                             .allow_paths = m->allow, .nallow_paths = m->nallow};
    m->warned = true; /* a model compiled again (each seed of compare) says them once */
    return syl_compile(m->path, NULL, 0, &opt, status);
}

void cli_progress_start(Progress *p, const char *label) {
    memset(p, 0, sizeof *p);
    p->label = label;
    p->start = cli_now();
    p->enabled = isatty(2);
}

void cli_progress(void *progress, double fraction) {
    Progress *p = progress;
    if (!p->enabled) return;
    double now = cli_now();
    if (fraction < 1 && (now - p->start < 1.0 || now - p->last < 0.1)) return;
    if (fraction >= 1) {
        if (p->shown) fputs("\r\033[K", stderr);
        p->shown = false;
        return;
    }
    p->last = now;
    p->shown = true;
    enum { WIDTH = 40 };
    char bar[WIDTH + 1];
    int fill = (int)(fraction * WIDTH + 0.5);
    for (int i = 0; i < WIDTH; i++) bar[i] = i < fill ? '#' : '.';
    bar[WIDTH] = 0;
    fprintf(stderr, "\r%-10s [%s] %3d%%", p->label, bar, (int)(fraction * 100 + 0.5));
    fflush(stderr);
}

int cli_plant(ModelArgs *m, SylDeriveOptions *d, const SylMeshOptions *mo, Plant *out) {
    memset(out, 0, sizeof *out);
    double t0 = cli_now();
    int status;
    SylProgram *p = cli_compile(m, SYL_WARN_MISTAKES | SYL_WARN_DRAWS, &status);
    if (!p) return status;
    double compiled = cli_now() - t0;
    snprintf(out->name, sizeof out->name, "%s", syl_program_name(p));
    double lod = syl_program_setting(p, "lod");
    out->lod = lod > 0 && lod <= SYL_LOD_MAX ? (int)lod : 0;
    /* grow blocks grow; a file with a scene, named without a model, makes its scene */
    int nscene = 0;
    bool scene = lang_kind_is(syl_program_kind(p), KF_UNNAMED) || (!m->model && syl_program_scene(p, &nscene));
    out->grown = scene || lang_kind_is(syl_program_kind(p), KF_GROWS);
    /* -n is the years of a grow block or scene: the limit of --years, with its message */
    if (out->grown && d->steps > SYL_GROW_MAX_YEARS) {
        char arg[32];
        double v;
        snprintf(arg, sizeof arg, "%d", d->steps);
        cli_integer("-n", arg, 0, SYL_GROW_MAX_YEARS, &v);
        syl_program_free(p);
        return SYL_EUSAGE;
    }
    Progress bar;
    cli_progress_start(&bar, out->grown ? "growing" : "deriving");
    SylPlantOptions po = {.use_steps = d->steps >= 0, .steps = d->steps, .use_seed = d->use_seed, .seed = d->seed,
                          .threads = d->threads, .max_modules = d->max_modules, .max_memory = d->max_memory,
                          .max_work = d->max_work, .max_metamers = m->max_metamers, .max_buds = m->max_buds, .age = m->age, .levels = m->levels,
                          .budget = d->budget, .until = mo ? SYL_PLANT_MESH : SYL_PLANT_SKELETON,
                          .drop_string = 1, .scene = !m->model, .mesh = mo, .diag = stderr,
                          .progress = cli_progress, .user = &bar};
    SylPlant pl;
    status = syl_plant_build(p, &po, &pl);
    syl_program_free(p);
    if (status) return status;
    out->sk = pl.skeleton;
    out->mesh = pl.mesh;
    out->parts = pl.parts;
    out->nparts = pl.nparts;
    out->modules = pl.modules;
    out->grow = pl.grow;
    out->derive_s = (out->grown ? 0 : compiled) + pl.derive_s; /* growth alone, as --stats says */
    out->derive_cpu_s = pl.derive_cpu_s;
    out->turtle_s = pl.turtle_s;
    out->mesh_s = pl.mesh_s;
    out->mesh_cpu_s = pl.mesh_cpu_s;
    d->rewritten = pl.rewritten;
    return SYL_OK;
}

void cli_plant_free(Plant *pl) {
    syl_mesh_free(pl->mesh);
    syl_mesh_parts_free(pl->parts, pl->nparts);
    pl->parts = NULL;
    pl->nparts = 0;
    syl_skeleton_free(pl->sk);
    pl->mesh = NULL;
    pl->sk = NULL;
}

bool out_open(OutFile *o, const char *path) {
    return outfile_open(o, path ? path : "-", &cli_temp_hooks, &cli_sink);
}

int out_close(OutFile *o, int status) {
    if (!outfile_close(o, status == SYL_OK, &cli_sink) && !status) status = SYL_EIO;
    return status;
}

double cli_now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

double cli_cpu_now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

double cli_peak_mb(void) {
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)ru.ru_maxrss / 1024.0;
}

bool cli_view(const char *arg, SylView *v) { return cli_view_or(arg, v, ""); }

bool cli_view_or(const char *arg, SylView *v, const char *also) {
    static const struct { const char *name; SylView view; } views[] = {
        {"iso", SYL_VIEW_ISO}, {"front", SYL_VIEW_FRONT}, {"side", SYL_VIEW_SIDE},
        {"top", SYL_VIEW_TOP}, {"auto", SYL_VIEW_AUTO},
    };
    for (size_t i = 0; i < sizeof views / sizeof *views; i++)
        if (!strcmp(arg, views[i].name)) {
            *v = views[i].view;
            return true;
        }
    fprintf(stderr, "sylva: error: --view expects iso, front, side, top or auto%s, not '%s'\n", also, arg);
    return false;
}

bool cli_picture_size(const char *arg, int *w, int *h) {
    double a, b;
    char *end;
    bool ok = read_number(arg, &a, &end);
    b = a;
    if (ok && (*end == 'x' || *end == 'X')) ok = read_number(end + 1, &b, &end);
    if (!ok || *end || (isfinite(a) && a != floor(a)) || (isfinite(b) && b != floor(b))) {
        fprintf(stderr, "sylva: error: --size expects WIDTHxHEIGHT, each from 1 to 16384, not '%s'\n", arg);
        return false;
    }
    if (out_of_range("--size", arg, a < b ? a : b, 1, 16384, "") || out_of_range("--size", arg, a > b ? a : b, 1, 16384, ""))
        return false;
    *w = (int)a;
    *h = (int)b;
    return true;
}

char *cli_output_name(const ModelArgs *m, const char *dir, const char *ext) {
    const char *name = m->model;
    size_t len;
    if (name) len = strlen(name);
    else {
        const char *slash = strrchr(m->path, '/');
        name = slash ? slash + 1 : m->path;
        if (!strcmp(name, "-") || !*name) name = "plant";
        const char *dot = strrchr(name, '.');
        len = dot && dot != name ? (size_t)(dot - name) : strlen(name);
    }
    size_t n = (dir ? strlen(dir) + 1 : 0) + len + strlen(ext) + 2;
    char *out = malloc(n);
    if (out) snprintf(out, n, "%s%s%.*s.%s", dir ? dir : "", dir ? "/" : "", (int)len, name, ext);
    return out;
}
