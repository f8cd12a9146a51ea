/* The `scene` block's directives:
 *
 *   plant NAME at (x, y, z) [seed S] [years N]      a model of this file
 *   plant "file.syl[:Model]" at (x, y, z) ...        a model of another file (relative path)
 *   obstacle "file.obj" [at (x, y, z)] [scale S]     a triangle mesh
 *   ground Y                                         the ground plane's height
 *   ground "terrain.obj" [at (x, y, z)] [scale S]    a terrain mesh; plants stand on it
 *   sun direction (x, y, z)                          towards the sun
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kinds/kinds.h"
#include "util/file.h"
#include "env/objread.h"
#include "lang/textures.h"
#include "lang/program.h"
#include "scene/spec.h"
#include "sot/params.h"
#include "sot/reader.h"
#include "sylva/grow.h"
#include "sylva/trees.h"

/* The ranges of the scene's rows (scene/params.def: what `sylva describe` shows of a scene) */
enum {
#define SCENE_ROW(id, ...) SR_##id,
#include "scene/params.def"
};
static const struct { double lo, hi; } range[] = {
#define SCENE_ROW(id, nm, ty, l, h, ...) [SR_##id] = {l, h},
#include "scene/params.def"
};

static bool vec3_of(Reader *r, const SylDirArg *a, const char *what, float out[3]) {
    if (a->kind != SYL_DARG_TUPLE || a->nvalues != 3) {
        ERR(r, a->line, a->col, "'%s' expects a point (x, y, z)", what);
        return false;
    }
    for (int k = 0; k < 3; k++) {
        if (!isfinite(a->values[k]) || fabs(a->values[k]) > range[SR_PLANT_X].hi) {
            ERR(r, a->line, a->col, "'%s': coordinates must be finite, within a million units", what);
            return false;
        }
        out[k] = (float)a->values[k];
    }
    return true;
}

/* KEY VALUE pairs from args[i] on: at, seed, years, scale (as allowed by the mask). */
enum { K_AT = 1, K_SEED = 2, K_YEARS = 4, K_SCALE = 8 };
static bool read_keys(Reader *r, const SylDirective *d, int i, int allowed, float at[3], uint64_t *seed,
                      bool *seed_set, int *years, bool *years_set, float *scale) {
    static const char *const names[] = {"at", "seed", "years", "scale"};
    for (; i < d->nargs; i += 2) {
        const SylDirArg *a = &d->args[i];
        int key = -1;
        for (int k = 0; k < 4; k++)
            if (a->kind == SYL_DARG_WORD && !strcmp(a->text, names[k]) && (allowed & (1 << k))) key = k;
        if (key < 0) {
            char list[64] = "";
            for (int k = 0; k < 4; k++)
                if (allowed & (1 << k)) strcat(strcat(list, list[0] ? ", " : ""), names[k]);
            if (a->kind == SYL_DARG_WORD) ERR(r, a->line, a->col, "unknown key '%s' of '%s' (keys: %s)", a->text, d->name, list);
            else ERR(r, a->line, a->col, "expected a key of '%s' here (%s)", d->name, list);
            return false;
        }
        if (i + 1 >= d->nargs) {
            ERR(r, a->line, a->col, "'%s' needs a value after it", a->text);
            return false;
        }
        const SylDirArg *v = &d->args[i + 1];
        double x;
        if (key == 0) {
            if (!vec3_of(r, v, "at", at)) return false;
        } else if (!reader_number(v, &x) || !isfinite(x)) {
            ERR(r, v->line, v->col, "'%s' expects a number", a->text);
            return false;
        } else if (key == 1) {
            if (x < 0 || x > range[SR_PLANT_SEED].hi || x != floor(x)) {
                ERR(r, v->line, v->col, "'seed' expects a whole number from 0, not %g", x);
                return false;
            }
            *seed = (uint64_t)x;
            *seed_set = true;
        } else if (key == 2) {
            if (x < 0 || x > range[SR_PLANT_YEARS].hi || x != floor(x)) {
                ERR(r, v->line, v->col, "'years' expects a whole number from 0 to %g, not %g", range[SR_PLANT_YEARS].hi, x);
                return false;
            }
            *years = (int)x;
            *years_set = true;
        } else {
            if (!(x > 0) || x > range[SR_OBSTACLE_SCALE].hi) {
                ERR(r, v->line, v->col, "'scale' expects a number above 0, not %g", x);
                return false;
            }
            *scale = (float)x;
        }
    }
    return true;
}

