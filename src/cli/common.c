#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"

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

bool cli_number(const char *opt, const char *arg, double min, double max, double *out) {
    char *end;
    errno = 0;
    double v = strtod(arg, &end);
    if (!*arg || *end || errno || !isfinite(v) || v < min || v > max) {
        fprintf(stderr, "sylva: error: %s expects a number from %g to %g, not '%s'\n", opt, min, max, arg);
        return false;
    }
    *out = v;
    return true;
}

bool cli_integer(const char *opt, const char *arg, double min, double max, double *out) {
    char *end;
    errno = 0;
    double v = strtod(arg, &end);
    if (!*arg || *end || errno || !isfinite(v) || v < min || v > max || v != floor(v)) {
        fprintf(stderr, "sylva: error: %s expects a whole number from %.0f to %.0f, not '%s'\n", opt, min, max, arg);
        return false;
    }
    *out = v;
    return true;
}

bool cli_size(const char *opt, const char *arg, unsigned long long *out) {
    char *end;
    errno = 0;
    double v = strtod(arg, &end);
    double unit = 1;
    if (*end == 'k' || *end == 'K') unit = 1024.0, end++;
    else if (*end == 'm' || *end == 'M') unit = 1024.0 * 1024, end++;
    else if (*end == 'g' || *end == 'G') unit = 1024.0 * 1024 * 1024, end++;
    if (*end == 'B' || *end == 'b') end++;
    if (!*arg || *end || errno || !(v > 0) || v * unit > 1e18) {
        fprintf(stderr, "sylva: error: %s expects a size such as 512M or 4G, not '%s'\n", opt, arg);
        return false;
    }
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

SylProgram *cli_compile(ModelArgs *m, int lint, int *status) {
    SylCompileOptions opt = {.model = m->model, .overrides = m->sets, .noverrides = m->nsets,
                             .diag = stderr, .lint = lint};
    return syl_compile(m->path, NULL, 0, &opt, status);
}

int cli_derive_option(int c, char *arg, ModelArgs *m, SylDeriveOptions *d) {
    double v;
    unsigned long long size;
    switch (c) {
    case 'n':
        if (!cli_integer("-n", arg, 0, 1e6, &v)) return -1;
        d->steps = (int)v;
        return 1;
    case 's':
        if (!cli_integer("--seed", arg, 0, 9007199254740991.0, &v)) return -1;
        d->use_seed = 1;
        d->seed = (uint64_t)v;
        return 1;
    case 'S': return cli_set(m, arg) ? 1 : -1;
    case 'j':
        if (!cli_integer("-j", arg, 1, 256, &v)) return -1;
        d->threads = (int)v;
        return 1;
    case 'M':
        if (!cli_integer("--max-modules", arg, 1, 2147483647.0, &v)) return -1;
        d->max_modules = (uint64_t)v;
        return 1;
    case 'm':
        if (!cli_size("--max-memory", arg, &size)) return -1;
        d->max_memory = size;
        return 1;
    default: return 0;
    }
}

int cli_derive_interpreted(ModelArgs *m, SylDeriveOptions *d, SylProgram **p, SylString **s) {
    int status;
    *s = NULL;
    *p = cli_compile(m, 0, &status);
    if (!*p) return status;
    SylString *derived = NULL;
    status = syl_derive(*p, d, &derived);
    if (!status) status = syl_interpret(*p, derived, d, s);
    syl_string_free(derived);
    if (status) {
        syl_string_free(*s);
        syl_program_free(*p);
        *s = NULL;
        *p = NULL;
    }
    return status;
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

typedef struct StepProgress {
    Progress bar;
    int steps;
} StepProgress;

static void on_step(void *user, int step, const SylString *s) {
    (void)s;
    StepProgress *sp = user;
    if (sp->steps > 0) cli_progress(&sp->bar, step >= sp->steps ? 1.0 : (double)step / sp->steps);
}

int cli_plant(ModelArgs *m, SylDeriveOptions *d, const SylMeshOptions *mo, Plant *out) {
    memset(out, 0, sizeof *out);
    double t0 = cli_now();
    int status;
    SylProgram *p = cli_compile(m, 0, &status);
    if (!p) return status;
    snprintf(out->name, sizeof out->name, "%s", syl_program_name(p));
    /* grow blocks grow; a file with a scene, named without a model, makes its scene */
    int nscene = 0;
    bool scene = syl_program_kind(p) == SYL_MODEL_SCENE || (!m->model && syl_program_scene(p, &nscene));
    if (scene || syl_program_kind(p) == SYL_MODEL_GROW) return cli_grow_plant(p, scene, d, mo, out);
    StepProgress sp = {.steps = d->steps >= 0 ? d->steps : syl_program_steps(p)};
    cli_progress_start(&sp.bar, "deriving");
    if (!d->on_step) {
        d->on_step = on_step;
        d->user = &sp;
    }
    SylString *derived = NULL, *s = NULL;
    status = syl_derive(p, d, &derived);
    cli_progress(&sp.bar, 1);
    if (d->on_step == on_step) d->on_step = NULL;
    if (!status) status = syl_interpret(p, derived, d, &s);
    syl_string_free(derived);
    double t1 = cli_now();
    if (!status) {
        SylTurtleOptions topt = {.diag = stderr};
        out->modules = syl_string_length(s);
        status = syl_turtle(p, s, &topt, &out->sk);
    }
    syl_string_free(s);
    syl_program_free(p);
    double t2 = cli_now();
    if (!status && mo) status = syl_mesh_build(out->sk, mo, &out->mesh);
    double t3 = cli_now();
    out->derive_s = t1 - t0;
    out->turtle_s = t2 - t1;
    out->mesh_s = t3 - t2;
    if (status) cli_plant_free(out);
    return status;
}

void cli_plant_free(Plant *pl) {
    syl_mesh_free(pl->mesh);
    syl_skeleton_free(pl->sk);
    pl->mesh = NULL;
    pl->sk = NULL;
}

bool out_open(OutFile *o, const char *path) {
    return outfile_open(o, path ? path : "-", &cli_temp_hooks, stderr);
}

int out_close(OutFile *o, int status) {
    if (!outfile_close(o, status == SYL_OK, stderr) && !status) status = SYL_EIO;
    return status;
}

double cli_now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

double cli_peak_mb(void) {
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)ru.ru_maxrss / 1024.0;
}

bool cli_view(const char *arg, SylView *v) {
    static const struct { const char *name; SylView view; } views[] = {
        {"iso", SYL_VIEW_ISO}, {"front", SYL_VIEW_FRONT}, {"side", SYL_VIEW_SIDE},
        {"top", SYL_VIEW_TOP}, {"auto", SYL_VIEW_AUTO},
    };
    for (size_t i = 0; i < sizeof views / sizeof *views; i++)
        if (!strcmp(arg, views[i].name)) {
            *v = views[i].view;
            return true;
        }
    fprintf(stderr, "sylva: error: --view expects iso, front, side, top or auto, not '%s'\n", arg);
    return false;
}

bool cli_picture_size(const char *arg, int *w, int *h) {
    char *end;
    long a = strtol(arg, &end, 10), b = a;
    if (end != arg && (*end == 'x' || *end == 'X')) {
        const char *s = end + 1;
        b = strtol(s, &end, 10);
        if (end == s) b = 0;
    }
    if (end == arg || *end || a < 1 || b < 1 || a > 16384 || b > 16384) {
        fprintf(stderr, "sylva: error: --size expects WIDTHxHEIGHT, each from 1 to 16384, not '%s'\n", arg);
        return false;
    }
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
