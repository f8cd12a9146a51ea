/* syl_render_draw_instances: a forest as Embree instances of a few prototype scenes over a ground
 * mesh, culled to the view and coarser far away; shaded by shade.c like any render. */

/* Each prototype (and its coarse level) is one Embree scene built once; a copy is an
 * instance geometry of it with its own transform, so 100,000 plants cost 100,000 small
 * records rather than their triangles. Instances get geometry IDs from their order in the
 * caller's array, so the BVH and the picture do not depend on the threads. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "render/scene.h"
#include "mesh/store.h"
#include "util/budget.h"
#include "util/coord.h"
#include "util/diag.h"

typedef struct Proto {
    RTCScene scene[2];   /* full, coarse (NULL: none) */
    const SylMesh *mesh[2];
    float c[3], r, height; /* bounding sphere of the full mesh (model units), its height */
} Proto;

typedef struct Work {
    Scene *s;
    Proto *pr;
    int npr;
    float *pos_copy[2 * 256 + 1];
    int ncopies;
    AlphaTest *alpha[2 * 256]; /* per level mesh: its leaf cards' alpha test (NULL: none) */
    uint8_t **tri_mat;        /* per level mesh: 2 * npr */
    float (*lin)[256][3];
    uint8_t (*kind)[256];
    int8_t (*img)[256];       /* per level mesh and material: its image in s->img, -1 none */
    const SylImage *image[SYL_IMAGES_MAX]; /* s->img[k]'s file: the looks' images, each once */
    int nimages;
    const SylMesh **level;    /* 2 * npr: the mesh of proto p at level k is level[2p + k] */
    uint32_t *inst_proto;
    float (*inst_cs)[2];
    float *inst_scale;
} Work;

static void camera_of(const SylRenderCamera *c, int width, int height, RenderCamera *cam) {
    memset(cam, 0, sizeof *cam);
    memcpy(cam->eye, c->eye, sizeof cam->eye);
    float f[3] = {c->target[0] - c->eye[0], c->target[1] - c->eye[1], c->target[2] - c->eye[2]};
    normalize3(f);
    if (!(fabsf(f[1]) < 0.9999f)) f[0] += 1e-3f, normalize3(f); /* straight down: any right will do */
    float r[3] = {-f[2], 0, f[0]}; /* f x (0, 1, 0) */
    normalize3(r);
    float u[3] = {r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]};
    memcpy(cam->fwd, f, sizeof f), memcpy(cam->right, r, sizeof r), memcpy(cam->up, u, sizeof u);
    float fov = c->fov > 1 && c->fov < 170 ? c->fov : 45;
    cam->tany = tanf(fov * 0.5f * (float)M_PI / 180);
    cam->tanx = cam->tany * (float)width / (float)height;
    cam->width = width, cam->height = height;
}

bool syl_render_project(const SylRenderCamera *c, int width, int height, const float p[3], float *x, float *y) {
    RenderCamera cam;
    camera_of(c, width, height, &cam);
    return render_project(&cam, p, x, y);
}

/* m's scene; with tri_mat (a prototype's level), its leaf cards alpha-tested through *alpha. */
static RTCScene mesh_scene(Work *w, RTCDevice dev, const SylMesh *m, const uint8_t *tri_mat, AlphaTest **alpha) {
    RTCScene sc = rtcNewScene(dev);
    size_t ntri = m->nidx / 3;
    if (ntri && m->nverts) {
        const float *pos = m->pos;
        if (!mesh_has_spare(m)) { /* Embree reads 16 bytes at a time: room past the end */
            float *cp = malloc((m->nverts * 3 + 4) * sizeof(float));
            if (!cp) {
                rtcReleaseScene(sc);
                return NULL;
            }
            memcpy(cp, m->pos, m->nverts * 3 * sizeof(float));
            memset(cp + m->nverts * 3, 0, 4 * sizeof(float));
            w->pos_copy[w->ncopies++] = cp;
            pos = cp;
        }
        RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, pos, 0, 3 * sizeof(float), m->nverts);
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m->idx, 0, 3 * sizeof(uint32_t), ntri);
        if (tri_mat && render_alpha_attach(m, tri_mat, NULL, g, alpha)) {
            rtcReleaseGeometry(g);
            rtcReleaseScene(sc);
            return NULL;
        }
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(sc, g, 0);
        rtcReleaseGeometry(g);
    }
    rtcCommitScene(sc);
    return sc;
}

