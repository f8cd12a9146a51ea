/* sylva view: a request made into what the CLI would write — the .glb of `sylva mesh`, the
 * messages of `sylva check`, the figures of `--stats`, the CSV of `sylva skeleton`, the
 * picture of `sylva render` — by the same library calls, in memory. */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "cli/view.h"
#include "lang/kinds.h"
#include "sylva/describe.h"
#include "sylva/impostor.h"
#include "sylva/lod.h"
#include "sylva/stream.h"
#include "sylva/wind.h"
#include "util/json.h"

/* One query argument of the page into rq; false with the reason in err. */
bool view_request_arg(ViewRequest *rq, const char *key, const char *value, char *err, size_t n) {
    char *end = NULL;
    if (!value) value = "";
    errno = 0;
    if (!strcmp(key, "model")) {
        if (strlen(value) >= sizeof rq->model) return snprintf(err, n, "model name too long"), false;
        snprintf(rq->model, sizeof rq->model, "%s", value);
    } else if (!strcmp(key, "seed")) {
        if (!*value) return true;
        unsigned long long s = strtoull(value, &end, 10);
        if (*end || errno || *value == '-') return snprintf(err, n, "seed: a whole number from 0"), false;
        rq->use_seed = true, rq->seed = s;
    } else if (!strcmp(key, "n") || !strcmp(key, "lod")) {
        if (!*value) return true;
        long s = strtol(value, &end, 10);
        long max = !strcmp(key, "n") ? 1000000 : SYL_LOD_MAX;
        if (*end || errno || s < 0 || s > max) return snprintf(err, n, "%s: a whole number from 0 to %ld", key, max), false;
        if (!strcmp(key, "n")) rq->steps = (int)s;
        else rq->lod = (int)s;
    } else if (!strcmp(key, "leaves")) {
        if (!*value) return true;
        int k = 0;
        while (k < SYL_LEAVES_MODES && strcmp(syl_leaves_names[k], value)) k++;
        if (k == SYL_LEAVES_MODES) return snprintf(err, n, "leaves: unknown mode '%s'", value), false;
        rq->leaves = k;
    } else if (!strcmp(key, "preview")) {
        if (strcmp(value, "") && strcmp(value, "0") && strcmp(value, "1")) return snprintf(err, n, "preview: 0 or 1"), false;
        rq->preview = !strcmp(value, "1");
    } else if (!strcmp(key, "impostor")) {
        if (strcmp(value, "") && strcmp(value, "0") && strcmp(value, "1")) return snprintf(err, n, "impostor: 0 or 1"), false;
        rq->impostor = !strcmp(value, "1");
    } else if (!strcmp(key, "wind")) {
        if (!*value) return true;
        double w = strtod(value, &end);
        if (*end || !(w >= 0 && w <= 100)) return snprintf(err, n, "wind: a speed from 0 to 100 m/s"), false;
        rq->wind = (float)w;
    } else if (!strcmp(key, "size")) {
        int w, h;
        char extra;
        if (sscanf(value, "%dx%d%c", &w, &h, &extra) != 2 || w < 16 || h < 16 || w > 4096 || h > 4096)
            return snprintf(err, n, "size: WxH, 16 to 4096 pixels each way"), false;
        rq->width = w, rq->height = h;
    } else if (!strcmp(key, "set")) {
        const char *eq = strchr(value, '=');
        if (!eq || eq == value || (size_t)(eq - value) >= sizeof rq->names[0])
            return snprintf(err, n, "set: name=value"), false;
        if (rq->nsets >= MAX_SETS) return snprintf(err, n, "set: at most %d", MAX_SETS), false;
        double x = strtod(eq + 1, &end);
        if (end == eq + 1 || *end || !isfinite(x)) return snprintf(err, n, "set: '%s' is not a number", eq + 1), false;
        char *name = rq->names[rq->nsets];
        memcpy(name, value, (size_t)(eq - value));
        name[eq - value] = 0;
        rq->sets[rq->nsets++] = (SylOverride){.name = name, .value = x};
    }
    /* other names (the token, a cache breaker) are not the model's */
    return true;
}

