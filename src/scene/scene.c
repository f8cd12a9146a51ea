/* syl_grow_build_scene: every plant of a file's scene in one environment. Grow plants become
 * trees of one forest. L-system plants beside trees derive in lockstep with them, a step a
 * year (lsys.c), shading and crowding them and shaded by them; in a scene of
 * L-systems only, each is derived and drawn in turn and stands, for the plants after it, as
 * static shadow casters and occupants. The skeleton holds every plant in the order the scene
 * lists them. */
#include <errno.h>
#include <libgen.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kinds/kinds.h"
#include "lang/program.h"
#include "mesh/store.h"
#include "scene/open.h"
#include "util/arena.h"
#include "util/namemap.h"
#include "sot/forest.h"
#include "sot/forest_internal.h"
#include "scene/lsys.h"
#include "scene/spec.h"
#include "scene/surface.h"
#include "sot/output.h"
#include "sylva/grow.h"
#include "sylva/trees.h"

enum { OBSTACLE_MATERIAL = 250 };

typedef struct Placed {
    SylSkeleton *lsys; /* an L-system, weber or strands plant, drawn and moved into place */
    int tree;          /* a grow plant: its tree, or -1 */
    int lockstep;      /* an L-system plant beside trees: its number in SceneLsys, or -1 */
} Placed;

/* path relative to the scene file's directory (free it). */
/* Each distinct model of a scene is compiled once, and a grow model's directives read once,
 * however many plants it has: compiling a model reads the whole file. */
typedef struct SceneModel {
    SylProgram *q;
    GrowParams P;  /* a grow model's */
} SceneModel;

typedef struct SceneModels {
    Arena keys;
    NameMap index; /* "m:NAME" of this file, "f:FILE[:SceneModel]" of another -> models[i] */
    SceneModel *v;
    int n, cap;
} SceneModels;

static void models_free(SceneModels *m) {
    for (int i = 0; i < m->n; i++) syl_program_free(m->v[i].q);
    free(m->v);
    arena_free(&m->keys);
}

/* Compile a plant's model: one of this file, or "file.syl[:SceneModel]" of another. */
static SylProgram *plant_program(const SylProgram *p, const ScenePlant *pl, FILE *diag, int *status) {
    /* the --set values reach every plant; a name one lacks is another's (Birch.lambda) */
    SylCompileOptions copt = {.diag = diag, .overrides = p->overrides, .noverrides = p->noverrides, .sibling = 1};
    if (pl->model) {
        /* the file and its scene were checked when p was compiled: no hook */
        size_t len = 0;
        const char *text = syl_program_source(p, &len);
        copt.model = pl->model;
        return syl_compile(syl_program_path(p), text, len, &copt, status);
    }
    return scene_plant_file(p, pl->file, pl->line, pl->col, diag, status);
}

/* How an L-system plant of the scene derives: its seed, and its steps (the plant line's
 * years, else the model's `derive`). */
static SylDeriveOptions lsys_options(const SylProgram *q, const SylGrowOptions *opt, const ScenePlant *pl, int index) {
    SylDeriveOptions d = {.steps = pl->years_set ? pl->years : syl_program_steps(q), .threads = opt->threads,
                          .diag = opt->diag, .max_modules = opt->max_modules, .max_work = opt->max_work,
                          .budget = opt->budget};
    if (pl->seed_set) d.use_seed = 1, d.seed = pl->seed;
    else if (opt->use_seed) d.use_seed = 1, d.seed = opt->seed + (uint64_t)index;
    return d;
}

/* A scene without trees: an L-system plant's ?E modules read the scene's obstacles, the
 * ground and the plants drawn before it (static casters and occupants), and the plant's own
 * skeleton. */
