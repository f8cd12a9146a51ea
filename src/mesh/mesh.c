/* Mesher: a generalized cylinder along every axis of a skeleton.
 *
 * An axis is a chain of nodes with the same axis id, each the parent of the next. Its tube
 * runs through the nodes' positions; a lateral axis starts at its parent node on the parent
 * axis, moved back along its own direction into the parent so that no gap shows at the
 * junction (the "unwelded insertion" of ez-tree or Mtree's basic mesher). Rings of vertices
 * are placed with rotation-minimising frames (the double reflection method of Wang, Juttler,
 * Zheng and Liu 2008, "Computation of rotation minimizing frames"), so a branch does not
 * twist; at a bend the ring lies across the bisector and is widened in the bend plane like a
 * mitre, so the tube keeps its thickness. Both ends are capped by fans: each tube is closed.
 *
 * Radii: the model's widths (a ring at a node has the radius of the segment ending there),
 * or the pipe model, r^e = sum of the children's r^e, tips having a fixed radius. Thin
 * tubes get fewer sides: sides ~ sqrt(r / r_max) keeps the depth of the facets (about
 * r pi^2 / 2 sides^2) the same on thin and thick branches.
 *
 * Bark UVs: u goes once around (the seam is duplicated), v is the length along the axis
 * divided by the local circumference, so texels stay square and v is continuous from the
 * base of an axis to its tip. The radius in v is at least 1/100 of the thickest tube's: a
 * twig so thin is about 5 texels of the trunk's bark tile around, so its bark stretching
 * along it does not show, and v no longer diverges on twigs that taper to a point (a range
 * a 16-bit v holds to half a texel: the .glb writer's quantized UVs). */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cglm/cglm.h>

#include "mesh/mesh_internal.h"
#include "mesh/store.h"
#include "util/budget.h"
#include "util/pages.h"
#include "util/diag.h"
#include "util/parallel.h"
#include "util/rng.h"

#define TWO_PI 6.28318530717958647692f
/* fmaxf and fminf are calls (they care about NaN); these are one instruction */
#define MAXF(a, b) ((a) > (b) ? (a) : (b))
#define MINF(a, b) ((a) < (b) ? (a) : (b))

typedef float v4f __attribute__((vector_size(16))); /* a GCC and Clang extension */

bool mesh_reserve(void **arr, size_t *cap, size_t n, size_t more, size_t elem) {
    if (n + more <= *cap) return true;
    size_t c = *cap ? *cap : 64;
    while (c < n + more) c *= 2;
    void *p;
    if (c * elem >= PAGES_OWNED_SCRATCH && *cap * elem < PAGES_OWNED_SCRATCH) {
        /* past the size where huge pages pay (util/pages.h): a whole one at once */
        if (c * elem < PAGES_HUGE) c = PAGES_HUGE / elem;
        if (!(p = pages_owned(c * elem, PAGES_OWNED_SCRATCH))) return false;
        if (*cap) memcpy(p, *arr, *cap * elem);
        free(*arr);
    } else if (!(p = realloc(*arr, c * elem))) {
        return false;
    }
    *arr = p;
    *cap = c;
    return true;
}

bool mesh_add_run(MeshPlan *pl, uint8_t mat, uint32_t tris) {
    if (!mesh_reserve((void **)&pl->runs, &pl->runs_cap, pl->nruns, 1, sizeof *pl->runs)) return false;
    pl->runs[pl->nruns++] = (MeshRun){.mat = mat, .tris = tris};
    return true;
}

const MeshTrig *mesh_trig(MeshPlan *pl, int sides) {
    if (!pl->trig[sides]) {
        MeshTrig *t = malloc(sizeof *t);
        if (!t) return NULL;
        for (int j = 0; j <= sides; j++) {
            double a = 2.0 * M_PI * j / sides;
            t->c[j] = (float)cos(a);
            t->s[j] = (float)sin(a);
            t->u[j] = (float)j / (float)sides;
        }
        t->c[sides] = t->c[0];
        t->s[sides] = t->s[0];
        pl->trig[sides] = t;
    }
    return pl->trig[sides];
}

static void plan_free(MeshPlan *pl) {
    free(pl->pts);
    free(pl->tubes);
    free(pl->runs);
    free(pl->items);
    free(pl->polys);
    free(pl->pv);
    free(pl->ptri);
    free(pl->clusters);
    for (int i = 0; i <= MESH_MAX_SIDES; i++) free(pl->trig[i]);
    for (int i = 0; i < 256; i++) free(pl->panels[i]);
}

void syl_mesh_free(SylMesh *m) {
    if (!m) return;
    struct SylMeshStore *st = m->store;
    if (st) budget_release(st->budget, st->charged);
    if (st && st->block) {
        free(st->block);
    } else {
        free(m->pos);
        free(m->nrm);
        free(m->uv);
        free(m->idx);
    }
    free(m->groups);
    free(m->node);
    syl_images_release(m->images);
    free(st);
    free(m);
}

static void diag(const SylMeshOptions *o, const char *msg) {
    if (o) sink_error(opt_sink(o), "mesh: %s", msg);
}

static bool finite3(const float p[3]) { return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]); }

static float clean_radius(float r) { return isfinite(r) && r > 0 ? r : 0; }

/* ------------------------------------------------------------------ radii */

