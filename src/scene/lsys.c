/* The L-system plants of a scene with trees: each derives one step per year of the forest,
 * in lockstep with the trees (docs/growth.md, "Scenes").
 *
 * At the start of every year (the forest's year_start hook, before light), every L-system
 * plant in the scene's order takes its step, its segment ends replace last year's as casters
 * in the forest's shadow grid, and then all of them replace the environment's static
 * occupants (space colonization, sky rays, the marker cloud). The trees then grow in light
 * that sees the plants as they are this year, and the plants' next step reads the trees as
 * they grew.
 *
 * ?E modules are answered by env/probe.h from this scene's world (not scene/open.c's): light
 * from the forest's shadow grid (the trees' metamers and every L-system's latest ends, its
 * own of this step included), crowding and sky exposure from the same points, distance from
 * the obstacles and the ground. A step that brings no
 * ?E answer (no probes, or no ?E at all) gets its ends from the turtle's skeleton. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "env/probe.h"
#include "lang/program.h"
#include "lsys/modstr.h"
#include "scene/lsys.h"
#include "sot/forest_internal.h"
#include "turtle/turtle.h"


typedef struct LsysPlant {
    SceneLsys *owner;
    const SylProgram *q; /* the scene's: plants of one model share it */
    SylDeriveOptions d; /* the deriver keeps a pointer to it: never moved */
    SylDeriver *dv;
    int steps, done;    /* steps to take in all; taken */
    float at[3];
    float ground;       /* the ground plane of ?E(2) */
    float voxel;        /* the default radius of ?E(1): the model's step */
    float (*ends)[3];   /* its casters in the forest now, scene coordinates */
    size_t nends, cap;
    bool fresh;         /* ends are those of the string as it is now */
    SylString *final;
    SylEnvFill fill;    /* what the turtle collects for the answers */
} LsysPlant;

struct SceneLsys {
    Forest *f;
    LsysPlant *plants;
    int n, cap;
    float (*ends)[3];   /* the turtle's ends for steps without ?E answers */
    size_t ends_cap;
};

int lsys_draw(const SylProgram *q, const SylString *s, const SylDeriveOptions *d, const float at[3], SylSkeleton **out) {
    SylString *ti = NULL;
    int st = syl_interpret(q, s, d, &ti);
    SylTurtleOptions to = {.diag = d->diag, .max_memory = d->max_memory, .budget = d->budget};
    if (!st) st = syl_turtle_draw(q, ti, &to, out);
    syl_string_free(ti);
    if (st) return st;
    SylSkeleton *sk = *out;
    for (size_t i = 0; i < sk->nnodes; i++)
        for (int k = 0; k < 3; k++) sk->nodes[i].pos[k] += at[k];
    for (size_t i = 0; i < sk->norgans; i++)
        for (int k = 0; k < 3; k++) sk->organs[i].pos[k] += at[k];
    for (size_t i = 0; i < sk->nverts; i++)
        for (int k = 0; k < 3; k++) sk->poly_verts[i][k] += at[k];
    return SYL_OK;
}

static int year_start(void *user, int year);

SceneLsys *scene_lsys_new(Forest *f, int max) {
    SceneLsys *s = calloc(1, sizeof *s);
    if (!s) return NULL;
    s->plants = calloc((size_t)(max > 0 ? max : 1), sizeof *s->plants);
    if (!s->plants) {
        free(s);
        return NULL;
    }
    s->f = f;
    s->cap = max;
    f->year_start = year_start;
    f->year_user = s;
    return s;
}

void scene_lsys_free(SceneLsys *s) {
    if (!s) return;
    for (int i = 0; i < s->n; i++) {
        LsysPlant *pl = &s->plants[i];
        if (pl->dv) syl_derive_end(pl->dv, NULL);
        syl_string_free(pl->final);
        free(pl->ends);
        syl_env_fill_free(&pl->fill);
    }
    free(s->plants);
    free(s->ends);
    free(s);
}

static const SylQueryOps plant_ops;

/* Does the model have an ?E module (used or not: the grid is kept as before)? */
static bool has_env_query(const SylProgram *q) {
    for (int s = 0; s < q->nsyms; s++)
        if (q->syms[s].turtle == TC_QUERY_E) return true;
    return false;
}

