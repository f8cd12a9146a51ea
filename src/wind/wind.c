/* The sway model: stems and joints from the skeleton, then each joint's rotation keys. */
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "sylva/wind.h"
#include "util/budget.h"
#include "util/diag.h"
#include "util/rng.h"

/* SylWind.store: what the wind is counted against until syl_wind_free */
struct SylWindStore {
    SylBudget *budget;
    uint64_t charged;
};

#define TWO_PI 6.28318530717958647692
enum { WIND_SEED = 0x5717d };
/* Bounds that keep a twig of huge L/r from spinning: the undirected sway (a1 + a2) and the
 * directed bend, radians. */
static const double undirected_max = 0.12, directed_max = 0.1;

/* Stems by axis: base, length, base radius, parent stem, order; phases from the axis id. */
static int find_stems(const SylSkeleton *s, const float *radius, SylWind *w) {
    int32_t n = 0;
    for (size_t i = 0; i < s->nnodes; i++)
        if (s->nodes[i].axis >= n) n = s->nodes[i].axis + 1;
    if (n <= 0) return SYL_OK;
    w->stems = calloc((size_t)n, sizeof *w->stems);
    bool *seen = calloc((size_t)n, sizeof *seen);
    if (!w->stems || !seen) {
        free(seen);
        return SYL_ELIMIT;
    }
    w->nstems = n;
    for (int32_t a = 0; a < n; a++) w->stems[a] = (SylWindStem){.joint = -1, .parent = -1};
    for (size_t i = 0; i < s->nnodes; i++) {
        const SylNode *nd = &s->nodes[i];
        if (nd->axis < 0) continue;
        SylWindStem *st = &w->stems[nd->axis];
        const SylNode *par = nd->parent >= 0 && (size_t)nd->parent < i ? &s->nodes[nd->parent] : NULL;
        if (!seen[nd->axis]) {
            seen[nd->axis] = true;
            memcpy(st->base, par ? par->pos : nd->pos, sizeof st->base);
            st->parent = par && par->axis != nd->axis ? par->axis : -1;
            if (par) {
                double d[3], n = 0;
                for (int c = 0; c < 3; c++) d[c] = (double)nd->pos[c] - par->pos[c], n += d[c] * d[c];
                for (int c = 0; c < 3 && n > 0; c++) st->dir[c] = (float)(d[c] / sqrt(n));
                if (st->parent >= 0) st->parent_radius = radius[nd->parent];
            }
            st->order = nd->order;
            Rng r = rng_stream(WIND_SEED, (uint64_t)nd->axis, 1, 0);
            st->phase = (float)(TWO_PI * rng_unit(&r));
        }
        if (st->radius <= 0 && nd->kind == SYL_KIND_INTERNODE && radius[i] > 0) st->radius = radius[i];
        if (par && nd->kind == SYL_KIND_INTERNODE) {
            double d2 = 0;
            for (int c = 0; c < 3; c++) d2 += (double)(nd->pos[c] - par->pos[c]) * (nd->pos[c] - par->pos[c]);
            st->length += (float)sqrt(d2);
        }
    }
    for (int32_t a = 0; a < n; a++) {
        SylWindStem *st = &w->stems[a];
        double r = st->radius > 0 ? st->radius : 1e-3, l = st->length > 0 ? st->length : 1e-3;
        st->stiffness = (float)(22.5 * r / (22.5 * r + l));
    }
    free(seen);
    return SYL_OK;
}

/* A joint for each stem of order below levels, parents first (a stem's parent has a lower
 * id: it was started earlier); the others take their parent stem's. */
static int find_joints(SylWind *w, int levels) {
    w->joints = malloc(((size_t)w->nstems + 1) * sizeof *w->joints);
    if (!w->joints) return SYL_ELIMIT;
    for (int32_t a = 0; a < w->nstems; a++) {
        SylWindStem *st = &w->stems[a];
        int32_t up = st->parent >= 0 && st->parent < a ? w->stems[st->parent].joint : -1;
        if (st->order < levels && (st->length > 0 || st->parent < 0)) {
            st->joint = w->njoints;
            SylWindJoint jt = {.stem = a, .parent = up};
            /* the part inside the parent moves with it; then a blend of four base radii,
             * both within the stem's first quarter, so the base bends instead of creasing */
            if (up >= 0 && (st->dir[0] || st->dir[1] || st->dir[2])) {
                jt.blend_start = fminf(st->parent_radius, st->length / 4);
                jt.blend_length = fminf(4 * st->radius, st->length / 4);
            }
            w->joints[w->njoints++] = jt;
        } else {
            st->joint = up;
        }
    }
    return SYL_OK;
}

static void quat_of(const double v[3], float q[4]) { /* rotation vector -> unit quaternion */
    double a = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]), k = a > 1e-12 ? sin(a / 2) / a : 0.5;
    q[0] = (float)(v[0] * k), q[1] = (float)(v[1] * k), q[2] = (float)(v[2] * k), q[3] = (float)cos(a / 2);
}

/* Joint j's keys. Weber–Penn: a0 = 4 L / r degrees, a1 = (W/50) a0, a2 = (G/50) a0 + a1/2
 * with gusts G = W, sines of frequency f and 0.7 f about x and z with their own phases
 * (Zamuda's R_x, R_z); Zamuda's directed wind bends by alpha_w = (S0/S) w_g about y x w,
 * S0/S the strands' ratio (R_trunk / r)^2, w_g = W / 1000. */