/* Pipe model, bottom-up: parents precede their children (checked by the caller). */
static void pipe_radii(const SylSkeleton *s, float e, float tip, float *rad) {
    size_t n = s->nnodes;
    double *acc = calloc(n, sizeof *acc);
    uint8_t *inner = calloc(n, 1);
    if (!acc || !inner) {
        free(acc);
        free(inner);
        for (size_t i = 0; i < n; i++) rad[i] = tip;
        return;
    }
    for (size_t i = 0; i < n; i++)
        if (s->nodes[i].parent >= 0) inner[s->nodes[i].parent] = 1;
    if (!(tip > 0)) { /* the model's: the mean radius of its tips */
        double sum = 0;
        size_t k = 0;
        for (size_t i = 0; i < n; i++)
            if (!inner[i] && s->nodes[i].parent >= 0 && clean_radius(s->nodes[i].radius) > 0) {
                sum += s->nodes[i].radius;
                k++;
            }
        tip = k ? (float)(sum / (double)k) : 0.05f;
    }
    double tip_e = pow(tip, e), inv_e = 1.0 / e;
    for (size_t i = n; i-- > 0;) {
        double v = inner[i] ? acc[i] : tip_e;
        rad[i] = inner[i] ? (float)(e == 2 ? sqrt(v) : pow(v, inv_e)) : tip;
        if (s->nodes[i].parent >= 0) acc[s->nodes[i].parent] += v;
    }
    free(acc);
    free(inner);
}

/* ------------------------------------------------------------------ tubes */

/* A node of the tube being planned. */
typedef struct RawPt {
    float p[3];
    float r;
    int32_t node;
    uint8_t mat;
    bool smooth;
    uint8_t lobes;
    uint16_t lobe_depth;
} RawPt;

/* Uniform Catmull-Rom between p1 and p2 at t. */
static void catmull_rom(const float *p0, const float *p1, const float *p2, const float *p3, float t, float *out) {
    float t2 = t * t, t3 = t2 * t;
    for (int k = 0; k < 3; k++)
        out[k] = 0.5f * (2 * p1[k] + (-p0[k] + p2[k]) * t + (2 * p0[k] - 5 * p1[k] + 4 * p2[k] - p3[k]) * t2 +
                         (-p0[k] + 3 * p1[k] - 3 * p2[k] + p3[k]) * t3);
}

static void any_perpendicular(vec3 t, vec3 out) {
    vec3 a = {1, 0, 0};
    if (fabsf(t[0]) > 0.9f) a[0] = 0, a[1] = 1;
    glm_vec3_cross(t, a, out);
    glm_vec3_normalize(out);
}

/* Project a onto the plane perpendicular to unit t; false when too short. */
static bool perpendicular_of(const float *a, vec3 t, vec3 out) {
    float d = a[0] * t[0] + a[1] * t[1] + a[2] * t[2];
    for (int k = 0; k < 3; k++) out[k] = a[k] - d * t[k];
    float len = glm_vec3_norm(out);
    if (!(len > 1e-4f)) return false;
    glm_vec3_scale(out, 1.0f / len, out);
    return true;
}

enum { SMOOTH_SUB = 4 }; /* a smoothed segment becomes this many */

/* Finish a tube of nraw points: drop repeated points, give radii, sink a lateral base, smooth,
 * and append its points. lateral: raw[0] is the parent node. */
static bool finish_tube(MeshPlan *pl, RawPt *raw, size_t nraw, bool lateral) {
    const SylSkeleton *s = pl->skel;
    size_t n = 0;
    for (size_t k = 0; k < nraw; k++) {
        if (!finite3(raw[k].p)) continue;
        if (n) {
            const float *q = raw[n - 1].p;
            float d2 = 0, scale = 0;
            for (int c = 0; c < 3; c++) {
                float dc = raw[k].p[c] - q[c];
                d2 += dc * dc;
                scale = MAXF(scale, fabsf(q[c]));
            }
            float eps = 1e-6f * scale + 1e-9f;
            if (d2 <= eps * eps) continue;
        } else if (k > 0) {
            lateral = false; /* the parent was unusable: start at this node */
        }
        raw[n++] = raw[k];
    }
    if (n < 2) return true;
    /* radius of every point; the first takes the first segment's */
    float r0 = raw[1].r;
    float rmax = 0;
    for (size_t k = 1; k < n; k++) rmax = MAXF(rmax, raw[k].r);
    if (!(rmax > 0)) return true; /* nothing to see */
    const SylNode *first = &s->nodes[raw[lateral ? 1 : 0].node];
    vec3 d0;
    glm_vec3_sub(raw[1].p, raw[0].p, d0);
    glm_vec3_normalize(d0);
    vec3 base;
    glm_vec3_copy(raw[0].p, base);
    if (lateral) { /* into the parent, but not out of its other side */
        const SylNode *par = &s->nodes[raw[0].node];
        float rp = raw[0].r;
        vec3 ph;
        glm_vec3_copy((float *)par->h, ph);
        float sink = 0;
        if (glm_vec3_norm(ph) > 1e-6f) {
            glm_vec3_normalize(ph);
            float cosa = fabsf(glm_vec3_dot(ph, d0));
            float sina = sqrtf(MAXF(0.f, 1.f - cosa * cosa));
            sink = rp;
            if (sina > 1e-4f) {
                sink = MINF(sink, sqrtf(MAXF(rp * rp - r0 * r0, 0.f)) / sina);
                sink = MINF(sink, MAXF(rp - r0 * cosa, 0.f) / sina);
            }
            sink *= 0.95f;
        }
        glm_vec3_muladds(d0, -sink, base);
    }
    /* the frame's first normal: the first node's U, else its L, across the first tangent */
    MeshTube tube = {.first = (uint32_t)pl->npts, .rmax = rmax, .node = raw[n - 1].node};
    if (!perpendicular_of(first->u, d0, tube.ref) && !perpendicular_of(first->l, d0, tube.ref))
        any_perpendicular(d0, tube.ref);
    /* points, smoothed segments subdivided */
    size_t extra = 0;
    for (size_t k = 1; k < n; k++)
        if (raw[k].smooth && raw[k - 1].smooth) extra += SMOOTH_SUB - 1;
    if (!mesh_reserve((void **)&pl->pts, &pl->pts_cap, pl->npts, n + extra, sizeof *pl->pts)) return false;
    MeshPt *out = pl->pts + pl->npts;
    size_t m = 0;
    out[m++] = (MeshPt){.p = {base[0], base[1], base[2]}, .r = r0, .mat = raw[1].mat, .lobes = raw[lateral ? 1 : 0].lobes,
                        .lobe_depth = raw[lateral ? 1 : 0].lobe_depth};
    for (size_t k = 1; k < n; k++) {
        const float r = raw[k].r;
        if (raw[k].smooth && raw[k - 1].smooth) {
            const float *p1 = k == 1 ? base : raw[k - 1].p, *p2 = raw[k].p;
            float pre[3], post[3];
            const float *p0 = pre, *p3 = post;
            if (k >= 2) p0 = raw[k - 2].p;
            else
                for (int c = 0; c < 3; c++) pre[c] = 2 * p1[c] - p2[c];
            if (k + 1 < n) p3 = raw[k + 1].p;
            else
                for (int c = 0; c < 3; c++) post[c] = 2 * p2[c] - p1[c];
            float rprev = out[m - 1].r;
            for (int i = 1; i < SMOOTH_SUB; i++) {
                float t = (float)i / SMOOTH_SUB;
                MeshPt *q = &out[m++];
                catmull_rom(p0, p1, p2, p3, t, q->p);
                q->r = rprev + (r - rprev) * t;
                q->mat = raw[k].mat;
                q->lobes = raw[k].lobes, q->lobe_depth = raw[k].lobe_depth;
            }
        }
        out[m++] = (MeshPt){.p = {raw[k].p[0], raw[k].p[1], raw[k].p[2]}, .r = r, .mat = raw[k].mat, .lobes = raw[k].lobes,
                            .lobe_depth = raw[k].lobe_depth};
    }
    tube.count = (uint32_t)m;
    pl->npts += m;
    if (!mesh_reserve((void **)&pl->tubes, &pl->tubes_cap, pl->ntubes, 1, sizeof *pl->tubes)) return false;
    pl->tubes[pl->ntubes++] = tube;
    return true;
}