static uint8_t *triangle_materials(const SylMesh *m) {
    size_t ntri = m->nidx / 3;
    uint8_t *t = calloc(ntri ? ntri : 1, 1);
    if (!t) return NULL;
    for (int g = 0; g < m->ngroups; g++)
        for (size_t i = m->groups[g].first / 3; i < (m->groups[g].first + m->groups[g].count) / 3 && i < ntri; i++)
            t[i] = m->groups[g].material;
    return t;
}

static bool mesh_ok(const SylMesh *m, const SylSink *sink) {
    if (!m) return true;
    for (size_t i = 0; i < m->nidx; i++)
        if (m->idx[i] >= m->nverts) {
            sink_error(sink, "render: mesh index %u out of range", m->idx[i]);
            return false;
        }
    return m->nidx / 3 <= 0xffffffffu && coord_check(m->pos, m->nverts, 3, "the model", sink);
}

/* Is the sphere (centre q, radius r) in the camera's view? */
static bool in_view(const RenderCamera *cam, const float q[3], float r) {
    float d[3] = {q[0] - cam->eye[0], q[1] - cam->eye[1], q[2] - cam->eye[2]};
    float z = dot3(d, cam->fwd), x = dot3(d, cam->right), y = dot3(d, cam->up);
    if (z < -r) return false;
    return fabsf(x) - z * cam->tanx <= r * sqrtf(1 + cam->tanx * cam->tanx) &&
           fabsf(y) - z * cam->tany <= r * sqrtf(1 + cam->tany * cam->tany);
}

static void proto_bounds(Proto *p, const SylMesh *m) {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < m->nverts; i++)
        for (int c = 0; c < 3; c++) lo[c] = fminf(lo[c], m->pos[3 * i + c]), hi[c] = fmaxf(hi[c], m->pos[3 * i + c]);
    if (!m->nverts) memset(lo, 0, sizeof lo), memset(hi, 0, sizeof hi);
    float e[3];
    for (int c = 0; c < 3; c++) p->c[c] = 0.5f * (lo[c] + hi[c]), e[c] = 0.5f * (hi[c] - lo[c]);
    p->r = sqrtf(dot3(e, e));
    p->height = hi[1] - lo[1];
}

static void work_free(Work *w) {
    Scene *s = w->s;
    for (int p = 0; w->pr && p < w->npr; p++)
        for (int k = 0; k < 2; k++)
            if (w->pr[p].scene[k]) rtcReleaseScene(w->pr[p].scene[k]);
    for (int i = 0; i < w->ncopies; i++) free(w->pos_copy[i]);
    for (int i = 0; i < 2 * w->npr; i++) render_alpha_free(w->alpha[i]);
    for (int i = 0; w->tri_mat && i < 2 * w->npr; i++) free(w->tri_mat[i]);
    free(w->tri_mat), free(w->lin), free(w->kind), free(w->img), free(w->level), free(w->pr);
    free(w->inst_proto), free(w->inst_cs), free(w->inst_scale);
    if (s) render_scene_free(s);
}

/* The index in s->img of the image material i of m wears, decoded the first time (the looks
 * of one model read the same file each: the same bytes are one texture); -1: none, or no
 * room (its procedural texture then). SYL_ELIMIT in *st when it cannot be decoded. */
static int proto_image(Work *w, const SylMesh *m, int i, int *st) {
    int j = render_material_image(m, i);
    if (j < 0) return -1;
    const SylImage *g = &m->images->img[j];
    int k = 0;
    while (k < w->nimages && !(w->image[k]->len == g->len && !memcmp(w->image[k]->png, g->png, g->len))) k++;
    if (k == w->nimages) {
        if (k == SYL_IMAGES_MAX) return -1;
        if ((*st = render_image_texture(&w->s->img[k], g, NULL))) return -1;
        w->image[w->nimages++] = g;
    }
    return k;
}