static void sway(const SylWindOptions *o, const double dir[2], float r0, SylWind *w, int j) {
    SylWindJoint *jt = &w->joints[j];
    const SylWindStem *st = &w->stems[jt->stem];
    double r = st->radius > 0 ? st->radius : 1e-3, l = st->length > 0 ? st->length : 1e-3, W = o->speed;
    double a0 = 4 * l / r * (TWO_PI / 360), a1 = W / 50 * a0, a2 = W / 50 * a0 + a1 / 2;
    if (a1 + a2 > undirected_max) {
        double k = undirected_max / (a1 + a2);
        a1 *= k, a2 *= k;
    }
    double ratio = r0 > 0 ? (double)r0 / r : 1, bend = fmin(directed_max, ratio * ratio * W / 1000);
    /* an Euler–Bernoulli cantilever rod: f = 0.28 r sqrt(E / rho) / L^2 for wood, a quarter of
     * it for the load it carries; a whole number of cycles per loop, so that the loop closes */
    double f = fmin(4, fmax(0.1, 265 * r / (l * l))), T = w->seconds;
    double n1 = fmax(1, round(f * T)), n2 = fmax(1, round(0.7 * n1));
    jt->frequency = (float)(n1 / T);
    jt->amplitude = (float)(bend + sqrt(2.0) * (a1 + a2));
    Rng rg = rng_stream(WIND_SEED, (uint64_t)jt->stem, 2, 0);
    double ph[4] = {st->phase, TWO_PI * rng_unit(&rg), TWO_PI * rng_unit(&rg), TWO_PI * rng_unit(&rg)};
    double axis[3] = {dir[1], 0, -dir[0]}; /* y x w: turning y about it leans downwind */
    for (int k = 0; k < w->nkeys; k++) {
        float *q = &w->rot[4 * ((size_t)j * (size_t)w->nkeys + (size_t)k)];
        if (k == w->nkeys - 1) { /* the loop closes exactly */
            memcpy(q, &w->rot[4 * (size_t)j * (size_t)w->nkeys], 4 * sizeof *q);
            continue;
        }
        double t = TWO_PI * k / (w->nkeys - 1);
        double ax = a1 * sin(n1 * t + ph[0]) + a2 * sin(n2 * t + ph[1]);
        double az = a1 * sin(n1 * t + ph[2]) + a2 * sin(n2 * t + ph[3]);
        double v[3] = {bend * axis[0] + ax, 0, bend * axis[2] + az};
        quat_of(v, q);
    }
}

int syl_wind_build(const SylSkeleton *s, const float *radius, const SylWindOptions *o, SylWind *out) {
    memset(out, 0, sizeof *out);
    if (!(o->speed > 0) || !isfinite(o->speed) || o->seconds < 0 || o->levels < 0 || o->fps < 0) {
        sink_error(opt_sink(o), "wind: a speed above 0, and seconds, levels and keys per second of at least 0");
        return SYL_EUSAGE;
    }
    out->seconds = o->seconds > 0 ? o->seconds : 4;
    int fps = o->fps > 0 ? o->fps : 15, levels = o->levels > 0 ? o->levels : 2;
    out->nkeys = (int)lround(out->seconds * fps) + 1;
    if (out->nkeys < 3) out->nkeys = 3;
    double dir[2] = {o->dir[0], o->dir[1]}, len = hypot(dir[0], dir[1]);
    if (len > 0) dir[0] /= len, dir[1] /= len;
    else dir[0] = 1, dir[1] = 0;
    int status = find_stems(s, radius, out);
    if (!status && out->nstems) status = find_joints(out, levels);
    uint64_t bytes = (uint64_t)out->nstems * (sizeof *out->stems + sizeof *out->joints) +
                     2 * 4 * sizeof *out->rot * (uint64_t)out->njoints * (uint64_t)out->nkeys;
    if (!status && !budget_charge(o->budget, bytes)) {
        sink_error(opt_sink(o),
                   "the wind's %d joints and %d keys would need %llu MB, more than --max-memory "
                   "allows (%llu MB in all); raise the limit with --max-memory, or use fewer --wind-levels or "
                   "--wind-seconds",
                    out->njoints, out->nkeys, (unsigned long long)(bytes >> 20),
                    (unsigned long long)budget_limit_mb(o->budget));
        syl_wind_free(out);
        return SYL_ELIMIT;
    }
    if (!status && o->budget) {
        if ((out->store = malloc(sizeof *out->store))) *out->store = (struct SylWindStore){o->budget, bytes};
        else budget_release(o->budget, bytes), status = SYL_ELIMIT;
    }
    if (!status && out->njoints &&
        !(out->rot = malloc(4 * sizeof *out->rot * (size_t)out->njoints * (size_t)out->nkeys)))
        status = SYL_ELIMIT;
    float r0 = 0; /* the thickest root stem's */
    for (int32_t a = 0; a < out->nstems && !status; a++)
        if (out->stems[a].parent < 0 && out->stems[a].radius > r0) r0 = out->stems[a].radius;
    for (int j = 0; j < out->njoints && !status; j++) sway(o, dir, r0, out, j);
    if (status == SYL_ELIMIT) sink_error(opt_sink(o), "out of memory building the wind's joints");
    if (status) syl_wind_free(out);
    return status;
}

void syl_wind_free(SylWind *w) {
    if (w->store) budget_release(w->store->budget, w->store->charged);
    free(w->store);
    free(w->stems);
    free(w->joints);
    free(w->rot);
    memset(w, 0, sizeof *w);
}