/* The file's model names, listed once per scene (listing parses the whole file). */
typedef struct Names {
    const char *v[512];
    SylModelKind kind[512];
    char buf[16384];
    int n; /* -1: not listed yet */
} Names;

/* The kind of the file's model called name; -1: none. */
static int model_kind(const SylProgram *p, Names *names, const char *name) {
    if (names->n < 0) {
        size_t len = 0;
        const char *text = syl_program_source(p, &len);
        names->n = lang_list_models(syl_program_path(p), text, len, names->v, names->kind, 512, names->buf,
                                    sizeof names->buf);
    }
    for (int i = 0; i < names->n; i++)
        if (!strcmp(names->v[i], name)) return (int)names->kind[i];
    return -1;
}

/* A zeroed slot at the end of *arr, doubling its capacity (NULL: out of memory). */
static void *push(void *arrp, int *n, int *cap, size_t elem) {
    void **arr = arrp;
    if (*n == *cap) {
        int c = *cap ? 2 * *cap : 16;
        void *p = realloc(*arr, (size_t)c * elem);
        if (!p) return NULL;
        *arr = p;
        *cap = c;
    }
    char *slot = (char *)*arr + (size_t)(*n)++ * elem;
    memset(slot, 0, elem);
    return slot;
}

/* --set scene.ground, scene.plant.N.KEY (x, y, z, seed, years) and scene.obstacle.N.KEY
 * (x, y, z, scale), N counting the lines of each kind from 1 (an `obstacle` and a terrain
 * `ground "file.obj"` line count as obstacles). */
static void set_one(Reader *r, SceneSpec *s, const char *typed, const char *name, double v) {
    static const char *const axes = "xyz";
    if (!strcmp(name, "ground")) {
        if (!isfinite(v) || fabs(v) > range[SR_GROUND].hi) {
            ERR(r, 0, 0, "--set %s: the ground's height must be finite, within a million units", typed);
            return;
        }
        s->ground = (float)v;
        s->ground_set = true;
        return;
    }
    bool plant = !strncmp(name, "plant.", 6), obstacle = !strncmp(name, "obstacle.", 9);
    const char *at = plant ? name + 6 : obstacle ? name + 9 : NULL;
    char *end = NULL;
    long n = at ? strtol(at, &end, 10) : 0;
    int count = plant ? s->nplants : s->nobstacles;
    if (!at || end == at || *end != '.') {
        ERR(r, 0, 0, "--set %s: the scene has no number '%s' (scene.ground, scene.plant.N.x|y|z|seed|years, "
            "scene.obstacle.N.x|y|z|scale)", typed, name);
        return;
    }
    if (n < 1 || n > count) {
        ERR(r, 0, 0, "--set %s: the scene has %d %s line%s", typed, count, plant ? "plant" : "obstacle",
            count == 1 ? "" : "s");
        return;
    }
    const char *key = end + 1;
    float *where = plant ? s->plants[n - 1].at : s->obstacles[n - 1].at;
    if (key[0] && !key[1] && strchr(axes, key[0])) {
        if (!isfinite(v) || fabs(v) > range[SR_PLANT_X].hi) {
            ERR(r, 0, 0, "--set %s: coordinates must be finite, within a million units", typed);
            return;
        }
        where[strchr(axes, key[0]) - axes] = (float)v;
    } else if (plant && (!strcmp(key, "seed") || !strcmp(key, "years"))) {
        bool seed = key[0] == 's';
        double hi = range[seed ? SR_PLANT_SEED : SR_PLANT_YEARS].hi;
        if (v < 0 || v > hi || v != floor(v)) {
            ERR(r, 0, 0, "--set %s: '%s' expects a whole number from 0 to %.17g, not %g", typed, key, hi, v);
            return;
        }
        ScenePlant *pl = &s->plants[n - 1];
        if (seed) pl->seed = (uint64_t)v, pl->seed_set = true;
        else pl->years = (int)v, pl->years_set = true;
    } else if (obstacle && !strcmp(key, "scale")) {
        if (!(v > 0) || v > range[SR_OBSTACLE_SCALE].hi) {
            ERR(r, 0, 0, "--set %s: 'scale' expects a number above 0, not %g", typed, v);
            return;
        }
        s->obstacles[n - 1].scale = (float)v;
    } else {
        ERR(r, 0, 0, "--set %s: a scene's %s has no number '%s' (%s)", typed, plant ? "plant" : "obstacle", key,
            plant ? "x, y, z, seed, years" : "x, y, z, scale");
    }
}