void view_request_init(ViewRequest *rq) {
    memset(rq, 0, sizeof *rq);
    rq->steps = -1, rq->lod = -1, rq->leaves = -1;
}

/* Everything one build makes, freed by made_free. */
typedef struct Made {
    SylPlant pl;
    SylMeshOptions mo;
    SylLodChain lods;
    SylImpostor imp;    /* its billboards: the chain's last level (sylva mesh --billboards 3) */
    SylWind wind;
    SylInstances *sets;
    int nsets;
    size_t instances;
    int lod;
    double compile_s, lod_s, write_s;
    SylBudget *budget;
    SylProgram *eco;    /* an ecosystem block: view_eco.c builds it */
    bool preview;       /* a lighter picture first (view_preview.c) */
    bool lines;         /* a preview of its segments only: no mesh */
} Made;

static void made_free(Made *m) {
    syl_instances_free(m->sets, m->nsets);
    syl_lod_free(&m->lods);
    syl_impostor_free(&m->imp);
    syl_wind_free(&m->wind);
    syl_plant_free(&m->pl);
    syl_budget_free(m->budget);
    memset(m, 0, sizeof *m);
}

/* A build stops (the library's SylCancel, asked between its passes) when the files changed
 * under it — the pages are told and ask again — or, a full build, when its page has moved on
 * (it asked for a newer value). */
typedef struct BuildStop {
    View *v;
    const ViewRequest *rq;
    unsigned gen; /* the files' generation it builds */
} BuildStop;

static unsigned current_gen(View *v);

/* Stop when the files changed, the server is stopping (Ctrl-C does not wait for a long
 * derivation), or, for a full build, its tab asked for something newer. */
static int build_stop(void *user) {
    const BuildStop *b = user;
    pthread_mutex_lock(&b->v->gen_lock);
    bool gone = b->v->stopping || b->v->gen != b->gen;
    pthread_mutex_unlock(&b->v->gen_lock);
    return gone || (!b->rq->preview && view_tab_moved_on(b->v, b->rq));
}

/* Compile (with every warning of `sylva check`) and build as `sylva mesh` does; stopped with
 * VIEW_SUPERSEDED when cancel says so (NULL: never). */
