/* The environment of an open L-system: see open.h. */
#include "scene/open.h"
#include "lang/program.h"
#include "lsys/modstr.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>


void open_env_init(OpenEnv *e, const OpenEnvParams *p) {
    memset(e, 0, sizeof *e);
    e->P = *p;
    if (!(e->P.voxel > 0) || !isfinite(e->P.voxel)) e->P.voxel = 1;
    ShadowParams sp = probe_shadow_params(e->P.voxel, e->P.sun);
    env_init_probes(&e->world, &sp, e->P.ground, diag_sink(&(SylSink){0}, e->P.diag, e->P.sink));
}

void open_env_free(OpenEnv *e) {
    env_free(&e->world);
    shadow_set_free(&e->own);
    free(e->probes.light);
    syl_env_fill_free(&e->fill);
    memset(e, 0, sizeof *e);
}

static int too_big(OpenEnv *e) {
    diag_say(e->P.diag, e->P.sink, DIAG_ERROR, NULL, "the environment of ?E needs too large a shadow grid");
    return SYL_ELIMIT;
}

/* Replace last step's own casters in the shadow grid by this step's. */
static int update_light(OpenEnv *e, const SylEnvFill *f) {
    if (!e->statics_cast) {
        if (e->P.nstatic && !shadow_cast_strided(&e->world.shadow, e->P.statics, 3, e->P.nstatic, 1)) return too_big(e);
        e->statics_cast = true;
    }
    if (!shadow_set_replace(&e->world.shadow, &e->own, (const float(*)[3])f->ends, f->nends, e->P.at)) return too_big(e);
    return SYL_OK;
}

static int update_space(OpenEnv *e, const SylEnvFill *f) {
    size_t n = e->P.nstatic + f->nends;
    if (!env_probe_points(&e->world, n)) return SYL_ELIMIT;
    float(*pts)[3] = e->world.probes.pts;
    if (e->P.nstatic) memcpy(pts, e->P.statics, e->P.nstatic * sizeof *pts);
    for (size_t i = 0; i < f->nends; i++)
        for (int k = 0; k < 3; k++) pts[e->P.nstatic + i][k] = f->ends[i][k] + e->P.at[k];
    return pgrid_build(&e->world.probes.occ, e->P.voxel, (const float *)pts, 3, n) ? SYL_OK : SYL_ELIMIT;
}

/* Sky exposure's foliage: this step's own ends and the scene's other plants. */
static int update_sky(OpenEnv *e, const SylEnvFill *f) {
    RTCDevice dev = env_device(&e->world);
    if (!dev) return SYL_ELIMIT;
    return probe_sky_build(&e->world.probes.sky, dev, e->P.obstacles, (const float(*)[3])f->ends, f->nends, e->P.at,
                           e->P.statics, e->P.nstatic, probe_foliage(e->P.voxel));
}

/* Update what the kinds asked read (bit k: kind k). */
static int update(OpenEnv *e, const SylEnvFill *f, unsigned kinds) {
    int st = kinds & 1u << PROBE_LIGHT ? update_light(e, f) : SYL_OK;
    if (!st && kinds & 1u << PROBE_SPACE) st = update_space(e, f);
    if (!st && kinds & 1u << PROBE_SKY) st = update_sky(e, f);
    return st;
}

static ProbeWorld world(OpenEnv *e) {
    return env_probe_world(&e->world, e->P.voxel, e->P.ground, e->P.obstacles, e->P.at);
}

int open_env_answer(OpenEnv *e, int step, const SylEnvFill *f, double *par) {
    int st = update(e, f, probe_kinds(f, par));
    ProbeWorld w = world(e);
    if (!st) probe_answer(&w, f, step, par);
    return st;
}

/* Light as probe_answer gives it, for compact probes. */
static void answer_light(const OpenEnv *e, const SylLightProbe *probes, size_t n, double *par) {
    for (size_t i = 0; i < n; i++) {
        const SylLightProbe *q = &probes[i];
        float pos[3];
        for (int k = 0; k < 3; k++) pos[k] = q->pos[k] + e->P.at[k];
        par[(q->par & ~SYL_LIGHT_TIP) + 1] = probe_light(&e->world.shadow, pos, (q->par & SYL_LIGHT_TIP) != 0);
    }
}

int open_env_fill(OpenEnv *e, const SylProgram *p, SylString *s, SylEnvFill *f, int step) {
    int st = syl_turtle_fill(p, s, f, &e->probes);
    if (st) return st;
    /* sky exposure keys its rays' streams by a probe's place among all of them: read again, as
     * the plain query pass does */
    if (e->probes.kinds & 1u << PROBE_SKY) {
        st = syl_turtle_query(p, s, f);
        return st || !f->nprobes ? st : open_env_answer(e, step, f, s->par);
    }
    st = update(e, f, e->probes.kinds);
    if (st) return st;
    ProbeWorld w = world(e);
    probe_answer(&w, f, step, s->par); /* crowding and distance */
    answer_light(e, e->probes.light, e->probes.nlight, s->par);
    return SYL_OK;
}

static int ops_fill(void *user, const SylProgram *p, SylString *s, int step) {
    OpenEnv *e = user;
    return p->uses_env ? open_env_fill(e, p, s, &e->fill, step) : syl_turtle_query(p, s, NULL);
}

const SylQueryOps open_env_ops = {.fill = ops_fill};

/* ---- the stand-alone environment ---- */

struct SylEnvStandalone {
    OpenEnv e;
    SylSink sink; /* the caller's, copied */
};

SylEnvStandalone *syl_env_standalone_new(const SylProgram *p, const SylSink *sink) {
    SylEnvStandalone *a = malloc(sizeof *a);
    if (!a) return NULL;
    if (sink) a->sink = *sink;
    OpenEnvParams P = {.voxel = (float)p->step, .sun = {0, 1, 0}, .sink = sink ? &a->sink : NULL};
    open_env_init(&a->e, &P);
    return a;
}

void syl_env_standalone_free(SylEnvStandalone *a) {
    if (!a) return;
    open_env_free(&a->e);
    free(a);
}

static int standalone_fill(void *user, const SylProgram *p, SylString *s, int step) {
    return ops_fill(&((SylEnvStandalone *)user)->e, p, s, step);
}

static const SylQueryOps standalone_ops = {.fill = standalone_fill};

const SylQueryOps *syl_env_standalone_ops(void) { return &standalone_ops; }