static void apply_sets(Reader *r, SceneSpec *s) {
    const SylProgram *p = r->p;
    for (int i = 0; i < p->noverrides; i++)
        if (!strncmp(p->overrides[i].name, "scene.", 6))
            set_one(r, s, p->overrides[i].name, p->overrides[i].name + 6, p->overrides[i].value);
}

int scene_spec_read(const SylProgram *p, SceneSpec *s, FILE *diag) {
    memset(s, 0, sizeof *s);
    s->sun[1] = 1;
    Reader r = {.p = p, .diag = diag};
    int n = 0;
    const SylDirective *dirs = syl_program_scene(p, &n);
    Names *names = malloc(sizeof *names);
    if (!names) {
        program_say(p, diag, DIAG_ERROR, NULL, "out of memory");
        return 1;
    }
    names->n = -1;
    for (int i = 0; dirs && i < n; i++) {
        const SylDirective *d = &dirs[i];
        const SylDirArg *a0 = d->nargs ? &d->args[0] : NULL;
        if (!strcmp(d->name, "plant")) {
            if (!a0 || (a0->kind != SYL_DARG_WORD && a0->kind != SYL_DARG_STRING)) {
                ERR(&r, a0 ? a0->line : d->line, a0 ? a0->col : d->col,
                    "'plant' expects a model's name or \"file.syl\" first");
                continue;
            }
            ScenePlant *pl = push(&s->plants, &s->nplants, &s->plants_cap, sizeof *pl);
            if (!pl) {
                ERR(&r, d->line, d->col, "out of memory");
                break;
            }
            pl->line = d->line, pl->col = d->col;
            if (a0->kind == SYL_DARG_WORD) {
                pl->model = a0->text;
                int kind = model_kind(p, names, a0->text);
                if (kind < 0)
                    ERR(&r, a0->line, a0->col, "no plant model '%s' in this file (an lsystem, grow, weber or strands block)",
                        a0->text);
                else if (!lang_kind_is((SylModelKind)kind, KF_IN_SCENE))
                    ERR(&r, a0->line, a0->col, "the %s '%s' cannot stand in a scene", syl_model_kind_name((SylModelKind)kind),
                        a0->text);
            } else pl->file = a0->text;
            bool at_given = false;
            for (int k = 1; k < d->nargs; k++)
                if (d->args[k].kind == SYL_DARG_WORD && !strcmp(d->args[k].text, "at")) at_given = true;
            float scale = 1;
            read_keys(&r, d, 1, K_AT | K_SEED | K_YEARS, pl->at, &pl->seed, &pl->seed_set, &pl->years, &pl->years_set,
                      &scale);
            if (!at_given) ERR(&r, d->line, d->col, "'plant' needs a place: at (x, y, z)");
        } else if (!strcmp(d->name, "obstacle") || (!strcmp(d->name, "ground") && a0 && a0->kind == SYL_DARG_STRING)) {
            if (!a0 || a0->kind != SYL_DARG_STRING) {
                ERR(&r, a0 ? a0->line : d->line, a0 ? a0->col : d->col, "'obstacle' expects a file name: \"file.obj\"");
                continue;
            }
            SceneObstacle *o = push(&s->obstacles, &s->nobstacles, &s->obstacles_cap, sizeof *o);
            if (!o) {
                ERR(&r, d->line, d->col, "out of memory");
                break;
            }
            o->file = a0->text;
            o->scale = 1;
            o->terrain = d->name[0] == 'g';
            o->line = a0->line, o->col = a0->col;
            uint64_t seed;
            bool set;
            int years;
            read_keys(&r, d, 1, K_AT | K_SCALE, o->at, &seed, &set, &years, &set, &o->scale);
        } else if (!strcmp(d->name, "ground")) {
            double y;
            if (!a0 || !reader_number(a0, &y) || !isfinite(y) || d->nargs != 1) {
                ERR(&r, a0 ? a0->line : d->line, a0 ? a0->col : d->col,
                    "'ground' expects a height (ground 0) or a terrain mesh (ground \"hill.obj\")");
                continue;
            }
            s->ground = (float)y;
            s->ground_set = true;
        } else if (!strcmp(d->name, "sun")) {
            int k = a0 && a0->kind == SYL_DARG_WORD && !strcmp(a0->text, "direction") ? 1 : 0;
            if (k >= d->nargs || d->nargs != k + 1) {
                ERR(&r, d->line, d->col, "'sun' expects direction (x, y, z)");
                continue;
            }
            if (!vec3_of(&r, &d->args[k], "sun direction", s->sun)) continue;
            float len = sqrtf(s->sun[0] * s->sun[0] + s->sun[1] * s->sun[1] + s->sun[2] * s->sun[2]);
            if (!(len > 0) || s->sun[1] <= 0) {
                ERR(&r, d->args[k].line, d->args[k].col, "the sun must be above the horizon (y > 0)");
                continue;
            }
            for (int j = 0; j < 3; j++) s->sun[j] /= len;
            s->sun_set = true;
        } else {
            ERR(&r, d->line, d->col, "unknown directive '%s' in a scene (known: plant, obstacle, ground, sun)", d->name);
        }
    }
    if (dirs && !s->nplants && !r.errors) ERR(&r, 0, 0, "the scene has no plant");
    int before = r.errors;
    if (dirs && !r.errors) apply_sets(&r, s);
    s->set_errors = r.errors - before;
    free(names);
    return r.errors;
}