static int make(View *v, const ViewRequest *rq, const SylCancel *cancel, FILE *diag, Made *m) {
    memset(m, 0, sizeof *m);
    int files = 1; /* syl_validate reads the scene's files, as `sylva check` does */
    SylCompileOptions opt = {.model = rq->model[0] ? rq->model : NULL, .overrides = rq->sets,
                             .noverrides = rq->nsets, .diag = diag, .lint = 1,
                             .validate = syl_validate, .validate_user = &files};
    double t0 = cli_now();
    int status;
    SylProgram *p = syl_compile(v->path, rq->text, rq->text_len, &opt, &status);
    m->compile_s = cli_now() - t0;
    if (!p) return status;
    SylModelKind kind = syl_program_kind(p);
    /* What is not a plant is made by a command of its own: the view runs it as `sylva
     * ecosystem` does (the one such kind, lang/kinds.def), its years once, for the full build. */
    if (lang_kind_is(kind, KF_NOT_A_PLANT) && rq->preview) {
        fprintf(diag, "sylva: note: an ecosystem has no preview\n");
        syl_program_free(p);
        return SYL_EUSAGE;
    }
    if (lang_kind_is(kind, KF_NOT_A_PLANT)) return m->eco = p, SYL_OK;
    double lod = syl_program_setting(p, "lod");
    m->lod = rq->lod >= 0 ? rq->lod : lod > 0 && lod <= SYL_LOD_MAX ? (int)lod : 0;
    if (rq->wind > 0) m->lod = rq->lod > 0 ? rq->lod : 0; /* as sylva mesh: the setting, without wind */
    if (rq->impostor && !m->lod) m->lod = 1; /* LOD0 and the billboards, as sylva mesh --billboards */
    m->budget = syl_budget_new(v->max_memory);
    m->mo = (SylMeshOptions){.diag = diag, .threads = v->threads, .budget = m->budget, .one_sided = 1,
                             .vertex_nodes = rq->wind > 0, .cancel = cancel};
    if (rq->leaves >= 0) m->mo.leaves = rq->leaves;
    if (rq->preview) view_preview_mesh_options(&m->mo), m->lod = 0, m->preview = true;
    int nscene = 0;
    bool scene = lang_kind_is(kind, KF_UNNAMED) || (!rq->model[0] && syl_program_scene(p, &nscene));
    SylPlantOptions po = {.use_steps = rq->steps >= 0, .steps = rq->steps, .use_seed = rq->use_seed,
                          .seed = rq->seed, .threads = v->threads, .max_modules = v->max_modules,
                          .max_memory = v->max_memory, .budget = m->budget, .until = SYL_PLANT_MESH,
                          .drop_string = 1, .scene = !rq->model[0], .mesh = &m->mo, .diag = diag};
    /* A plant (not a scene, whose objects the build takes apart) stops after its skeleton, so
     * that a superseded build stops before the mesh and a big preview is only its segments;
     * syl_plant_build meshes the same skeleton with the same options. */
    if (!scene) po.until = SYL_PLANT_SKELETON;
    status = syl_plant_build(p, &po, &m->pl);
    syl_program_free(p);
    if (status == SYL_ECANCELED) return VIEW_SUPERSEDED;
    if (status) return status;
    if (!scene && syl_cancelled(cancel)) return VIEW_SUPERSEDED;
    if (!scene && rq->preview && view_preview_as_lines(m->pl.skeleton)) return m->lines = true, SYL_OK;
    if (!scene) {
        double tm = cli_now();
        status = syl_mesh_build(m->pl.skeleton, &m->mo, &m->pl.mesh);
        m->pl.mesh_s = cli_now() - tm;
        if (status == SYL_ECANCELED) return VIEW_SUPERSEDED;
        if (status) return status;
        if (syl_cancelled(cancel)) return VIEW_SUPERSEDED;
    }
    double t1 = cli_now();
    if (rq->preview) { /* no levels, no wind, no reordering for the vertex cache */
        if (m->mo.leaves == SYL_LEAVES_INSTANCED || m->mo.leaves == SYL_LEAVES_INSTANCED_CARDS) {
            status = syl_instances_build(m->pl.skeleton, &m->mo, &m->sets, &m->nsets);
            for (int i = 0; i < m->nsets; i++) m->instances += m->sets[i].count;
        }
        m->lod_s = cli_now() - t1;
        return status;
    }
    if (m->lod > 0) { /* with the impostor, its billboards are the last of the levels */
        status = syl_lod_build(m->pl.skeleton, &m->mo, m->pl.mesh, m->lod - rq->impostor, &m->lods);
        if (status && status != SYL_ECANCELED) fprintf(diag, "sylva: error: cannot build the levels of detail (out of memory)\n");
        SylImpostorOptions io = {.grid = -1, .billboards = 3, .threads = v->threads, .diag = diag, .budget = m->budget};
        if (!status && rq->impostor) status = syl_impostor_add_level(&m->lods, m->pl.skeleton, &m->mo, &io, &m->imp);
    } else {
        status = syl_mesh_optimize(m->pl.mesh);
    }
    if (!status && rq->wind > 0) {
        if (!m->pl.mesh->node) {
            fprintf(diag, "sylva: error: --wind cannot skin this mesh: part of it is not the plant's\n");
            return SYL_EUSAGE;
        }
        const SylSkeleton *sk = m->pl.skeleton;
        SylWindOptions wo = {.speed = rq->wind, .dir = {1, 0}};
        float *radius = malloc((sk->nnodes + 1) * sizeof *radius);
        status = radius ? syl_mesh_radii(sk, &m->mo, radius) : SYL_ELIMIT;
        if (!status) status = syl_wind_build(sk, radius, &wo, &m->wind);
        free(radius);
        if (status) fprintf(diag, "sylva: error: cannot build the wind's joints\n");
    }
    bool instanced = m->mo.leaves == SYL_LEAVES_INSTANCED || m->mo.leaves == SYL_LEAVES_INSTANCED_CARDS;
    if (!status && instanced) {
        status = syl_instances_build(m->pl.skeleton, &m->mo, &m->sets, &m->nsets);
        for (int i = 0; i < m->nsets; i++) m->instances += m->sets[i].count;
        if (m->lod > 0) m->lods.level[0].sets = m->sets, m->lods.level[0].nsets = m->nsets;
    }
    m->lod_s = cli_now() - t1;
    return status;
}