/* The prototypes' scenes and their materials. */
static int build_protos(Work *w, const SylRenderProto *protos, int nprotos) {
    w->npr = nprotos;
    w->pr = calloc((size_t)nprotos + 1, sizeof *w->pr);
    w->tri_mat = calloc(2 * (size_t)nprotos + 1, sizeof *w->tri_mat);
    w->lin = calloc(2 * (size_t)nprotos + 1, sizeof *w->lin);
    w->kind = calloc(2 * (size_t)nprotos + 1, sizeof *w->kind);
    w->img = calloc(2 * (size_t)nprotos + 1, sizeof *w->img);
    w->level = calloc(2 * (size_t)nprotos + 1, sizeof *w->level);
    if (!w->pr || !w->tri_mat || !w->lin || !w->kind || !w->img || !w->level) return SYL_ELIMIT;
    for (int p = 0; p < nprotos; p++) {
        Proto *pr = &w->pr[p];
        pr->mesh[0] = protos[p].mesh;
        pr->mesh[1] = protos[p].coarse;
        proto_bounds(pr, protos[p].mesh);
        for (int k = 0; k < 2; k++) {
            const SylMesh *m = pr->mesh[k];
            if (!m) continue;
            w->level[2 * p + k] = m;
            for (int i = 0; i < 256; i++) {
                int st = SYL_OK, j = proto_image(w, m, i, &st);
                if (st) return st;
                w->img[2 * p + k][i] = (int8_t)j;
                /* an image of the model's own is the colour itself (white times the image) */
                for (int c = 0; c < 3; c++) w->lin[2 * p + k][i][c] = j >= 0 ? 1 : srgb_to_linear(m->materials[i].rgb[c]);
                w->kind[2 * p + k][i] = m->materials[i].kind;
            }
        }
    }
    return SYL_OK;
}

/* Level k of prototype p as a scene, built when a plant in view first wants it: a forest's
 * looks cover every species, age class and variant, and a view shows few of them. */
static RTCScene proto_scene(Work *w, int p, int k) {
    Proto *pr = &w->pr[p];
    if (pr->scene[k]) return pr->scene[k];
    if (!(w->tri_mat[2 * p + k] = triangle_materials(pr->mesh[k]))) return NULL;
    return pr->scene[k] = mesh_scene(w, w->s->dev, pr->mesh[k], w->tri_mat[2 * p + k], &w->alpha[2 * p + k]);
}