static int draw_lsystem(const SylProgram *q, const SylGrowOptions *opt, const ScenePlant *pl, int index,
                        const SceneSpec *S, Forest *f, SylSkeleton **out) {
    const Env *env = &f->env;
    SylDeriveOptions d = lsys_options(q, opt, pl, index);
    OpenEnvParams P = {.voxel = (float)syl_program_setting(q, "step"), .ground = S->ground_set ? S->ground : pl->at[1],
                       .sun = {0, 1, 0}, .at = {pl->at[0], pl->at[1], pl->at[2]},
                       .obstacles = obstacles_any(&env->obstacles) ? &env->obstacles : NULL,
                       .statics = env->statics, .nstatic = env->nstatic, .diag = opt->diag};
    if (S->sun_set) memcpy(P.sun, S->sun, sizeof P.sun);
    OpenEnv oe;
    open_env_init(&oe, &P);
    d.queries = &open_env_ops;
    d.queries_user = &oe;
    SylString *s = NULL;
    int st = syl_derive(q, &d, &s);
    open_env_free(&oe);
    if (!st) st = lsys_draw(q, s, &d, pl->at, out);
    syl_string_free(s);
    if (st) f->reported = true; /* the deriver and the turtle say why */
    return st;
}

/* A plant built from its parameters (its kind's build, kinds/kinds.c: weber, strands): built
 * once and moved to where it stands. Its
 * seed is the plant line's, else the command's plus its place in the list, else the block's
 * own plus that place, so that a row of one species is a row of different trees. */
static int draw_tree(const SylProgram *q, const SylGrowOptions *opt, const ScenePlant *pl, int index, Forest *f,
                     SylSkeleton **out) {
    SylTreeOptions t = {.use_seed = pl->seed_set || opt->use_seed,
                        .seed = pl->seed_set ? pl->seed : opt->seed + (uint64_t)index,
                        .seed_offset = pl->seed_set || opt->use_seed ? 0 : (uint64_t)index,
                        .threads = opt->threads, .max_memory = opt->max_memory, .budget = opt->budget,
                        .diag = opt->diag};
    int st = kinds_ops(syl_program_kind(q))->build(q, &t, out);
    if (st) {
        f->reported = true; /* the generator says why */
        return st;
    }
    SylSkeleton *sk = *out;
    for (size_t k = 0; k < sk->nnodes; k++)
        for (int c = 0; c < 3; c++) sk->nodes[k].pos[c] += pl->at[c];
    for (size_t k = 0; k < sk->norgans; k++)
        for (int c = 0; c < 3; c++) sk->organs[k].pos[c] += pl->at[c];
    for (size_t k = 0; k < sk->nverts; k++)
        for (int c = 0; c < 3; c++) sk->poly_verts[k][c] += pl->at[c];
    return SYL_OK;
}

/* Append skeleton b to a, whose axes are below `axis`: indices and axes renumbered, b's
 * material m drawn with a's map[m] (surface.h). */
static int append_skeleton(SylSkeleton *a, const SylSkeleton *b, int32_t axis, const uint8_t map[256]) {
    size_t first = a->nnodes;
    for (size_t i = 0; i < b->nnodes; i++) {
        SylNode n = b->nodes[i];
        if (n.parent >= 0) n.parent += (int32_t)first;
        n.axis += axis;
        n.material = map[n.material];
        if (syl_skeleton_add_node(a, &n) < 0) return SYL_ELIMIT;
    }
    for (size_t i = 0; i < b->norgans; i++) {
        SylOrgan o = b->organs[i];
        if (o.node >= 0) o.node += (int32_t)first;
        o.material = map[o.material];
        if (syl_skeleton_add_organ(a, &o) < 0) return SYL_ELIMIT;
    }
    for (size_t i = 0; i < b->npolys; i++) {
        const SylPolygon *p = &b->polys[i];
        if (syl_skeleton_add_polygon(a, (const float(*)[3])b->poly_verts[p->first], p->count,
                                     p->node >= 0 ? p->node + (int32_t)first : -1, map[p->material], p->module) < 0)
            return SYL_ELIMIT;
    }
    return SYL_OK;
}