/* The .glb as `sylva mesh` writes it, into out (its textures from tc, the same bytes). */
static int write_glb(Made *m, SylTextureCache *tc, FILE *out, FILE *diag) {
    bool wind = m->wind.njoints > 0;
    return m->lod > 0 ? syl_wind_write_glb_lods_cached(&m->lods, m->pl.skeleton, wind ? &m->wind : NULL, tc, out, cli_text_sink(diag))
           : wind     ? syl_wind_write_glb_cached(m->pl.mesh, m->sets, m->nsets, m->pl.skeleton, &m->wind, tc, out, cli_text_sink(diag))
                      : syl_mesh_write_glb_instanced_cached(m->pl.mesh, m->sets, m->nsets, tc, out, cli_text_sink(diag));
}

void view_caps_json(FILE *f, SylModelKind k) {
    fputs("\"caps\":{", f);
    for (int i = 0; syl_model_cap_name(i); i++)
        fprintf(f, "%s\"%s\":%s", i ? "," : "", syl_model_cap_name(i), syl_model_kind_caps(k) >> i & 1 ? "true" : "false");
    fputc('}', f);
}

/* What `sylva mesh --stats` prints, as JSON, with the kind's capabilities. */
static char *stats_json(const Made *m) {
    char *s = NULL;
    size_t n = 0;
    FILE *f = open_memstream(&s, &n);
    if (!f) return NULL;
    const SylSkeleton *sk = m->pl.skeleton;
    static const SylMesh none = {0};
    const SylMesh *me = m->pl.mesh ? m->pl.mesh : &none; /* a preview's segments: no mesh */
    float lo[3], hi[3];
    syl_skeleton_bounds(sk, lo, hi);
    fprintf(f, "{\"kind\":\"%s\",", syl_model_kind_name(m->pl.kind));
    view_caps_json(f, m->pl.kind);
    fprintf(f, ",\"modules\":%zu,\"nodes\":%zu,\"organs\":%zu,\"polygons\":%zu,"
               "\"vertices\":%zu,\"triangles\":%zu,\"material_groups\":%d,\"leaf_instances\":%zu,",
            m->pl.modules, sk->nnodes, sk->norgans, sk->npolys, me->nverts,
            me->nidx / 3, me->ngroups, m->instances);
    fprintf(f, "\"preview\":\"%s\",", m->lines ? "lines" : m->preview ? "mesh" : "");
    fprintf(f, "\"lod_levels\":%d,\"lod_triangles\":[", m->lods.n);
    for (int k = 0; k < m->lods.n; k++) fprintf(f, "%s%zu", k ? "," : "", m->lods.level[k].mesh->nidx / 3);
    fprintf(f, "],\"bounds\":[%g,%g,%g,%g,%g,%g],", (double)lo[0], (double)lo[1], (double)lo[2], (double)hi[0],
            (double)hi[1], (double)hi[2]);
    fprintf(f, "\"compile_time\":%.6f,\"derive_time\":%.6f,\"derive_cpu_time\":%.6f,\"turtle_time\":%.6f,"
               "\"mesh_time\":%.6f,\"lod_time\":%.6f,\"write_time\":%.6f,\"memory_mb\":%.2f,\"peak_memory_mb\":%.2f}",
            m->compile_s, m->pl.derive_s, m->pl.derive_cpu_s, m->pl.turtle_s, m->pl.mesh_s, m->lod_s, m->write_s,
            (double)syl_budget_used(m->budget) / 1048576.0, cli_peak_mb());
    fclose(f);
    return s;
}

/* A scene's obstacles (the OBJ meshes a grow scene names), one node each: the page's targets
 * for placing a plant on them. */
typedef struct Obstacles {
    SylMesh *part[64];
    int n;
} Obstacles;

