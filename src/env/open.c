/* The environment of an open L-system: see open.h. */
#include "env/open.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { Q_LIGHT = 0, Q_SPACE = 1, Q_DISTANCE = 2 };

void open_env_init(OpenEnv *e, const OpenEnvParams *p) {
    memset(e, 0, sizeof *e);
    e->P = *p;
    if (!(e->P.voxel > 0) || !isfinite(e->P.voxel)) e->P.voxel = 1;
    ShadowParams sp = {.voxel = e->P.voxel, .full = 1, .a = 0.25f, .b = 2, .depth = 8};
    memcpy(sp.sun, e->P.sun, sizeof sp.sun);
    if (!(sp.sun[1] > 0)) sp.sun[0] = sp.sun[2] = 0, sp.sun[1] = 1;
    shadow_init(&e->shadow, &sp, e->P.ground);
}

void open_env_free(OpenEnv *e) {
    shadow_free(&e->shadow);
    pgrid_free(&e->occ);
    free(e->cast);
    free(e->pts);
    memset(e, 0, sizeof *e);
}

static int too_big(OpenEnv *e) {
    if (e->P.diag) fprintf(e->P.diag, "sylva: error: the environment of ?E needs too large a shadow grid\n");
    return SYL_ELIMIT;
}

/* Replace last step's own casters in the shadow grid by this step's. */
static int update_light(OpenEnv *e, const SylEnvFill *f) {
    if (!e->statics_cast) {
        if (e->P.nstatic && !shadow_cast_strided(&e->shadow, e->P.statics, 3, e->P.nstatic, 1)) return too_big(e);
        e->statics_cast = true;
    }
    if (e->ncast && !shadow_cast(&e->shadow, (const float(*)[3])e->cast, e->ncast, -1)) return too_big(e);
    e->ncast = 0;
    if (f->nends > e->cast_cap) {
        float(*c)[3] = realloc(e->cast, f->nends * sizeof *c);
        if (!c) return SYL_ELIMIT;
        e->cast = c;
        e->cast_cap = f->nends;
    }
    for (size_t i = 0; i < f->nends; i++)
        for (int k = 0; k < 3; k++) e->cast[i][k] = f->ends[i][k] + e->P.at[k];
    if (f->nends && !shadow_cast(&e->shadow, (const float(*)[3])e->cast, f->nends, 1)) return too_big(e);
    e->ncast = f->nends;
    return SYL_OK;
}

static int update_space(OpenEnv *e, const SylEnvFill *f) {
    size_t n = e->P.nstatic + f->nends;
    if (n > e->pts_cap) {
        float(*p)[3] = realloc(e->pts, n * sizeof *p);
        if (!p) return SYL_ELIMIT;
        e->pts = p;
        e->pts_cap = n;
    }
    if (e->P.nstatic) memcpy(e->pts, e->P.statics, e->P.nstatic * sizeof *e->pts);
    for (size_t i = 0; i < f->nends; i++)
        for (int k = 0; k < 3; k++) e->pts[e->P.nstatic + i][k] = f->ends[i][k] + e->P.at[k];
    return pgrid_build(&e->occ, e->P.voxel, (const float *)e->pts, 3, n) ? SYL_OK : SYL_ELIMIT;
}

/* Points within r of c, but not within r/1000 of the turtle (its own segment's end). */
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

static double distance(const OpenEnv *e, const float pos[3], const float h[3]) {
    float far = (float)OPEN_FAR;
    if (h[1] < 0 && pos[1] > e->P.ground) far = (e->P.ground - pos[1]) / h[1];
    if (e->P.obstacles) far = obstacles_distance(e->P.obstacles, pos, h, far);
    return far;
}

int open_env_answer(void *user, int step, const SylEnvFill *f, double *par) {
    (void)step;
    OpenEnv *e = user;
    bool light = false, space = false;
    for (size_t i = 0; i < f->nprobes; i++) {
        const SylEnvProbe *q = &f->probes[i];
        double kind = q->na ? par[q->par] : Q_LIGHT;
        light |= kind == Q_LIGHT;
        space |= kind == Q_SPACE;
    }
    int st = light ? update_light(e, f) : SYL_OK;
    if (!st && space) st = update_space(e, f);
    for (size_t i = 0; !st && i < f->nprobes; i++) {
        const SylEnvProbe *q = &f->probes[i];
        if (q->na < 2) continue; /* nowhere to answer */
        double *a = par + q->par;
        float pos[3];
        for (int k = 0; k < 3; k++) pos[k] = q->pos[k] + e->P.at[k];
        if (a[0] == Q_LIGHT) {
            const ShadowParams *sp = &e->shadow.p;
            double v = sp->full - shadow_at(&e->shadow, pos) + (q->tip ? sp->a : 0); /* not its own shadow */
            a[1] = v < 0 ? 0 : v < sp->full ? v : sp->full;
        } else if (a[0] == Q_SPACE) {
            float r = q->na >= 3 && a[2] > 0 && isfinite(a[2]) ? (float)a[2] : e->P.voxel, c[3];
            for (int k = 0; k < 3; k++) c[k] = pos[k] + r * q->h[k];
            a[1] = count_near(&e->occ, c, r, pos);
        } else if (a[0] == Q_DISTANCE) {
            a[1] = distance(e, pos, q->h);
        }
    }
    return st;
}