static void raw_point(RawPt *r, const SylNode *nd, int32_t idx, const float *rad) {
    memcpy(r->p, nd->pos, sizeof r->p);
    r->r = clean_radius(rad[idx]);
    r->mat = nd->material;
    r->node = idx;
    r->smooth = (nd->flags & SYL_NODE_SMOOTH) != 0;
    r->lobes = nd->lobes;
    r->lobe_depth = nd->lobe_depth;
}

/* Split the nodes into tubes in one pass in node order: a node continues the tube of its
 * parent when it has the same axis and the parent is that tube's last node so far; any
 * other node starts a tube (at its parent, if it has one). A second pass gathers each
 * tube's points, in tube order, and a third finishes the tubes. */
static bool plan_tubes(MeshPlan *pl, const float *rad) {
    const SylSkeleton *s = pl->skel;
    const size_t n = s->nnodes;
    uint32_t *tube_of = malloc((n ? n : 1) * sizeof *tube_of);
    uint32_t *tail = NULL, *count = NULL;
    int32_t *base = NULL;
    size_t nt = 0, cap = 0, ccap = 0, bcap = 0;
    RawPt *raw = NULL;
    bool ok = tube_of != NULL;
    for (size_t i = 0; i < n && ok; i++) {
        const SylNode *nd = &s->nodes[i];
        const int32_t p = nd->parent;
        if (p >= 0 && s->nodes[p].axis == nd->axis && tail[tube_of[p]] == (uint32_t)p) {
            uint32_t t = tube_of[p];
            tail[t] = (uint32_t)i;
            count[t]++;
            tube_of[i] = t;
            continue;
        }
        if (!mesh_reserve((void **)&tail, &cap, nt, 1, sizeof *tail) ||
            !mesh_reserve((void **)&count, &ccap, nt, 1, sizeof *count) ||
            !mesh_reserve((void **)&base, &bcap, nt, 1, sizeof *base)) {
            ok = false;
            break;
        }
        tail[nt] = (uint32_t)i;
        count[nt] = 1 + (p >= 0);
        base[nt] = p;
        tube_of[i] = (uint32_t)nt++;
    }
    size_t total = 0;
    for (size_t t = 0; t < nt && ok; t++) { /* count becomes each tube's cursor, tail its start */
        uint32_t c = count[t];
        tail[t] = count[t] = (uint32_t)total;
        total += c;
    }
    if (ok) ok = (raw = pages_owned((total ? total : 1) * sizeof *raw, PAGES_OWNED_SCRATCH)) != NULL;
    for (size_t t = 0; t < nt && ok; t++)
        if (base[t] >= 0) raw_point(&raw[count[t]++], &s->nodes[base[t]], base[t], rad);
    for (size_t i = 0; i < n && ok; i++) raw_point(&raw[count[tube_of[i]]++], &s->nodes[i], (int32_t)i, rad);
    /* room for every point (smoothing may add more) and every tube */
    if (ok) ok = mesh_reserve((void **)&pl->pts, &pl->pts_cap, pl->npts, total, sizeof *pl->pts) &&
                 mesh_reserve((void **)&pl->tubes, &pl->tubes_cap, pl->ntubes, nt, sizeof *pl->tubes);
    for (size_t t = 0; t < nt && ok; t++) ok = finish_tube(pl, raw + tail[t], count[t] - tail[t], base[t] >= 0);
    free(raw);
    free(tube_of);
    free(tail);
    free(count);
    free(base);
    return ok;
}