int scene_lsys_add(SceneLsys *s, const SylProgram *q, const SylDeriveOptions *d, const float at[3], float ground, int steps) {
    if (s->n == s->cap) return SYL_ELIMIT;
    LsysPlant *pl = &s->plants[s->n++];
    pl->owner = s;
    pl->q = q;
    pl->d = *d;
    pl->d.queries = &plant_ops;
    pl->d.queries_user = pl;
    pl->steps = steps;
    memcpy(pl->at, at, sizeof pl->at);
    pl->ground = ground;
    pl->voxel = (float)syl_program_setting(q, "step");
    if (!(pl->voxel > 0) || !isfinite(pl->voxel)) pl->voxel = 1;
    /* ?E light needs a grid even when no tree keeps one: the stand-alone one's parameters */
    Forest *f = s->f;
    if (has_env_query(q) && !f->lsys_shadow) {
        f->lsys_shadow = true;
        f->lsys_shadow_voxel = pl->voxel;
    }
    return SYL_OK;
}


/* Replace the plant's casters in the shadow grid by these ends (plant coordinates). Removing
 * and adding are exact in fixed point, so the grid is as if only this year's were there. */
static int recast(LsysPlant *pl, const float (*ends)[3], size_t n) {
    Env *e = &pl->owner->f->env;
    if (e->shadow_on && pl->nends && !shadow_cast(&e->shadow, (const float(*)[3])pl->ends, pl->nends, -1))
        return forest_shadow_too_big(pl->owner->f);
    pl->nends = 0;
    if (n > pl->cap) {
        float(*p)[3] = realloc(pl->ends, n * sizeof *p);
        if (!p) return SYL_ELIMIT;
        pl->ends = p;
        pl->cap = n;
    }
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) pl->ends[i][k] = ends[i][k] + pl->at[k];
    if (e->shadow_on && n && !shadow_cast(&e->shadow, (const float(*)[3])pl->ends, n, 1)) return forest_shadow_too_big(pl->owner->f);
    pl->nends = n;
    pl->fresh = true;
    return SYL_OK;
}

/* The current string's segment ends (its skeleton's internodes), when no ?E answer brought
 * them this step: the turtle fills ?E only for models with query modules. */
static int turtle_ends(LsysPlant *pl) {
    SceneLsys *s = pl->owner;
    SylDeriveOptions d = pl->d;
    d.steps = pl->done; /* the step number of the interpret rules' random streams */
    SylString *ti = NULL;
    SylSkeleton *sk = NULL;
    int st = syl_interpret(pl->q, syl_deriver_string(pl->dv), &d, &ti);
    SylTurtleOptions to = {.diag = d.diag, .max_memory = d.max_memory, .budget = d.budget};
    if (!st) st = syl_turtle_draw(pl->q, ti, &to, &sk);
    syl_string_free(ti);
    size_t n = 0;
    if (!st && sk->nnodes > s->ends_cap) {
        float(*e)[3] = realloc(s->ends, sk->nnodes * sizeof *e);
        if (e) s->ends = e, s->ends_cap = sk->nnodes;
        else st = SYL_ELIMIT;
    }
    for (size_t i = 0; !st && i < sk->nnodes; i++)
        if (sk->nodes[i].kind == SYL_KIND_INTERNODE) memcpy(s->ends[n++], sk->nodes[i].pos, sizeof *s->ends);
    syl_skeleton_free(sk);
    return st ? st : recast(pl, (const float(*)[3])s->ends, n);
}

/* Derive until `want` steps are taken (begin with the axiom the first time). */
static int advance(LsysPlant *pl, int want) {
    int st = SYL_OK;
    if (want > pl->steps) want = pl->steps;
    if (!pl->dv) {
        pl->fresh = false;
        st = syl_derive_begin(pl->q, &pl->d, NULL, &pl->dv);
    }
    while (!st && pl->done < want) {
        pl->fresh = false;
        st = syl_derive_step(pl->dv);
        pl->done++;
    }
    if (!st && !pl->fresh) st = turtle_ends(pl);
    if (st) pl->owner->f->reported = true; /* the deriver and the turtle say why */
    return st;
}