/* The obstacles' triangles as a mesh, one flat-shaded material; each vertex's node is the
 * number of the obstacle it belongs to (first_tri: each one's first triangle, nobst of them). */
static SylMesh *obstacle_mesh(const Obstacles *o, const size_t *first_tri, int nobst) {
    SylMesh *m = calloc(1, sizeof *m);
    if (!m) return NULL;
    size_t nv = 3 * o->nt;
    m->pos = malloc((3 * nv + 4) * sizeof *m->pos);
    m->nrm = malloc(3 * nv * sizeof *m->nrm);
    m->uv = calloc(2 * nv, sizeof *m->uv);
    m->idx = malloc(nv * sizeof *m->idx);
    m->groups = malloc(sizeof *m->groups);
    m->node = malloc((nv + 1) * sizeof *m->node);
    if (!m->pos || !m->nrm || !m->uv || !m->idx || !m->groups || !m->node) {
        syl_mesh_free(m);
        return NULL;
    }
    for (size_t t = 0; t < o->nt; t++) {
        const float *p[3];
        for (int k = 0; k < 3; k++) p[k] = o->v + 3 * o->tri[3 * t + k];
        float e1[3], e2[3], n[3];
        for (int k = 0; k < 3; k++) e1[k] = p[1][k] - p[0][k], e2[k] = p[2][k] - p[0][k];
        n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int k = 0; k < 3; k++) n[k] = len > 0 ? n[k] / len : (k == 1);
        for (int v = 0; v < 3; v++) {
            size_t i = 3 * t + (size_t)v;
            memcpy(m->pos + 3 * i, p[v], 3 * sizeof(float));
            memcpy(m->nrm + 3 * i, n, 3 * sizeof(float));
            m->idx[i] = (uint32_t)i;
            int k = 0;
            while (k + 1 < nobst && first_tri[k + 1] <= t) k++;
            m->node[i] = k;
        }
    }
    memset(m->pos + 3 * nv, 0, 4 * sizeof(float));
    m->nverts = nv;
    mesh_mark_spare(m); /* pos has 4 floats past the last vertex */
    m->nidx = nv;
    m->groups[0] = (SylMeshGroup){.first = 0, .count = (uint32_t)nv, .material = OBSTACLE_MATERIAL};
    m->ngroups = 1;
    m->materials[OBSTACLE_MATERIAL] = (SylMaterial){.rgb = {0.72f, 0.70f, 0.66f}, .kind = SYL_MATERIAL_PLAIN};
    m->nmaterials = OBSTACLE_MATERIAL + 1;
    snprintf(m->name, sizeof m->name, "obstacles");
    return m;
}

static int load_obstacles(Forest *f, const SylProgram *p, const SceneSpec *S, size_t *first_tri, FILE *diag) {
    for (int i = 0; i < S->nobstacles; i++) {
        const SceneObstacle *o = &S->obstacles[i];
        first_tri[i] = f->env.obstacles.nt;
        char *path = NULL;
        int st = scene_spec_path(p, o->file, NULL, &path);
        if (st == SYL_EIO) program_say(p, diag, DIAG_ERROR, NULL, "cannot read '%s': %s", o->file, syl_file_refused);
        if (!st) st = obstacles_add_obj(&f->env.obstacles, path, o->at, o->scale, diag_sink(&(SylSink){0}, diag, program_sink(p)));
        free(path);
        if (st) {
            if (diag) syl_program_report_error(p, diag, o->line, o->col, "cannot use the obstacle \"%s\"", o->file);
            return st;
        }
    }
    return obstacles_commit(&f->env.obstacles, f->env.dev, diag_sink(&(SylSink){0}, diag, program_sink(p)));
}

static bool has_terrain(const SceneSpec *S) {
    for (int i = 0; i < S->nobstacles; i++)
        if (S->obstacles[i].terrain) return true;
    return false;
}