void scene_spec_free(SceneSpec *s) {
    free(s->plants);
    free(s->obstacles);
    memset(s, 0, sizeof *s);
}

int scene_spec_path(const SylProgram *p, const char *file, char **model, char **out) {
    char *name = strdup(file);
    if (!name) return SYL_ELIMIT;
    char *colon = model ? strrchr(name, ':') : NULL; /* "file.syl:Model", split before the file is judged */
    if (colon && colon > name && colon[1] && (!strrchr(name, '/') || colon > strrchr(name, '/'))) *colon = 0;
    else colon = NULL;
    if (model) *model = NULL;
    int st = syl_program_file(p, name, out);
    if (!st && colon && !(*model = strdup(colon + 1))) {
        free(*out);
        *out = NULL;
        st = SYL_ELIMIT;
    }
    free(name);
    return st;
}

SylProgram *scene_plant_file(const SylProgram *p, const char *file, int line, int col, FILE *diag, int *status) {
    char *path = NULL, *model = NULL;
    *status = scene_spec_path(p, file, &model, &path);
    if (*status) {
        if (*status == SYL_EIO && diag)
            syl_program_report_error(p, diag, line, col, "the plant file \"%s\" cannot be read: %s", file, syl_file_refused);
        return NULL;
    }
    /* the --set values reach every plant; its own folder is within p's: it reads no further */
    SylCompileOptions copt = {.diag = diag, .overrides = p->overrides, .noverrides = p->noverrides, .sibling = 1,
                              .model = model, .allow_paths = p->roots, .nallow_paths = p->nroots,
                              .validate = syl_validate}; /* another file: checked as `sylva check` would */
    size_t len = 0;
    char *text = file_read_named(path, &len, NULL); /* a regular file, of a bounded size */
    SylProgram *q = NULL;
    if (!text) {
        program_say(p, diag, DIAG_ERROR, NULL, "cannot read '%s': %s", path, file_strerror(errno));
        *status = errno == ENOMEM ? SYL_ELIMIT : SYL_EIO;
    } else if (!syl_text_is_model(text, len)) { /* its lines are not shown: it may be anything */
        if (diag)
            syl_program_report_error(p, diag, line, col, "the plant file \"%s\" is not a model file (no lsystem, grow, weber or strands block)", file);
        *status = SYL_EMODEL;
    } else {
        q = syl_compile(path, text, len, &copt, status);
    }
    file_free_named(text, len, NULL), free(path), free(model);
    return q;
}