/* The instances in view, each at its level, into the top scene after the ground (ID 0). */
static int place(Work *w, const SylRenderInstance *inst, size_t n, SylRenderCounts *counts) {
    Scene *s = w->s;
    w->inst_proto = malloc((n + 1) * sizeof *w->inst_proto);
    w->inst_cs = malloc((n + 1) * sizeof *w->inst_cs);
    w->inst_scale = malloc((n + 1) * sizeof *w->inst_scale);
    if (!w->inst_proto || !w->inst_cs || !w->inst_scale) return SYL_ELIMIT;
    unsigned id = 1;
    for (size_t i = 0; i < n; i++) {
        const SylRenderInstance *a = &inst[i];
        Proto *pr = &w->pr[a->proto];
        float c = cosf(a->yaw), sn = sinf(a->yaw), k = a->scale;
        float q[3] = {a->t[0] + k * (c * pr->c[0] + sn * pr->c[2]), a->t[1] + k * pr->c[1],
                      a->t[2] + k * (-sn * pr->c[0] + c * pr->c[2])};
        /* grown by the height: the copy's shadow may fall into the view */
        if (!(k > 0) || !pr->mesh[0]->nidx || !in_view(&s->cam, q, k * (pr->r + pr->height))) {
            counts->culled++;
            continue;
        }
        float z = dot3((float[3]){q[0] - s->cam.eye[0], q[1] - s->cam.eye[1], q[2] - s->cam.eye[2]}, s->cam.fwd);
        float rows = z > 0 ? k * pr->height / (2 * z * s->cam.tany) * (float)s->full_h : INFINITY;
        int level = pr->mesh[1] && rows < SYL_RENDER_COARSE_PX ? 1 : 0;
        RTCScene proto = proto_scene(w, (int)a->proto, level);
        if (!proto) return SYL_ELIMIT;
        counts->coarse += (size_t)level;
        counts->drawn++;
        float xfm[12] = {k * c, 0, -k * sn, 0, k, 0, k * sn, 0, k * c, a->t[0], a->t[1], a->t[2]};
        RTCGeometry g = rtcNewGeometry(s->dev, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(g, proto);
        rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(s->scene, g, id);
        rtcReleaseGeometry(g);
        w->inst_proto[id] = 2 * a->proto + (uint32_t)level;
        w->inst_cs[id][0] = c, w->inst_cs[id][1] = sn;
        w->inst_scale[id] = k;
        id++;
    }
    s->proto = w->level;
    s->proto_tri_mat = w->tri_mat;
    s->proto_lin = w->lin;
    s->proto_kind = w->kind;
    s->proto_img = w->img;
    s->inst_proto = w->inst_proto;
    s->inst_cs = (const float(*)[2])w->inst_cs;
    s->inst_scale = w->inst_scale;
    return SYL_OK;
}

static int check(const SylMesh *ground, const SylRenderProto *protos, int nprotos, const SylRenderInstance *inst,
                 size_t n, const SylRenderOptions *opt, const int (*windows)[4], int nwindows, uint64_t *pixels) {
    SylSink text;
    const SylSink *sink = diag_sink(&text, opt->diag, opt->sink);
    int W = opt->width > 0 ? opt->width : 1024, H = opt->height > 0 ? opt->height : 1024;
    if (opt->width < 0 || opt->height < 0 || W > 65536 || H > 65536 || (size_t)W * (size_t)H > (size_t)1 << 28) {
        sink_error(sink, "render: picture size %d x %d out of range", W, H);
        return SYL_EUSAGE;
    }
    if (nwindows < 0 || (nwindows && !windows)) {
        sink_error(sink, "render: %d windows", nwindows);
        return SYL_EUSAGE;
    }
    *pixels = nwindows ? 0 : (uint64_t)W * (uint64_t)H;
    for (int k = 0; k < nwindows; k++) {
        const int *win = windows[k];
        if (win[0] < 0 || win[1] < 0 || win[2] > W || win[3] > H || win[0] >= win[2] || win[1] >= win[3]) {
            if (sink)
                sink_error(sink, "render: window %d,%d..%d,%d is not inside the %d x %d picture", win[0],
                        win[1], win[2], win[3], W, H);
            return SYL_EUSAGE;
        }
        *pixels += (uint64_t)(win[2] - win[0]) * (uint64_t)(win[3] - win[1]);
    }
    if (nprotos < 0 || nprotos > 256) {
        sink_error(sink, "render: %d prototypes (at most 256)", nprotos);
        return SYL_EUSAGE;
    }
    if (!mesh_ok(ground, sink)) return SYL_EMODEL;
    for (int p = 0; p < nprotos; p++)
        if (!protos[p].mesh || !mesh_ok(protos[p].mesh, sink) || !mesh_ok(protos[p].coarse, sink)) {
            if (sink && !protos[p].mesh) sink_error(sink, "render: prototype %d has no mesh", p);
            return SYL_EMODEL;
        }
    for (size_t i = 0; i < n; i++)
        if (inst[i].proto >= (uint32_t)nprotos || !isfinite(inst[i].t[0]) || !isfinite(inst[i].t[1]) ||
            !isfinite(inst[i].t[2]) || !isfinite(inst[i].yaw) || !isfinite(inst[i].scale)) {
            sink_error(sink, "render: instance %zu is malformed", i);
            return SYL_EUSAGE;
        }
    return SYL_OK;
}

/* The lights and the scale: the ground's bounds for the fog, a plant's size for the rest. */
static void lighting(Scene *s, const SylMesh *ground, const SylRenderInstance *inst, size_t n) {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; ground && i < ground->nverts; i++)
        for (int c = 0; c < 3; c++) lo[c] = fminf(lo[c], ground->pos[3 * i + c]), hi[c] = fmaxf(hi[c], ground->pos[3 * i + c]);
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) lo[c] = fminf(lo[c], inst[i].t[c]), hi[c] = fmaxf(hi[c], inst[i].t[c]);
    if (!(lo[0] <= hi[0])) memset(lo, 0, sizeof lo), memset(hi, 0, sizeof hi);
    memcpy(s->cam.lo, lo, sizeof lo), memcpy(s->cam.hi, hi, sizeof hi);
    render_set_lighting(s);
    float reach = fmaxf(fmaxf(fabsf(lo[0]), fabsf(hi[0])), fmaxf(fabsf(lo[2]), fabsf(hi[2])));
    s->eps = 2e-3f + 4e-6f * reach; /* twigs are centimetres thick whatever the terrain's size */
    s->ao_dist = 4;                  /* metres: the occlusion of neighbours, not of hills */
    s->pixel_angle = 2 * s->cam.tany / (float)s->full_h;
    s->shadow_far = 4 * s->size + 1000;
}