/* The plant's model, compiled the first time a plant names it. */
static SceneModel *plant_model(const SylProgram *p, const ScenePlant *pl, SceneModels *m, FILE *diag, int *status) {
    char *key = arena_printf(&m->keys, "%c:%s", pl->model ? 'm' : 'f', pl->model ? pl->model : pl->file);
    if (!key) {
        *status = SYL_ELIMIT;
        return NULL;
    }
    int at = namemap_get(&m->index, key, -1);
    if (at >= 0) return &m->v[at];
    if (m->n == m->cap) {
        int cap = m->cap ? 2 * m->cap : 16;
        SceneModel *v = realloc(m->v, (size_t)cap * sizeof *v);
        if (!v) {
            *status = SYL_ELIMIT;
            return NULL;
        }
        m->v = v;
        m->cap = cap;
    }
    SceneModel *md = &m->v[m->n];
    memset(md, 0, sizeof *md);
    if (!(md->q = plant_program(p, pl, diag, status))) return NULL;
    if (lang_kind_is(syl_program_kind(md->q), KF_GROWS) && grow_params_read(md->q, &md->P, diag)) {
        syl_program_free(md->q);
        *status = SYL_EMODEL;
        return NULL;
    }
    namemap_put(&m->index, key, m->n);
    return &m->v[m->n++];
}

/* Compile every plant (its place set on the terrain) before any grows: whether a tree is
 * among them decides how the L-systems derive. progs[i] belongs to m. */
static int compile_plants(const SylProgram *p, const SceneSpec *S, Forest *f, ScenePlant *plants, SceneModel **progs,
                          SceneModels *m, FILE *diag) {
    for (int i = 0; i < S->nplants; i++) {
        ScenePlant *pl = &plants[i];
        *pl = S->plants[i];
        float h;
        if (has_terrain(S) && obstacles_height(&f->env.obstacles, pl->at[0], pl->at[2], f->env.obstacles.hi[1] + 1, &h))
            pl->at[1] = h + 0.01f; /* just above, so its first metamer's ray starts clear */
        int st = SYL_OK;
        progs[i] = plant_model(p, pl, m, diag, &st);
        if (!progs[i]) {
            if (diag && st != SYL_ELIMIT) syl_program_report_error(p, diag, pl->line, pl->col, "cannot use this plant");
            else program_say(p, diag, DIAG_ERROR, NULL, "out of memory");
            return st ? st : SYL_EMODEL;
        }
        SylModelKind kind = syl_program_kind(progs[i]->q);
        if (lang_kind_is(kind, KF_UNNAMED)) {
            syl_program_report_error(p, diag, pl->line, pl->col, "a scene cannot be a plant of a scene");
            return SYL_EMODEL;
        }
        if (!lang_kind_is(kind, KF_IN_SCENE)) { /* another file's: sylva check said so of this file's */
            syl_program_report_error(p, diag, pl->line, pl->col, "the %s '%s' cannot stand in a scene",
                                     syl_model_kind_name(kind), syl_program_name(progs[i]->q));
            return SYL_EMODEL;
        }
    }
    return SYL_OK;
}

