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
 * ?E modules are answered here, not by env/open.c: light from the forest's shadow grid (the
 * trees' metamers and every L-system's latest ends, its own of this step included), crowding
 * from the same points, distance from the obstacles and the ground. A step that brings no
 * ?E answer (no probes, or no ?E at all) gets its ends from the turtle's skeleton. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "env/open.h"
#include "sot/forest_internal.h"

enum { Q_LIGHT = 0, Q_SPACE = 1, Q_DISTANCE = 2 };

typedef struct LsysPlant {
    SceneLsys *owner;
    SylProgram *q;
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
} LsysPlant;

struct SceneLsys {
    Forest *f;
    LsysPlant *plants;
    int n, cap;
    float (*ends)[3];   /* the turtle's ends for steps without ?E answers */
    size_t ends_cap;
    float (*pts)[3];    /* occupants for ?E(1) */
    size_t pts_cap;
    PointGrid occ;
};

int lsys_draw(const SylProgram *q, const SylString *s, const SylDeriveOptions *d, const float at[3], SylSkeleton **out) {
    SylString *ti = NULL;
    int st = syl_interpret(q, s, d, &ti);
    SylTurtleOptions to = {.diag = d->diag};
    if (!st) st = syl_turtle(q, ti, &to, out);
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
        syl_program_free(pl->q);
        free(pl->ends);
    }
    free(s->plants);
    free(s->ends);
    free(s->pts);
    pgrid_free(&s->occ);
    free(s);
}

static int answer(void *user, int step, const SylEnvFill *fill, double *par);

int scene_lsys_add(SceneLsys *s, SylProgram *q, const SylDeriveOptions *d, const float at[3], float ground, int steps) {
    if (s->n == s->cap) return SYL_ELIMIT;
    LsysPlant *pl = &s->plants[s->n++];
    pl->owner = s;
    pl->q = q;
    pl->d = *d;
    pl->d.env = answer;
    pl->d.env_user = pl;
    pl->steps = steps;
    memcpy(pl->at, at, sizeof pl->at);
    pl->ground = ground;
    pl->voxel = (float)syl_program_setting(q, "step");
    if (!(pl->voxel > 0) || !isfinite(pl->voxel)) pl->voxel = 1;
    /* ?E light needs a grid even when no tree keeps one: the stand-alone one's parameters */
    Forest *f = s->f;
    if (syl_program_symbol_find(q, "?E") >= 0 && !f->lsys_shadow) {
        f->lsys_shadow = true;
        f->lsys_shadow_params = (ShadowParams){.voxel = pl->voxel, .full = 1, .a = 0.25f, .b = 2, .depth = 8};
    }
    return SYL_OK;
}

static int too_big(const Forest *f) {
    if (f->diag)
        fprintf(f->diag, "sylva: error: the shadow grid would need more than %zu voxels: the scene is too large "
                         "for its voxel size\n", f->env.shadow.max_voxels);
    return SYL_ELIMIT;
}

/* Replace the plant's casters in the shadow grid by these ends (plant coordinates). Removing
 * and adding are exact in fixed point, so the grid is as if only this year's were there. */
static int recast(LsysPlant *pl, const float (*ends)[3], size_t n) {
    Env *e = &pl->owner->f->env;
    if (e->shadow_on && pl->nends && !shadow_cast(&e->shadow, (const float(*)[3])pl->ends, pl->nends, -1))
        return too_big(pl->owner->f);
    pl->nends = 0;
    if (n > pl->cap) {
        float(*p)[3] = realloc(pl->ends, n * sizeof *p);
        if (!p) return SYL_ELIMIT;
        pl->ends = p;
        pl->cap = n;
    }
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) pl->ends[i][k] = ends[i][k] + pl->at[k];
    if (e->shadow_on && n && !shadow_cast(&e->shadow, (const float(*)[3])pl->ends, n, 1)) return too_big(pl->owner->f);
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
    SylTurtleOptions to = {.diag = d.diag};
    if (!st) st = syl_turtle(pl->q, ti, &to, &sk);
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
    return lsys_draw(pl->q, pl->final, &d, pl->at, out);
}

/* ---- ?E answers ---- */