static int write_obstacles_file(void *ctx, const char *path, FILE *diag) {
    const Obstacles *o = ctx;
    return syl_mesh_write_glb_parts(o->part, o->n, "obstacles", path, cli_text_sink(diag));
}

static int write_obstacles(const Made *m, ViewBuild *slot, FILE *diag) {
    const SylSkeleton *sk = m->pl.skeleton;
    Obstacles o = {.n = 0};
    for (int j = 0; j < m->pl.nparts; j++)
        for (int i = 0; i < sk->nparts && o.n < 64; i++)
            if (sk->parts[i].obstacle > 0 && !strcmp(sk->parts[i].name, m->pl.parts[j]->name)) o.part[o.n++] = m->pl.parts[j];
    if (!o.n) return SYL_OK;
    FILE *out = open_memstream(&slot->obstacles, &slot->obstacles_len);
    if (!out) return SYL_ELIMIT;
    int st = view_write_via_file(write_obstacles_file, &o, "obstacles.glb", out, diag);
    fclose(out);
    return st;
}

static void entry_free(ViewBuild *b) {
    free(b->diag);
    free(b->obstacles);
    free(b->glb);
    free(b->csv);
    free(b->lines);
    free(b->stats);
    free(b->metrics);
    memset(b, 0, sizeof *b);
}

void view_cache_free(View *v) {
    for (int i = 0; i < VIEW_CACHE; i++) entry_free(&v->cache[i]);
    view_eco_free(v->eco);
    v->eco = NULL;
    view_keep_free(v);
    syl_texture_cache_free(v->textures);
    v->textures = NULL;
}

static unsigned current_gen(View *v) {
    pthread_mutex_lock(&v->gen_lock);
    unsigned gen = v->gen;
    pthread_mutex_unlock(&v->gen_lock);
    return gen;
}

ViewBuild *view_build(View *v, const ViewRequest *rq, const char *key) {
    unsigned gen = current_gen(v);
    ViewBuild *slot = &v->cache[0];
    for (int i = 0; i < VIEW_CACHE; i++) {
        ViewBuild *b = &v->cache[i];
        if (b->id && b->gen == gen && !strcmp(b->key, key)) {
            b->used = cli_now();
            return b;
        }
        if (!b->id || b->used < slot->used) slot = b;
    }
    entry_free(slot);
    slot->id = ++v->next_id;
    slot->gen = gen;
    slot->used = cli_now();
    snprintf(slot->key, sizeof slot->key, "%s", key);
    size_t dlen = 0;
    FILE *diag = open_memstream(&slot->diag, &dlen);
    if (!diag) {
        slot->status = SYL_ELIMIT;
        return slot;
    }
    Made m;
    pthread_mutex_lock(&v->gen_lock);
    v->builds++;
    pthread_mutex_unlock(&v->gen_lock);
    BuildStop stop = {.v = v, .rq = rq, .gen = gen};
    SylCancel cancel = {.stop = build_stop, .user = &stop};
    int status = make(v, rq, &cancel, diag, &m);
    if (!status && m.eco) {
        status = view_eco_build(v, rq, m.eco, gen, diag, slot);
        m.eco = NULL;
    } else if (!status && m.lines) { /* a preview of a big plant: its segments */
        double t = cli_now();
        status = view_preview_lines(m.pl.skeleton, true, &slot->lines, &slot->lines_len);
        m.write_s = cli_now() - t;
        if (!status) slot->stats = stats_json(&m);
    } else if (!status && syl_cancelled(&cancel)) {
        status = VIEW_SUPERSEDED;
    } else if (!status) {
        double t = cli_now();
        FILE *out = view_bytes_open(&slot->glb, &slot->glb_len);
        if (!v->textures) v->textures = syl_texture_cache_new(); /* NULL: made at each write */
        status = out ? write_glb(&m, v->textures, out, diag) : SYL_ELIMIT;
        if (out) fclose(out);
        m.write_s = cli_now() - t;
        if (!status) status = write_obstacles(&m, slot, diag);
        if (!status) slot->stats = stats_json(&m);
        /* its metrics, when the page asks (of what is exported: not of a preview) */
        if (!status && !rq->preview) view_keep(v, slot->id, &m.pl, &m.budget);
    }
    made_free(&m);
    fclose(diag);
    if (status == SYL_ECANCELED) status = VIEW_SUPERSEDED; /* stopped inside a level's or a leaf's mesh */
    slot->status = status;
    if (status == VIEW_SUPERSEDED) { /* never found again: built anew when asked */
        slot->key[0] = 0;
        pthread_mutex_lock(&v->gen_lock);
        v->stopped++;
        pthread_mutex_unlock(&v->gen_lock);
    }
    if (status) { /* keep the messages only */
        free(slot->glb), slot->glb = NULL, slot->glb_len = 0;
        free(slot->csv), slot->csv = NULL, slot->csv_len = 0;
        free(slot->lines), slot->lines = NULL, slot->lines_len = 0;
        free(slot->obstacles), slot->obstacles = NULL, slot->obstacles_len = 0;
    }
    return slot;
}