static int grow_scene(const SylProgram *p, SylGrowOptions *opt, const SceneSpec *S, Forest *f, Placed *placed,
                      ScenePlant *plants, SceneModel **progs, SceneModels *models, SceneLsys **lsys,
                      size_t *first_tri, SylSkeleton **out, SylMesh **obstacles) {
    FILE *diag = opt->diag;
    double ts = forest_now();
    int st = load_obstacles(f, p, S, first_tri, diag);
    if (!st) st = compile_plants(p, S, f, plants, progs, models, diag);
    if (st) return st;
    bool trees = false;
    float ground = S->ground, lowest = INFINITY;
    for (int i = 0; i < S->nplants; i++) {
        trees |= lang_kind_is(syl_program_kind(progs[i]->q), KF_GROWS);
        if (plants[i].at[1] < lowest) lowest = plants[i].at[1];
    }
    if (trees && !(*lsys = scene_lsys_new(f, S->nplants))) return SYL_ELIMIT;
    int nlsys = 0;
    for (int i = 0; i < S->nplants && !st; i++) {
        const ScenePlant *pl = &plants[i];
        SylProgram *q = progs[i]->q;
        placed[i].tree = placed[i].lockstep = -1;
        if (lang_kind_is(syl_program_kind(q), KF_GROWS)) {
            GrowParams P = progs[i]->P;
            if (pl->seed_set) P.seed = pl->seed;
            else if (opt->use_seed) P.seed = opt->seed + (uint64_t)i;
            else P.seed += (uint64_t)i;
            int years = opt->years >= 0 ? opt->years : pl->years_set ? pl->years : P.years;
            placed[i].tree = f->ntrees;
            if (!st) st = forest_add_tree(f, &P, pl->at, years);
        } else if (kinds_ops(syl_program_kind(q))->build) {
            /* a tree made from parameters does not grow: it shades and crowds from the start */
            st = draw_tree(q, opt, pl, i, f, &placed[i].lsys);
            opt->stats.plants++;
            const SylSkeleton *sk = placed[i].lsys;
            for (size_t k = 0; !st && k < sk->nnodes; k++) st = forest_add_static(f, sk->nodes[k].pos);
            for (size_t k = 0; !st && k < sk->norgans; k++) st = forest_add_static(f, sk->organs[k].pos);
        } else if (trees) { /* derived later, year by year with the trees */
            SylDeriveOptions d = lsys_options(q, opt, pl, i);
            placed[i].lockstep = nlsys++;
            st = scene_lsys_add(*lsys, q, &d, pl->at, S->ground_set ? S->ground : pl->at[1], d.steps);
            opt->stats.plants++;
        } else {
            st = draw_lsystem(q, opt, pl, i, S, f, &placed[i].lsys);
            opt->stats.plants++;
            const SylSkeleton *sk = placed[i].lsys;
            for (size_t k = 0; !st && k < sk->nnodes; k++) st = forest_add_static(f, sk->nodes[k].pos);
        }
    }
    if (st) return st;
    if (!S->ground_set) ground = has_terrain(S) ? f->env.obstacles.lo[1] : lowest;
    st = forest_setup(f, ground, S->sun, S->sun_set);
    double t0 = forest_now();
    opt->stats.other_s += t0 - ts;
    if (!st) st = forest_run(f, opt->progress, opt->user);
    double t1 = forest_now();
    if (!st && *lsys) st = scene_lsys_finish(*lsys);
    for (int i = 0; i < S->nplants && !st; i++)
        if (placed[i].lockstep >= 0) st = scene_lsys_draw(*lsys, placed[i].lockstep, &placed[i].lsys);
    if (st) return st;
    SylSkeleton *sk = syl_skeleton_new("scene");
    if (!sk) return SYL_ELIMIT;
    int32_t axis = 0; /* above every axis of sk: each plant's axes follow the last one's */
    SceneSurface surface = {0};
    for (int i = 0; i < S->nplants && !st; i++) {
        size_t first = sk->nnodes;
        if (syl_skeleton_add_part(sk, syl_program_name(progs[i]->q), 0) < 0) st = SYL_ELIMIT;
        SylSkeleton *grown = NULL; /* a grown tree's own skeleton, then appended as the others */
        if (!st && placed[i].tree >= 0) {
            if (!(grown = syl_skeleton_new(syl_program_name(progs[i]->q)))) st = SYL_ELIMIT;
            else st = tree_to_skeleton(&f->trees[placed[i].tree], f->years, grown, 0, &opt->stats.organs);
        }
        const SylSkeleton *own = grown ? grown : placed[i].lsys;
        if (!st && own) {
            uint8_t map[256];
            scene_surface_map(&surface, sk, own, map, syl_program_name(progs[i]->q), p, plants[i].line,
                              plants[i].col, diag);
            st = append_skeleton(sk, own, axis, map);
        }
        syl_skeleton_free(grown);
        for (size_t k = first; k < sk->nnodes; k++)
            if (sk->nodes[k].axis >= axis) axis = sk->nodes[k].axis + 1;
    }
    if (!st && obstacles && f->env.obstacles.nt) {
        *obstacles = obstacle_mesh(&f->env.obstacles, first_tri, S->nobstacles);
        if (!*obstacles) st = SYL_ELIMIT;
    }
    for (int i = 0; !st && obstacles && i < S->nobstacles; i++) { /* named after their files */
        const char *file = S->obstacles[i].file, *base = strrchr(file, '/');
        char name[64];
        snprintf(name, sizeof name, "%.*s", (int)strcspn(base ? base + 1 : file, "."), base ? base + 1 : file);
        if (syl_skeleton_add_part(sk, name[0] ? name : "obstacle", i + 1) < 0) st = SYL_ELIMIT;
    }
    if (st) {
        syl_skeleton_free(sk);
        return st;
    }
    opt->stats.other_s += forest_now() - t1;
    *out = sk;
    return SYL_OK;
}