/* A file the scene names, read as the run will read it: one outside the folders the model may
 * read, one that cannot be read (said with the path it was looked for at) or a malformed one is
 * an error at its line (returns 1), since the commands that grow the scene fail on it. */
static int check_file(const SylProgram *p, FILE *diag, const char *what, const char *file, int line, int col) {
    bool plant = !strcmp(what, "plant");
    char *path = NULL, *model = NULL;
    int st = scene_spec_path(p, file, plant ? &model : NULL, &path);
    free(model);
    if (st == SYL_EIO) syl_program_report_error(p, diag, line, col, "the %s file \"%s\" cannot be read: %s", what, file, syl_file_refused);
    if (st) return st == SYL_EIO;
    if (lang_check_file(p, diag, what, file, line, col)) {
        free(path);
        return 1;
    }
    int bad = 0;
    if (plant) {
        SylProgram *q = scene_plant_file(p, file, line, col, diag, &st);
        bad = !q;
        syl_program_free(q);
    } else {
        ObjMesh m;
        bad = obj_read(path, &m, diag_sink(&(SylSink){0}, diag, program_sink(p))) != SYL_OK;
        obj_free(&m);
        if (bad) syl_program_report_error(p, diag, line, col, "cannot use the %s \"%s\"", what, file);
    }
    free(path);
    return bad;
}

int scene_spec_check(const SylProgram *p, FILE *diag, bool files) {
    SceneSpec s;
    int errors = scene_spec_read(p, &s, diag), set_errors = s.set_errors, refused = 0;
    for (int i = 0; files && !errors && i < s.nobstacles; i++)
        refused += check_file(p, diag, s.obstacles[i].terrain ? "ground" : "obstacle", s.obstacles[i].file,
                                   s.obstacles[i].line, s.obstacles[i].col);
    for (int i = 0; files && !errors && i < s.nplants; i++)
        if (s.plants[i].file)
            refused += check_file(p, diag, "plant", s.plants[i].file, s.plants[i].line, s.plants[i].col);
    errors += refused;
    scene_spec_free(&s);
    return errors && errors == set_errors ? -errors : errors;
}

/* `sylva check`: an ecosystem's terrain, a weber or curvetree block's envelope, a
 * curvetree's trunk file and any texture image that cannot be read are errors at their line (the runs fail on them). */
static int check_inputs(const SylProgram *p, FILE *diag) {
    static const char *const named[] = {"terrain", "envelope", "trunk"};
    int n = 0, errors = 0;
    const SylDirective *d = syl_program_directives(p, &n);
    for (int i = 0; i < n; i++)
        for (int k = 0; k < (int)(sizeof named / sizeof *named); k++)
            if (!d[i].file && !strcmp(d[i].name, named[k]) && d[i].nargs && d[i].args[0].kind == SYL_DARG_STRING)
                errors += lang_check_file(p, diag, named[k], d[i].args[0].text, d[i].args[0].line,
                                         d[i].args[0].col);
    return errors + lang_textures_check(p, diag); /* any kind's texture images */
}

/* syl_compile's hook (sylva.h): the block's own check, from its kind's row (kinds/kinds.c),
 * then the scene's. The scene is checked with the file's first model only, so that checking
 * every model of a file (`sylva check`) reports it once. */
int syl_validate(void *user, const SylProgram *p, FILE *diag) {
    bool files = user && *(const int *)user;
    const KindOps *ops = kinds_ops(p->kind);
    int errors = ops->validate ? ops->validate(p, diag) : 0;
    int missing = !errors && files ? check_inputs(p, diag) : 0;
    if (!errors && p->has_scene && p->first_model) errors += scene_spec_check(p, diag, files);
    if (missing) errors = (errors < 0 ? -errors : errors) + missing;
    /* negative: every error was of --set, a bad command line */
    return errors;
}