/* Sides and runs of every tube, once the thickest is known. */
static bool size_tubes(MeshPlan *pl) {
    float rmax = 0;
    for (size_t t = 0; t < pl->ntubes; t++) rmax = MAXF(rmax, pl->tubes[t].rmax);
    pl->uv_rmin = rmax / 100; /* 5 texels of the thickest tube's bark around: the head of this file */
    if (!mesh_reserve((void **)&pl->runs, &pl->runs_cap, pl->nruns, pl->ntubes, sizeof *pl->runs)) return false;
    for (size_t t = 0; t < pl->ntubes; t++) {
        MeshTube *tb = &pl->tubes[t];
        const MeshPt *p = pl->pts + tb->first;
        int sides = (int)ceilf((float)pl->sides * sqrtf(tb->rmax / rmax) - 1e-4f);
        if (sides < pl->min_sides) sides = pl->min_sides;
        if (sides > pl->sides) sides = pl->sides;
        /* the model's own points of a ring (SylMaterial.ring_sides), each plant of a scene its own */
        const SylNode *nd = tb->node >= 0 ? &pl->skel->nodes[tb->node] : NULL;
        const uint8_t *ring = nd ? pl->skel->materials[nd->material].ring_sides : NULL;
        const int o = nd && nd->order < 3 ? nd->order : 3;
        if (pl->model_sides && ring && ring[o] >= 3) sides = ring[o];
        int lobes = 0; /* a lobed ring needs four sides a lobe to show its lobes */
        for (uint32_t k = 0; k < tb->count; k++) lobes = p[k].lobes > lobes ? p[k].lobes : lobes;
        if (lobes && sides < 4 * lobes) sides = 4 * lobes < MESH_MAX_SIDES ? 4 * lobes : MESH_MAX_SIDES;
        tb->sides = (uint16_t)sides;
        if (!mesh_trig(pl, sides)) return false;
        tb->vert = pl->nverts;
        pl->nverts += (size_t)tb->count * (sides + 1) + (pl->caps ? 2 : 0);
        tb->run = (uint32_t)pl->nruns;
        uint32_t cap = pl->caps ? (uint32_t)sides : 0;
        if (!mesh_add_run(pl, p[1].mat, cap)) return false;
        for (uint32_t k = 1; k < tb->count; k++) {
            if (p[k].mat != pl->runs[pl->nruns - 1].mat && !mesh_add_run(pl, p[k].mat, 0)) return false;
            pl->runs[pl->nruns - 1].tris += 2 * (uint32_t)sides;
        }
        pl->runs[pl->nruns - 1].tris += cap;
    }
    return true;
}

/* ------------------------------------------------------------------ emission */

static inline void dir_len(const float *a, const float *b, vec3 d, float *len) {
    glm_vec3_sub((float *)b, (float *)a, d);
    *len = glm_vec3_norm(d);
    glm_vec3_scale(d, 1.0f / *len, d);
}

/* A lobed ring (Weber & Penn's trunk): vertex j at angle a_j = 2 pi j / S from ref moves out
 * to f = 1 + depth sin(lobes a_j) times its distance from the centre; its normal is the polar
 * curve's, (f w - f' w_perp) / |..| with f' = depth lobes cos(lobes a_j), still leaning back by
 * the taper's slope. */
static void lobe_ring(int lobes, float depth, int S, const MeshTrig *tr, v4f C, float ninv, v4f NT, const vec3 ref,
                      const vec3 bb, float *vp, float *vn) {
    const v4f R = {ref[0], ref[1], ref[2], 0}, B = {bb[0], bb[1], bb[2], 0};
    for (int j = 0; j < S; j++) {
        const float a = (float)lobes * TWO_PI * (float)j / (float)S;
        const float f = 1.0f + depth * sinf(a), df = depth * (float)lobes * cosf(a);
        v4f p = {0};
        memcpy(&p, vp + 3 * j, 3 * sizeof(float));
        p = C + f * (p - C);
        const float cj = tr->c[j], sj = tr->s[j];
        const v4f w = cj * R + sj * B, wp = cj * B - sj * R;
        const float inv = 1.0f / sqrtf(f * f + df * df);
        const v4f nv = NT + (ninv * inv) * (f * w - df * wp);
        memcpy(vp + 3 * j, &p, 3 * sizeof(float));
        memcpy(vn + 3 * j, &nv, 3 * sizeof(float));
    }
}

/* The trunk's jitter (SylMaterial.trunk_jitter): each vertex of the ring moves out by a factor
 * 1 + u, u uniform in [-k, k] from a stream keyed by the ring's point and the vertex, so
 * that the mesh is the same for any number of threads. Normals are kept. */
static void jitter_ring(float k, uint32_t ring, int S, v4f C, float *vp) {
    for (int j = 0; j < S; j++) {
        Rng r = rng_stream(0x0ca1e, ring, 0, (uint64_t)j);
        const float f = 1.0f + k * (float)(2 * rng_unit(&r) - 1);
        v4f p = {0};
        memcpy(&p, vp + 3 * j, 3 * sizeof(float));
        p = C + f * (p - C);
        memcpy(vp + 3 * j, &p, 3 * sizeof(float));
    }
}