int syl_grow_build_scene(const SylProgram *p, SylGrowOptions *opt, SylSkeleton **out, SylMesh **obstacles) {
    SylGrowOptions local = {.years = -1};
    if (!opt) opt = &local;
    *out = NULL;
    if (obstacles) *obstacles = NULL;
    memset(&opt->stats, 0, sizeof opt->stats);
    if (opt->years > SYL_GROW_MAX_YEARS) {
        program_say(p, opt->diag, DIAG_ERROR, NULL, "at most %d years, not %d", SYL_GROW_MAX_YEARS, opt->years);
        return SYL_EUSAGE;
    }
    double t0 = forest_now();
    SceneSpec S;
    int errors = scene_spec_read(p, &S, opt->diag);
    if (errors || !S.nplants) {
        if (!errors) program_say(p, opt->diag, DIAG_ERROR, NULL, "the file has no scene");
        scene_spec_free(&S);
        return errors ? SYL_EMODEL : SYL_EUSAGE;
    }
    Forest f;
    Placed *placed = calloc((size_t)S.nplants, sizeof *placed);
    ScenePlant *plants = calloc((size_t)S.nplants, sizeof *plants);
    SceneModel **progs = calloc((size_t)S.nplants, sizeof *progs);
    size_t *first_tri = calloc((size_t)S.nobstacles + 1, sizeof *first_tri);
    SceneModels models = {0};
    namemap_init(&models.index, &models.keys);
    SceneLsys *lsys = NULL;
    int st = placed && plants && progs && first_tri ? forest_init(&f, opt->threads, opt->diag, &opt->stats) : SYL_ELIMIT;
    if (!st) {
        f.sink = program_sink(p);
        if (f.sink) f.env.sink = *f.sink; /* Embree's errors too */
        forest_limits(&f, opt);
        f.shoot_derive = syl_derive_begin; /* shoots' query modules: the stand-alone environment */
        st = grow_scene(p, opt, &S, &f, placed, plants, progs, &models, &lsys, first_tri, out, obstacles);
        st = forest_said(&f, st, 0);
        scene_lsys_free(lsys);
        forest_free(&f);
    }
    for (int i = 0; placed && i < S.nplants; i++) syl_skeleton_free(placed[i].lsys);
    models_free(&models);
    free(placed);
    free(plants);
    free(progs);
    free(first_tri);
    scene_spec_free(&S);
    if (st && obstacles) {
        syl_mesh_free(*obstacles);
        *obstacles = NULL;
    }
    opt->stats.total_s = forest_now() - t0;
    return st;
}