/* A picture as `sylva render` draws it (its default camera and light), as PNG. */
static int write_png(Made *m, const ViewRequest *rq, FILE *out, FILE *diag, int threads) {
    int w = rq->width ? rq->width : 1024, h = rq->height ? rq->height : 1024;
    uint8_t *rgb = malloc((size_t)w * (size_t)h * 3);
    if (!rgb) return SYL_ELIMIT;
    SylRenderOptions ro = {.width = w, .height = h, .threads = threads, .diag = diag, .budget = m->budget};
    int status = syl_render_draw_mesh(m->pl.mesh, &ro, rgb);
    if (!status) status = syl_png_write_stream(out, rgb, w, h, cli_text_sink(diag));
    free(rgb);
    return status;
}

typedef struct Bytes {
    char **buf, *data;
    size_t *len, n, cap;
} Bytes;

static ssize_t bytes_write(void *c, const char *p, size_t n) {
    Bytes *b = c;
    if (b->n + n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 1 << 16;
        while (cap < b->n + n + 1) cap *= 2;
        char *d = realloc(b->data, cap);
        if (!d) return -1;
        b->data = d, b->cap = cap;
    }
    memcpy(b->data + b->n, p, n);
    b->n += n;
    return (ssize_t)n;
}

static int bytes_close(void *c) {
    Bytes *b = c;
    if (!b->data) b->data = malloc(1);
    if (b->data) b->data[b->n] = 0;
    *b->buf = b->data, *b->len = b->data ? b->n : 0;
    free(b);
    return 0;
}

FILE *view_bytes_open(char **buf, size_t *len) {
    Bytes *b = calloc(1, sizeof *b);
    if (!b) return NULL;
    b->buf = buf, b->len = len;
    FILE *f = fopencookie(b, "w", (cookie_io_functions_t){.write = bytes_write, .close = bytes_close});
    if (!f) free(b);
    else setvbuf(f, NULL, _IOFBF, 1 << 16);
    return f;
}