int syl_render_draw_instances(const SylMesh *ground, const SylRenderProto *protos, int nprotos,
                              const SylRenderInstance *inst, size_t n, const SylRenderCamera *cam,
                              const SylRenderOptions *opt, const int (*windows)[4], int nwindows, uint8_t *rgb,
                              SylRenderCounts *counts) {
    static const SylRenderOptions defaults = {0};
    if (!opt) opt = &defaults;
    SylRenderCounts own_counts;
    if (!counts) counts = &own_counts;
    memset(counts, 0, sizeof *counts);
    SylSink text;
    const SylSink *sink = diag_sink(&text, opt->diag, opt->sink);
    uint64_t pixels;
    int status = check(ground, protos, nprotos, inst, n, opt, windows, nwindows, &pixels);
    if (status) return status;
    Budget own, *mem = budget_use(&own, opt->max_memory, opt->budget);
    uint64_t tris = ground ? ground->nidx / 3 : 0;
    for (int p = 0; p < nprotos; p++) tris += protos[p].mesh->nidx / 3 + (protos[p].coarse ? protos[p].coarse->nidx / 3 : 0);
    uint64_t need = tris * 150 + (uint64_t)n * 600 + pixels * 3 + (uint64_t)nprotos * (2u << 17) + (8u << 20);
    if (!budget_charge(mem, need)) {
        sink_error(sink, "rendering %zu instances would need about %llu MB, more than --max-memory "
                               "allows (%llu MB in all); raise the limit with --max-memory\n",
                    n, (unsigned long long)(need >> 20), (unsigned long long)budget_limit_mb(mem));
        return SYL_ELIMIT;
    }
    Work w = {0};
    Scene *s = w.s = calloc(1, sizeof *s);
    status = s ? SYL_OK : SYL_ELIMIT;
    int threads = opt->threads > 0 ? opt->threads : render_cpu_count();
    if (threads > 256) threads = 256;
    if (!status) {
        int W = opt->width > 0 ? opt->width : 1024, H = opt->height > 0 ? opt->height : 1024;
        s->m = ground;
        s->full_w = W, s->full_h = H;
        s->ground = false, s->unlit = opt->unlit;
        s->samples = opt->samples > 0 ? (opt->samples > MAX_SAMPLES ? MAX_SAMPLES : opt->samples) : 4;
        int ao = opt->ao_samples < 0 ? 0 : opt->ao_samples == 0 ? 8 : opt->ao_samples > MAX_AO ? MAX_AO : opt->ao_samples;
        s->ao = ao ? (ao + s->samples - 1) / s->samples : 0;
        s->shadows = opt->shadows;
        camera_of(cam, W, H, &s->cam);
        lighting(s, ground, inst, n);
        char config[64];
        snprintf(config, sizeof config, "threads=%d,verbose=0", threads);
        s->dev = rtcNewDevice(config);
        if (!s->dev) status = SYL_ELIMIT;
    }
    if (!status) {
        rtcSetDeviceErrorFunction(s->dev, render_embree_error, (void *)sink);
        for (int k = 0; k < 4 && !status; k++)
            if (!texture_build(&s->tex[k], k == 3 ? -1 : k, TEX_SIZE)) status = SYL_ELIMIT;
    }
    if (!status) status = build_protos(&w, protos, nprotos);
    if (!status) {
        s->scene = rtcNewScene(s->dev);
        if (ground && ground->nidx) {
            if (!(s->tri_mat = triangle_materials(ground))) status = SYL_ELIMIT;
            RTCScene g = status ? NULL : mesh_scene(&w, s->dev, ground, NULL, NULL);
            if (!status && !g) status = SYL_ELIMIT;
            if (g) { /* the ground as an instance of itself would cost a level: its geometry, directly */
                RTCGeometry geo = rtcGetGeometry(g, 0);
                rtcAttachGeometryByID(s->scene, geo, 0);
                rtcReleaseScene(g);
            }
        }
    }
    if (!status) status = place(&w, inst, n, counts);
    if (!status) {
        rtcCommitScene(s->scene);
        if (rtcGetDeviceError(s->dev) != RTC_ERROR_NONE) status = SYL_ELIMIT;
    }
    if (status == SYL_ELIMIT) sink_error(sink, "render: out of memory");
    const int whole[1][4] = {{0, 0, s ? s->full_w : 0, s ? s->full_h : 0}};
    if (!nwindows) windows = whole, nwindows = 1;
    for (int k = 0; !status && k < nwindows; k++) { /* each window on the one scene */
        const int *win = windows[k];
        s->ox = win[0], s->oy = win[1];
        s->width = win[2] - win[0], s->height = win[3] - win[1];
        s->out = rgb;
        rgb += (size_t)s->width * (size_t)s->height * 3;
        atomic_store(&s->next_tile, 0);
        atomic_store(&s->tiles_done, 0);
        render_all_tiles(s, threads, opt);
    }
    work_free(&w);
    budget_release(mem, need);
    return status;
}