static void emit_tube(const MeshPlan *pl, const MeshTube *tb, SylMesh *m) {
    const MeshPt *P = pl->pts + tb->first;
    const uint32_t n = tb->count;
    const int S = tb->sides, S1 = S + 1;
    const MeshTrig *tr = pl->trig[S];
    float *pos = m->pos + 3 * tb->vert, *nrm = m->nrm + 3 * tb->vert, *uv = m->uv + 2 * tb->vert;
    vec3 ref, tprev = {0}, din = {0}, dout, t0 = {0}, tk = {0};
    glm_vec3_copy((float *)tb->ref, ref);
    float lin = 0, lout, v = 0;
    const float tj = tb->node >= 0 ? pl->skel->materials[pl->skel->nodes[tb->node].material].trunk_jitter : 0;
    const float jitter = tb->node >= 0 && pl->skel->nodes[tb->node].order == 0 && isfinite(tj) ? tj : 0;
    /* an image's tiles (SylMaterial.tile): tu times around, tv times as often along */
    const SylMaterial *tm = tb->node >= 0 ? &pl->skel->materials[pl->skel->nodes[tb->node].material] : NULL;
    const bool tiled = tm && syl_material_image(pl->skel->images, tm);
    const float tu = tiled && tm->tile[0] > 0 ? tm->tile[0] : 1, tv = tiled && tm->tile[1] > 0 ? tm->tile[1] : 1;
    dir_len(P[0].p, P[1].p, dout, &lout);
    for (uint32_t k = 0; k < n; k++) {
        const bool inner = k > 0 && k + 1 < n;
        float mitre = 0;
        vec3 mdir = {0};
        if (k == 0) glm_vec3_copy(dout, tk);
        else if (!inner) glm_vec3_copy(din, tk);
        else {
            glm_vec3_add(din, dout, tk);
            float len = glm_vec3_norm(tk);
            if (len < 1e-3f) glm_vec3_copy(dout, tk);
            else {
                glm_vec3_scale(tk, 1.0f / len, tk);
                if (len < 1.9999f) { /* a bend: widen the ring in the bend plane */
                    mitre = MINF(2.0f / len, 2.0f) - 1.0f;
                    glm_vec3_sub(dout, din, mdir);
                    glm_vec3_normalize(mdir);
                }
            }
        }
        if (k > 0) { /* double reflection: frame at P[k-1] -> P[k] */
            vec3 v1, rl, tl, v2;
            glm_vec3_sub((float *)P[k].p, (float *)P[k - 1].p, v1);
            float c1 = glm_vec3_dot(v1, v1);
            glm_vec3_copy(ref, rl);
            glm_vec3_muladds(v1, -2.0f / c1 * glm_vec3_dot(v1, ref), rl);
            glm_vec3_copy(tprev, tl);
            glm_vec3_muladds(v1, -2.0f / c1 * glm_vec3_dot(v1, tprev), tl);
            glm_vec3_sub(tk, tl, v2);
            float c2 = glm_vec3_dot(v2, v2);
            glm_vec3_copy(rl, ref);
            if (c2 > 1e-12f) glm_vec3_muladds(v2, -2.0f / c2 * glm_vec3_dot(v2, rl), ref);
        }
        glm_vec3_muladds(tk, -glm_vec3_dot(ref, tk), ref); /* keep it exactly across */
        if (glm_vec3_norm(ref) < 1e-4f) any_perpendicular(tk, ref);
        glm_vec3_normalize(ref);
        vec3 bb;
        glm_vec3_cross(tk, ref, bb);
        if (k == 0) glm_vec3_copy(tk, t0);
        const float r = P[k].r;
        const float rp = k ? P[k - 1].r : r, rn = k + 1 < n ? P[k + 1].r : r;
        const float span = (k ? lin : 0) + (k + 1 < n ? lout : 0);
        float slope = span > 0 ? (rn - rp) / span : 0; /* dr/ds: the normal leans back on a taper */
        slope = MAXF(-4.f, MINF(4.f, slope));
        const float ninv = 1.0f / sqrtf(1.0f + slope * slope);
        if (k) v += lin / (TWO_PI * MAXF(0.5f * (rp + r), MAXF(pl->uv_rmin, 1e-6f)));
        const float rm = glm_vec3_dot(ref, mdir) * mitre, bm = glm_vec3_dot(bb, mdir) * mitre;
        /* vertex j: c + r (w + (w.m) mitre m), normal (w - slope t) / |..|, w = cos ref + sin bb */
        const v4f C = {P[k].p[0], P[k].p[1], P[k].p[2], 0};
        const v4f A = {r * ref[0], r * ref[1], r * ref[2], 0}, B = {r * bb[0], r * bb[1], r * bb[2], 0};
        const v4f M = {r * mdir[0], r * mdir[1], r * mdir[2], 0};
        const v4f NA = {ninv * ref[0], ninv * ref[1], ninv * ref[2], 0};
        const v4f NB = {ninv * bb[0], ninv * bb[1], ninv * bb[2], 0};
        const v4f NT = {-slope * ninv * tk[0], -slope * ninv * tk[1], -slope * ninv * tk[2], 0};
        float *vp = pos + 3 * (size_t)k * S1, *vn = nrm + 3 * (size_t)k * S1, *vt = uv + 2 * (size_t)k * S1;
        for (int j = 0; j < S; j++) { /* 4-wide stores run into the next vertex, written after */
            const float cj = tr->c[j], sj = tr->s[j], wm = cj * rm + sj * bm;
            const v4f p = C + cj * A + sj * B + wm * M, nv = NT + cj * NA + sj * NB;
            memcpy(vp + 3 * j, &p, sizeof p);
            memcpy(vn + 3 * j, &nv, sizeof nv);
            vt[2 * j] = tu * tr->u[j];
            vt[2 * j + 1] = tu * tv * v;
        }
        if (P[k].lobes) lobe_ring(P[k].lobes, P[k].lobe_depth * 1e-4f, S, tr, C, ninv, NT, ref, bb, vp, vn);
        if (jitter > 0) jitter_ring(jitter, tb->first + k, S, C, vp);
        memcpy(vp + 3 * S, vp, 3 * sizeof *vp); /* the seam */
        memcpy(vn + 3 * S, vn, 3 * sizeof *vn);
        vt[2 * S] = tu;
        vt[2 * S + 1] = tu * tv * v;
        glm_vec3_copy(tk, tprev);
        glm_vec3_copy(dout, din);
        lin = lout;
        if (k + 2 < n) dir_len(P[k + 1].p, P[k + 2].p, dout, &lout);
    }
    /* caps: a fan from a centre to the end ring, whose normals stay smooth (the tip looks
     * rounded, as with the hemispheres of Picek 2015, and costs two vertices) */
    const uint32_t v0 = (uint32_t)tb->vert;
    const uint32_t capv = v0 + n * (uint32_t)S1;
    if (pl->caps)
        for (int e = 0; e < 2; e++) {
            const size_t cv = (size_t)n * S1 + (size_t)e;
            const float *ax = e ? tk : t0, sg = e ? 1.f : -1.f;
            memcpy(pos + 3 * cv, P[e ? n - 1 : 0].p, 3 * sizeof *pos);
            for (int q = 0; q < 3; q++) nrm[3 * cv + q] = sg * ax[q];
            uv[2 * cv] = 0.5f * tu;
            uv[2 * cv + 1] = e ? tu * tv * v : 0;
        }
    /* triangles, run by run */
    const MeshRun *run = pl->runs + tb->run;
    uint32_t *ix = m->idx + run->idx;
    uint8_t cur = run->mat;
    if (pl->caps)
        for (uint32_t j = 0; j < (uint32_t)S; j++) *ix++ = capv, *ix++ = v0 + j + 1, *ix++ = v0 + j;
    for (uint32_t k = 0; k + 1 < n; k++) {
        if (P[k + 1].mat != cur) {
            run++;
            ix = m->idx + run->idx;
            cur = run->mat;
        }
        const uint32_t a = v0 + k * (uint32_t)S1, b = a + (uint32_t)S1;
        for (uint32_t j = 0; j < (uint32_t)S; j++) {
            ix[0] = a + j, ix[1] = a + j + 1, ix[2] = b + j;
            ix[3] = a + j + 1, ix[4] = b + j + 1, ix[5] = b + j;
            ix += 6;
        }
    }
    if (pl->caps) {
        const uint32_t last = v0 + (n - 1) * (uint32_t)S1;
        for (uint32_t j = 0; j < (uint32_t)S; j++) *ix++ = capv + 1, *ix++ = last + j, *ix++ = last + j + 1;
    }
}