int view_write_via_file(ViewPathWriter write, void *ctx, const char *name, FILE *out, FILE *diag) {
    char dir[] = "/tmp/sylva-view-XXXXXX";
    if (!mkdtemp(dir)) {
        fprintf(diag, "sylva: error: cannot make a temporary directory: %s\n", strerror(errno));
        return SYL_EIO;
    }
    char path[sizeof dir + 256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    int status = write(ctx, path, diag);
    size_t len = 0;
    char *text = status ? NULL : syl_read_file(path, &len);
    if (!status && !text) status = SYL_EIO;
    if (text) fwrite(text, 1, len, out);
    free(text);
    /* the file and what its writer put beside it (an .obj's .mtl and texture PNGs) */
    DIR *d = opendir(dir);
    for (struct dirent *e; d && (e = readdir(d));) {
        if (e->d_name[0] == '.') continue;
        char p[sizeof dir + 512];
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        unlink(p);
    }
    if (d) closedir(d);
    rmdir(dir);
    return status;
}

static int write_obj_file(void *ctx, const char *path, FILE *diag) {
    return syl_mesh_write_obj(((Made *)ctx)->pl.mesh, path, cli_text_sink(diag));
}

/* The skeleton's segments as a segments preview has them, not joined (tests/view/join.test.mjs
 * joins them as the page did and compares). */
static int write_segments(const Made *m, FILE *of) {
    char *b;
    size_t n;
    int status = view_preview_lines(m->pl.skeleton, false, &b, &n);
    if (!status) fwrite(b, 1, n, of), free(b);
    return status;
}

int view_export(View *v, const ViewRequest *rq, const char *format, char **out, size_t *len, char **diag) {
    size_t dlen = 0;
    *out = NULL, *len = 0, *diag = NULL;
    FILE *df = open_memstream(diag, &dlen);
    FILE *of = open_memstream(out, len);
    if (!df || !of) {
        if (df) fclose(df);
        if (of) fclose(of);
        return SYL_ELIMIT;
    }
    Made m;
    int status = make(v, rq, NULL, df, &m); /* asked for: never stopped */
    if (!status && m.eco) { /* an ecosystem: its forest's .glb */
        ViewBuild b = {0};
        if (!strcmp(format, "glb")) status = view_eco_build(v, rq, m.eco, current_gen(v), df, &b);
        else syl_program_free(m.eco), status = SYL_EUSAGE;
        if (status == SYL_EUSAGE) fprintf(df, "sylva: error: an ecosystem exports its forest as .glb only\n");
        if (!status) fwrite(b.glb, 1, b.glb_len, of);
        entry_free(&b);
        m.eco = NULL;
    } else if (!status) {
        if (!strcmp(format, "glb")) status = write_glb(&m, NULL, of, df); /* the export: sylva mesh's own path */
        else if (!strcmp(format, "csv")) status = syl_skeleton_write_csv(m.pl.skeleton, of);
        else if (!strcmp(format, "segments")) status = write_segments(&m, of);
        else if (!strcmp(format, "png")) status = write_png(&m, rq, of, df, v->threads);
        else if (!strcmp(format, "obj")) status = view_write_via_file(write_obj_file, &m, "plant.obj", of, df);
        else status = SYL_EUSAGE;
    }
    made_free(&m);
    fclose(df);
    fclose(of);
    return status;
}

char *view_models_json(View *v) {
    size_t len = 0;
    char *text = syl_read_file(v->path, &len);
    const char *names[256];
    char buf[8192];
    int n = text ? syl_model_list(v->path, text, len, names, 256, buf, sizeof buf) : 0;
    char *s = NULL;
    size_t sl = 0;
    FILE *f = open_memstream(&s, &sl);
    if (!f) return free(text), NULL;
    fputs("{\"file\":", f);
    json_string_file(f, v->path);
    pthread_mutex_lock(&v->gen_lock);
    fprintf(f, ",\"gen\":%u,\"builds\":%u,\"stopped\":%u,\"models\":[", v->gen, v->builds, v->stopped);
    pthread_mutex_unlock(&v->gen_lock);
    for (int i = 0; i < n; i++) {
        fputs(i ? "," : "", f);
        json_string_file(f, names[i]);
    }
    fputs("]}", f);
    fclose(f);
    free(text);
    return s;
}

char *view_describe_json(View *v, const ViewRequest *rq, char **diag) {
    size_t dlen = 0, len = 0;
    char *s = NULL;
    *diag = NULL;
    FILE *df = open_memstream(diag, &dlen);
    if (!df) return NULL;
    int files = 1, status;
    SylCompileOptions opt = {.model = rq->model[0] ? rq->model : NULL, .overrides = rq->sets,
                             .noverrides = rq->nsets, .diag = df, .validate = syl_validate,
                             .validate_user = &files};
    SylProgram *p = syl_compile(v->path, rq->text, rq->text_len, &opt, &status);
    FILE *f = p ? open_memstream(&s, &len) : NULL;
    if (f) {
        if (syl_describe_json(p, f)) {
            fclose(f);
            free(s);
            s = NULL;
        } else {
            fclose(f);
        }
    }
    syl_program_free(p);
    fclose(df);
    return s;
}