/* Every plant's ends become the environment's static occupants for this year's growth. */
static int publish(SceneLsys *s) {
    Env *e = &s->f->env;
    env_clear_statics(e);
    for (int i = 0; i < s->n; i++)
        for (size_t k = 0; k < s->plants[i].nends; k++)
            if (!env_add_static(e, s->plants[i].ends[k])) return SYL_ELIMIT;
    if (e->cloud_on) /* markers near a new segment are taken, as by a new metamer */
        for (size_t k = 0; k < e->nstatic; k++) markers_kill_near(&e->cloud, e->statics + 3 * k);
    return forest_occupancy(s->f);
}

/* Steps beyond the forest's years are all taken in its last year. */
static int year_start(void *user, int year) {
    SceneLsys *s = user;
    int st = SYL_OK;
    for (int i = 0; i < s->n && !st; i++) {
        LsysPlant *pl = &s->plants[i];
        st = advance(pl, year >= s->f->years ? pl->steps : year);
    }
    return st ? st : publish(s);
}

int scene_lsys_finish(SceneLsys *s) {
    int st = SYL_OK;
    for (int i = 0; i < s->n && !st; i++) {
        LsysPlant *pl = &s->plants[i];
        st = advance(pl, pl->steps);
        if (!st) {
            st = syl_derive_end(pl->dv, &pl->final);
            pl->dv = NULL;
            if (st) s->f->reported = true;
        }
    }
    return st;
}

int scene_lsys_draw(SceneLsys *s, int i, SylSkeleton **out) {
    LsysPlant *pl = &s->plants[i];
    *out = NULL;
    if (!pl->final) return SYL_ELIMIT;
    SylDeriveOptions d = pl->d;
    d.steps = pl->steps;
    int st = lsys_draw(pl->q, pl->final, &d, pl->at, out);
    if (st) s->f->reported = true;
    return st;
}

/* ---- ?E answers ---- */

/* Crowding and sky exposure see the trees' metamer ends and every L-system's ends as they
 * are now (*n of them, in the environment's ?E points). */
static int build_space(SceneLsys *s, const LsysPlant *pl, size_t *npts) {
    Forest *f = s->f;
    size_t n = 0;
    for (int i = 0; i < f->ntrees; i++) n += f->trees[i].n - 1;
    for (int i = 0; i < s->n; i++) n += s->plants[i].nends;
    if (!env_probe_points(&f->env, n)) return SYL_ELIMIT;
    float(*pts)[3] = f->env.probes.pts;
    size_t m = 0;
    for (int i = 0; i < f->ntrees; i++)
        for (size_t k = 1; k < f->trees[i].n; k++) memcpy(pts[m++], f->trees[i].nodes[k].pos, sizeof *pts);
    for (int i = 0; i < s->n; i++)
        if (s->plants[i].nends) {
            memcpy(pts + m, s->plants[i].ends, s->plants[i].nends * sizeof *pts);
            m += s->plants[i].nends;
        }
    *npts = n;
    return pgrid_build(&f->env.probes.occ, pl->voxel, (const float *)pts, 3, n) ? SYL_OK : SYL_ELIMIT;
}

/* The probes of one step: the plant's ends replace its casters first, so it shades itself. */
static int answer(LsysPlant *pl, int step, const SylEnvFill *fill, double *par) {
    SceneLsys *s = pl->owner;
    Env *e = &s->f->env;
    int st = recast(pl, (const float(*)[3])fill->ends, fill->nends);
    unsigned kinds = probe_kinds(fill, par);
    size_t npts = 0;
    if (!st && kinds & (1u << PROBE_SPACE | 1u << PROBE_SKY)) st = build_space(s, pl, &npts);
    if (!st && kinds & 1u << PROBE_SKY)
        st = probe_sky_build(&e->probes.sky, e->dev, &e->obstacles, NULL, 0, pl->at, (const float *)e->probes.pts,
                             npts, probe_foliage(pl->voxel));
    ProbeWorld w = env_probe_world(e, pl->voxel, pl->ground, &e->obstacles, pl->at);
    if (!st) probe_answer(&w, fill, step, par);
    return st;
}

/* The turtle's query pass, then the scene's answers (user: the plant). */
static int plant_fill(void *user, const SylProgram *p, SylString *s, int step) {
    LsysPlant *pl = user;
    if (!p->uses_env) return syl_turtle_query(p, s, NULL);
    int st = syl_turtle_query(p, s, &pl->fill);
    if (!st && pl->fill.nprobes) st = answer(pl, step, &pl->fill, s->par);
    return st;
}

static const SylQueryOps plant_ops = {.fill = plant_fill};