typedef struct Work {
    const MeshPlan *pl;
    SylMesh *m;
    size_t tube0, tube1;
    size_t item0, item1;
} Work;

/* The runs of tube t: up to the next tube's, or the first item's. */
static size_t tube_runs_end(const MeshPlan *pl, size_t t) {
    return t + 1 < pl->ntubes ? pl->tubes[t + 1].run : (pl->nitems ? pl->items[0].run : pl->nruns);
}

static void work_run(const Work *w) {
    const MeshPlan *pl = w->pl;
    MeshFirstUse fu = {0};
    for (size_t t = w->tube0; t < w->tube1; t++) {
        const MeshTube *tb = &pl->tubes[t];
        emit_tube(pl, tb, w->m);
        mesh_first_use(&fu, w->m, tb->vert, (size_t)tb->count * (tb->sides + 1u) + (pl->caps ? 2 : 0),
                       pl->runs + tb->run, tube_runs_end(pl, t) - tb->run);
    }
    for (size_t i = w->item0; i < w->item1; i++) {
        const MeshItem *it = &pl->items[i];
        mesh_emit_item(pl, it, w->m);
        mesh_first_use(&fu, w->m, it->vert, it->verts, pl->runs + it->run, 1);
    }
    mesh_first_use_free(&fu);
}

static void work_chunk(void *works, int k) { work_run((const Work *)works + k); }

static size_t piece_tris(const MeshPlan *pl, size_t run0, size_t run1) {
    size_t n = 0;
    for (size_t r = run0; r < run1; r++) n += pl->runs[r].tris;
    return n;
}

/* Split the pieces into nthreads ranges of about the same number of triangles. */
static void emit_all(const MeshPlan *pl, SylMesh *m, int nthreads) {
    size_t total = nthreads > 1 ? piece_tris(pl, 0, pl->nruns) : 0;
    if (total < 50000) nthreads = 1;
    if (nthreads <= 1) {
        Work w = {pl, m, 0, pl->ntubes, 0, pl->nitems};
        work_run(&w);
        return;
    }
    Work *w = calloc((size_t)nthreads, sizeof *w);
    if (!w) {
        Work one = {pl, m, 0, pl->ntubes, 0, pl->nitems};
        work_run(&one);
        return;
    }
    /* pieces in order: tubes, then items; each range gets total / nthreads triangles */
    size_t npieces = pl->ntubes + pl->nitems, p = 0, acc = 0;
    for (int t = 0; t < nthreads; t++) {
        size_t want = total * (size_t)(t + 1) / (size_t)nthreads, from = p;
        while (p < npieces && (acc < want || t == nthreads - 1)) {
            size_t r0, r1;
            if (p < pl->ntubes) {
                r0 = pl->tubes[p].run;
                r1 = tube_runs_end(pl, p);
            } else {
                r0 = pl->items[p - pl->ntubes].run;
                r1 = r0 + 1;
            }
            acc += piece_tris(pl, r0, r1);
            p++;
        }
        w[t].pl = pl;
        w[t].m = m;
        w[t].tube0 = from < pl->ntubes ? from : pl->ntubes;
        w[t].tube1 = p < pl->ntubes ? p : pl->ntubes;
        w[t].item0 = from > pl->ntubes ? from - pl->ntubes : 0;
        w[t].item1 = p > pl->ntubes ? p - pl->ntubes : 0;
        if (w[t].item1 < w[t].item0) w[t].item1 = w[t].item0;
    }
    par_run(nthreads, work_chunk, w);
    free(w);
}

/* ------------------------------------------------------------------ build */