/* Crowding sees the trees' metamer ends and every L-system's ends as they are now. */
static int build_space(SceneLsys *s, const LsysPlant *pl) {
    const Forest *f = s->f;
    size_t n = 0;
    for (int i = 0; i < f->ntrees; i++) n += f->trees[i].n - 1;
    for (int i = 0; i < s->n; i++) n += s->plants[i].nends;
    if (n > s->pts_cap) {
        float(*p)[3] = realloc(s->pts, n * sizeof *p);
        if (!p) return SYL_ELIMIT;
        s->pts = p;
        s->pts_cap = n;
    }
    size_t m = 0;
    for (int i = 0; i < f->ntrees; i++)
        for (size_t k = 1; k < f->trees[i].n; k++) memcpy(s->pts[m++], f->trees[i].nodes[k].pos, sizeof *s->pts);
    for (int i = 0; i < s->n; i++)
        if (s->plants[i].nends) {
            memcpy(s->pts + m, s->plants[i].ends, s->plants[i].nends * sizeof *s->pts);
            m += s->plants[i].nends;
        }
    return pgrid_build(&s->occ, pl->voxel, (const float *)s->pts, 3, n) ? SYL_OK : SYL_ELIMIT;
}

/* Points within r of c, but not within r/1000 of the turtle (its own segment's end): as
 * env/open.c counts them. */
static double count_near(const PointGrid *g, const float c[3], float r, const float self[3]) {
    double n = 0;
    float r2 = r * r, e2 = r2 * 1e-6f;
    PGRID_FOR_CELLS(g, c, r, X, Y, Z) {
        uint32_t first, cnt = pgrid_cell(g, X, Y, Z, &first);
        for (uint32_t i = first; i < first + cnt; i++) {
            const float *q = g->pts[i];
            float d2 = 0, s2 = 0;
            for (int k = 0; k < 3; k++) d2 += (q[k] - c[k]) * (q[k] - c[k]), s2 += (q[k] - self[k]) * (q[k] - self[k]);
            n += d2 < r2 && s2 > e2;
        }
    }
    return n;
}

static double distance(const LsysPlant *pl, const float pos[3], const float h[3]) {
    const Obstacles *o = &pl->owner->f->env.obstacles;
    float far = (float)OPEN_FAR;
    if (h[1] < 0 && pos[1] > pl->ground) far = (pl->ground - pos[1]) / h[1];
    if (obstacles_any(o)) far = obstacles_distance(o, pos, h, far);
    return far;
}

/* Light as the trees see it, Q = C - s (+ a at a segment's own end), divided by C: 1 in the
 * open whatever the species' C. */
static double light(const ShadowGrid *g, const float pos[3], bool tip) {
    const ShadowParams *sp = &g->p;
    double v = (sp->full - shadow_at(g, pos) + (tip ? sp->a : 0)) / sp->full;
    return v < 0 ? 0 : v < 1 ? v : 1;
}

/* A SylEnvFn: user is the plant. Its ends replace its casters first, so it shades itself. */
static int answer(void *user, int step, const SylEnvFill *fill, double *par) {
    (void)step;
    LsysPlant *pl = user;
    SceneLsys *s = pl->owner;
    const Env *e = &s->f->env;
    int st = recast(pl, (const float(*)[3])fill->ends, fill->nends);
    bool space = false;
    for (size_t i = 0; i < fill->nprobes; i++) {
        const SylEnvProbe *q = &fill->probes[i];
        space |= q->na && par[q->par] == Q_SPACE;
    }
    if (!st && space) st = build_space(s, pl);
    for (size_t i = 0; !st && i < fill->nprobes; i++) {
        const SylEnvProbe *q = &fill->probes[i];
        if (q->na < 2) continue; /* nowhere to answer */
        double *a = par + q->par;
        float pos[3];
        for (int k = 0; k < 3; k++) pos[k] = q->pos[k] + pl->at[k];
        if (a[0] == Q_LIGHT) a[1] = e->shadow_on ? light(&e->shadow, pos, q->tip) : 1;
        else if (a[0] == Q_SPACE) {
            float r = q->na >= 3 && a[2] > 0 && isfinite(a[2]) ? (float)a[2] : pl->voxel, c[3];
            for (int k = 0; k < 3; k++) c[k] = pos[k] + r * q->h[k];
            a[1] = count_near(&s->occ, c, r, pos);
        } else if (a[0] == Q_DISTANCE) a[1] = distance(pl, pos, q->h);
    }
    return st;
}