/* Place every run in SylMesh.idx, grouped by material in increasing order. */
static bool place_runs(MeshPlan *pl, SylMesh *m) {
    size_t per[256] = {0}, start[256];
    for (size_t r = 0; r < pl->nruns; r++) per[pl->runs[r].mat] += 3 * (size_t)pl->runs[r].tris;
    size_t at = 0;
    int ng = 0;
    for (int k = 0; k < 256; k++) {
        start[k] = at;
        at += per[k];
        if (per[k]) ng++;
    }
    if (at > UINT32_MAX) return false; /* SylMeshGroup counts are 32 bits */
    m->nidx = at;
    m->groups = calloc(ng ? (size_t)ng : 1, sizeof *m->groups);
    if (!m->groups) return false;
    for (int k = 0; k < 256; k++)
        if (per[k]) m->groups[m->ngroups++] = (SylMeshGroup){(uint32_t)start[k], (uint32_t)per[k], (uint8_t)k};
    for (size_t r = 0; r < pl->nruns; r++) {
        pl->runs[r].idx = start[pl->runs[r].mat];
        start[pl->runs[r].mat] += 3 * (size_t)pl->runs[r].tris;
    }
    return true;
}

/* Each vertex's node: a tube's last node, an organ's or a polygon's. */
static bool fill_nodes(const MeshPlan *pl, SylMesh *m) {
    if (!(m->node = malloc((m->nverts ? m->nverts : 1) * sizeof *m->node))) return false;
    for (size_t v = 0; v < m->nverts; v++) m->node[v] = -1;
    for (size_t t = 0; t < pl->ntubes; t++) {
        const MeshTube *tb = &pl->tubes[t];
        size_t n = (size_t)tb->count * (tb->sides + 1u) + (pl->caps ? 2 : 0);
        for (size_t v = 0; v < n; v++) m->node[tb->vert + v] = tb->node;
    }
    for (size_t i = 0; i < pl->nitems; i++)
        for (uint32_t v = 0; v < pl->items[i].verts; v++) m->node[pl->items[i].vert + v] = pl->items[i].node;
    return true;
}


/* The materials of the leaves and petals made with one face (cards are one face anyway). */
static void mark_double_sided(const MeshPlan *pl, SylMesh *m) {
    if (!pl->one_sided) return;
    for (size_t i = 0; i < pl->nitems; i++) {
        const MeshItem *it = &pl->items[i];
        if (it->poly) continue;
        const SylOrgan *o = &pl->skel->organs[it->index];
        if (o->kind == SYL_KIND_FLOWER || (o->kind == SYL_KIND_LEAF && pl->leaves != SYL_LEAVES_CARDS))
            m->double_sided[o->material] = 1;
    }
}

static int ncpu(void) {
    int n = par_threads(0);
    return n > 64 ? 64 : n;
}

/* Defaults filled in and checked: SYL_OK, or the status of the (reported) problem. */
static int resolve_options(const SylSkeleton *s, const SylMeshOptions *opt, SylMeshOptions *o) {
    *o = opt ? *opt : (SylMeshOptions){0};
    if (o->sides == 0) o->sides = 8;
    if (o->min_sides == 0) o->min_sides = 3;
    if (o->pipe_exponent == 0) o->pipe_exponent = 2.0f;
    if (o->sides < 3 || o->sides > MESH_MAX_SIDES || o->min_sides < 3 || o->min_sides > MESH_MAX_SIDES) {
        diag(o, "sides must be from 3 to 256");
        return SYL_EUSAGE;
    }
    if (o->min_sides > o->sides) o->min_sides = o->sides;
    if (o->radius != SYL_RADIUS_MODEL && o->radius != SYL_RADIUS_PIPE) {
        diag(o, "unknown radius model");
        return SYL_EUSAGE;
    }
    if (!(o->pipe_exponent >= 0.5f && o->pipe_exponent <= 10.f) || !(o->tip_radius >= 0) || !isfinite(o->tip_radius)) {
        diag(o, "the pipe exponent must be from 0.5 to 10 and the tip radius positive");
        return SYL_EUSAGE;
    }
    for (size_t i = 0; i < s->nnodes; i++)
        if (s->nodes[i].parent < -1 || s->nodes[i].parent >= (int32_t)i) {
            sink_error(opt_sink(o), "mesh: node %zu has parent %d: parents must come before their children", i,
                       s->nodes[i].parent);
            return SYL_EMODEL;
        }
    return SYL_OK;
}

static void radii(const SylSkeleton *s, const SylMeshOptions *o, float *rad) {
    if (o->radius == SYL_RADIUS_PIPE) pipe_radii(s, o->pipe_exponent, o->tip_radius, rad);
    else
        for (size_t i = 0; i < s->nnodes; i++) rad[i] = s->nodes[i].radius;
}

int syl_mesh_radii(const SylSkeleton *s, const SylMeshOptions *opt, float *radius) {
    SylMeshOptions o;
    int status = resolve_options(s, opt, &o);
    if (!status) radii(s, &o, radius);
    return status;
}

/* The material of the first leaf with an outline of its own (NULL: none): a mesh's cards share
 * one texture, so they draw that one outline. */
static const SylMaterial *own_leaf_material(const SylSkeleton *s) {
    for (size_t i = 0; i < s->norgans; i++)
        if (s->organs[i].kind == SYL_KIND_LEAF && mesh_own_leaf(&s->materials[s->organs[i].material]))
            return &s->materials[s->organs[i].material];
    return NULL;
}

/* The card shape of a material with an outline of its own. */
static int own_card(const SylMaterial *m) {
    return LEAF_OUTLINE_CARD(m->leaf_outline, m->leaf_tris < LEAF_OUTLINE_CARD_MAX_TRIS ? m->leaf_tris
                                                                                       : LEAF_OUTLINE_CARD_MAX_TRIS);
}

int syl_mesh_card_shape(const SylMesh *m, int material) {
    int c = m->leaves == SYL_LEAVES_CARDS ? m->card_shape[(uint8_t)material] : 0;
    return c ? c - 1 : m->leaf_shape;
}

int syl_mesh_build(const SylSkeleton *s, const SylMeshOptions *opt, SylMesh **out) {
    *out = NULL;
    SylMeshOptions o;
    int status = resolve_options(s, opt, &o);
    if (status) return status;
    if (syl_cancelled(o.cancel)) return SYL_ECANCELED;
    MeshPlan pl = {.skel = s, .sides = o.sides, .min_sides = o.min_sides, .caps = o.caps != -1,
                   .one_sided = o.one_sided != 0, .model_sides = !opt || opt->sides == 0};
    pl.sphere_stacks = o.sides / 2 > 3 ? o.sides / 2 : 3;
    pl.leaves = o.leaves;
    pl.leaf_shape = o.leaf_shape;
    const SylMaterial *leafm = own_leaf_material(s);
    if (leafm) pl.leaf_shape = own_card(leafm); /* cards and clusters draw the leaves' own outline */
    pl.cluster_shape = pl.leaf_shape;
    pl.cluster_leaves = o.cluster_leaves > 0 ? o.cluster_leaves : SYL_CLUSTER_LEAVES;
    SylMesh *m = calloc(1, sizeof *m);
    float *rad = NULL;
    if (!m || !mesh_store(m)) goto oom;
    /* the budget is the caller's, or one of max_memory for this mesh alone */
    Budget own, *mem = budget_use(&own, o.max_memory, o.budget);
    /* planning holds a radius and a few words per node; the mesh itself is counted once
     * its size is known, before a byte of it is allocated */
    uint64_t plan_bytes = (uint64_t)s->nnodes * 64 + (uint64_t)s->norgans * 32 + (uint64_t)s->npolys * 32;
    if (!budget_charge(mem, plan_bytes)) {
        sink_error(opt_sink(&o), "meshing %zu nodes would need more than the %llu MB that --max-memory "
                            "allows; raise the limit with --max-memory",
                    s->nnodes, (unsigned long long)budget_limit_mb(mem));
        status = SYL_ELIMIT;
        goto done;
    }
    rad = malloc((s->nnodes ? s->nnodes : 1) * sizeof *rad);
    if (!rad) goto oom_plan;
    radii(s, &o, rad);
    if (!plan_tubes(&pl, rad) || !size_tubes(&pl) || !mesh_plan_shapes(&pl)) goto oom_plan;
    budget_release(mem, plan_bytes);
    plan_bytes = 0;
    if (syl_cancelled(o.cancel)) { /* before the mesh's memory is taken and written */
        status = SYL_ECANCELED;
        goto done;
    }
    if (pl.nverts > UINT32_MAX) {
        diag(&o, "more than 2^32 vertices");
        status = SYL_ELIMIT;
        goto done;
    }
    size_t ntris = 0;
    for (size_t r = 0; r < pl.nruns; r++) ntris += (size_t)pl.runs[r].tris;
    uint64_t bytes = (uint64_t)pl.nverts * 8 * sizeof(float) + (uint64_t)ntris * 3 * sizeof(uint32_t);
    if (!budget_charge(mem, bytes)) { /* "in all": a budget other engines share */
        sink_error(opt_sink(&o), "the mesh would need %zu triangles (%llu MB), more than --max-memory "
                            "allows (%llu MB%s); raise the limit with --max-memory, or use fewer --sides",
                    ntris, (unsigned long long)(bytes >> 20), (unsigned long long)budget_limit_mb(mem),
                    o.budget ? " in all" : "");
        status = SYL_ELIMIT;
        goto done;
    }
    if (o.budget) m->store->budget = o.budget, m->store->charged = bytes;
    if (!place_runs(&pl, m)) goto oom;
    m->nverts = pl.nverts;
    size_t nv = pl.nverts ? pl.nverts : 1;
    /* the four arrays in one block (each on a 64-byte line): on huge pages, 2 MB zeroed per
     * 2 MB used instead of a page of its own for each (util/pages.h) */
    size_t at3 = (nv * 3 * sizeof(float) + 63) & ~(size_t)63, at2 = (nv * 2 * sizeof(float) + 63) & ~(size_t)63;
    char *block = pages_owned(2 * at3 + at2 + (m->nidx ? m->nidx : 1) * sizeof *m->idx, PAGES_OWNED_KEPT);
    if (!block) goto oom;
    m->store->block = block;
    m->pos = (float *)block, m->nrm = (float *)(block + at3), m->uv = (float *)(block + 2 * at3);
    m->idx = (uint32_t *)(block + 2 * at3 + at2);
    memcpy(m->materials, s->materials, sizeof m->materials);
    m->nmaterials = s->nmaterials;
    m->images = syl_images_ref(s->images);
    mark_double_sided(&pl, m);
    snprintf(m->name, sizeof m->name, "%s", s->name);
    m->leaves = (uint8_t)o.leaves;
    m->leaf_shape = (uint8_t)pl.cluster_shape;
    for (size_t i = 0; i < s->norgans && o.leaves == SYL_LEAVES_CARDS; i++) { /* each leaf material's cards */
        const SylMaterial *k = &s->materials[s->organs[i].material];
        if (s->organs[i].kind == SYL_KIND_LEAF)
            m->card_shape[s->organs[i].material] = (uint8_t)(1 + (mesh_own_leaf(k) ? own_card(k) : o.leaf_shape));
    }
    emit_all(&pl, m, o.threads > 0 ? o.threads : ncpu());
    if (o.vertex_nodes && !fill_nodes(&pl, m)) goto oom;
    goto done;
oom_plan:
    budget_release(mem, plan_bytes);
oom:
    diag(&o, "out of memory");
    status = SYL_ELIMIT;
done:
    free(rad);
    plan_free(&pl);
    if (status) syl_mesh_free(m);
    else *out = m;
    return status;
}
