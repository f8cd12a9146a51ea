/* syl_render_draw_mesh: check the request, set up the scene, build textures and BVH, render tiles. */

/* One Embree triangle geometry over the mesh's own buffers, a ground square at the mesh's
 * lowest point (intersected analytically: it is a plane and never occludes anything), a sun
 * with ray-traced shadows, sky light with ambient occlusion, procedural textures and a sky
 * gradient (shade.c). Pictures are cut into 32 x 32 tiles that worker threads take in turn;
 * a pixel's value depends only on its coordinates (its random numbers are a hash of the
 * pixel index), so the output is the same for any number of threads. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#define HAVE_MXCSR 1
#endif

#include "texture/srgbbytes.h"
#include "util/pngin.h"
#include "render/scene.h"
#include "mesh/store.h"
#include "util/budget.h"
#include "util/parallel.h"
#include "util/coord.h"
#include "util/diag.h"

void render_embree_error(void *user, enum RTCError code, const char *msg) {
    const SylSink *sink = user;
    sink_error(sink, "embree: %s (code %d)", msg ? msg : "error", (int)code);
}

/* Embree wants denormals flushed to zero (much faster); each worker sets it for itself and
 * the calling thread puts its own mode back afterwards. */
unsigned render_fast_floats(void) {
#ifdef HAVE_MXCSR
    unsigned old = _mm_getcsr();
    _mm_setcsr(old | 0x8040); /* flush to zero, denormals are zero */
    return old;
#else
    return 0;
#endif
}

void render_restore_floats(unsigned old) {
#ifdef HAVE_MXCSR
    _mm_setcsr(old);
#else
    (void)old;
#endif
}

/* One call per finished tile; the last one is exactly 1.0. */
static void tile_finished(Scene *s) {
    if (!s->progress) return;
    pthread_mutex_lock(&s->progress_lock);
    int done = atomic_fetch_add(&s->tiles_done, 1) + 1;
    s->progress(s->user, done == s->ntiles ? 1.0 : (double)done / (double)s->ntiles);
    pthread_mutex_unlock(&s->progress_lock);
}

static void render_tiles(Scene *s) {
    int t;
    while ((t = atomic_fetch_add(&s->next_tile, 1)) < s->ntiles) {
        render_tile(s, t);
        tile_finished(s);
    }
}

/* A tile worker (par_run), in the fast float mode while it works. */
static void worker(void *arg, int k) {
    (void)k;
    Scene *s = arg;
    unsigned csr = render_fast_floats();
    render_tiles(s);
    render_restore_floats(csr);
}

void render_scene_free(Scene *s) {
    if (s->scene) rtcReleaseScene(s->scene);
    if (s->dev) rtcReleaseDevice(s->dev);
    for (int i = 0; i < 4; i++) texture_free(&s->tex[i]);
    for (int i = 0; i < SYL_IMAGES_MAX; i++) texture_free(&s->img[i]);
    free(s->tri_mat);
    free(s->quad_index);
    free(s->quad_halves);
    render_alpha_free(s->alphatest);
    free(s->pos_copy);
    free(s);
}

int render_cpu_count(void) { return par_threads(0); }

/* Textures are made on threads of their own while Embree builds its hierarchy. */
typedef struct TexJob {
    Texture *tex;
    int kind;
    bool ok;
} TexJob;

static void tex_job(TexJob *j) { j->ok = texture_build(j->tex, j->kind, TEX_SIZE); }

static int build_scene(Scene *s, int threads, const SylSink *sink);

/* The scene's hierarchy on the calling thread (k = 0) and each texture on one of its own. */
typedef struct Prepare {
    Scene *s;
    int threads, status;
    const SylSink *sink;
    TexJob *jobs;
} Prepare;

static void prepare_part(void *arg, int k) {
    Prepare *p = arg;
    if (k == 0) p->status = build_scene(p->s, p->threads, p->sink);
    else tex_job(&p->jobs[k - 1]);
}

/* Embree: the mesh as one triangle geometry on the mesh's own arrays. */
static int build_scene(Scene *s, int threads, const SylSink *sink) {
    const SylMesh *m = s->m;
    size_t ntri = m ? m->nidx / 3 : 0;
    if (m && !coord_check(m->pos, m->nverts, 3, "the model", sink)) return SYL_EMODEL;
    char config[64];
    snprintf(config, sizeof config, "threads=%d,verbose=0", threads);
    s->dev = rtcNewDevice(config);
    if (!s->dev) {
        sink_error(sink, "render: cannot start Embree (error %d)", (int)rtcGetDeviceError(NULL));
        return SYL_ELIMIT;
    }
    rtcSetDeviceErrorFunction(s->dev, render_embree_error, (void *)sink);
    s->scene = rtcNewScene(s->dev);
    if (ntri) {
        s->tri_mat = calloc(ntri, 1);
        if (!s->tri_mat) return SYL_ELIMIT;
        for (int g = 0; g < m->ngroups; g++) {
            size_t first = m->groups[g].first / 3, count = m->groups[g].count / 3;
            for (size_t i = first; i < first + count && i < ntri; i++) s->tri_mat[i] = m->groups[g].material;
        }
        /* Embree reads vertices 16 bytes at a time: the array needs room past the last one,
         * which a vertex array with spare capacity has. */
        const float *pos = m->pos;
        if (!mesh_has_spare(m)) {
            s->pos_copy = malloc((m->nverts * 3 + 4) * sizeof(float));
            if (!s->pos_copy) return SYL_ELIMIT;
            memcpy(s->pos_copy, m->pos, m->nverts * 3 * sizeof(float));
            memset(s->pos_copy + m->nverts * 3, 0, 4 * sizeof(float));
            pos = s->pos_copy;
        }
        /* Impostor baking (adaptive) traces millions of rays into one scene: quads there, for a
         * quicker build and traversal; other pictures keep Embree's triangles. */
        size_t nquads = 0;
        if (s->adaptive && render_quads(m, s->tri_mat, &s->quad_index, &s->quad_halves, &nquads)) return SYL_ELIMIT;
        RTCGeometry geom = rtcNewGeometry(s->dev, s->quad_index ? RTC_GEOMETRY_TYPE_QUAD : RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, pos, 0, 3 * sizeof(float),
                                   m->nverts);
        if (s->quad_index)
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, s->quad_index, 0,
                                       4 * sizeof(uint32_t), nquads);
        else
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m->idx, 0,
                                       3 * sizeof(uint32_t), ntri);
        if (render_alpha_test(s, geom)) { /* after the quads: its filter reads their halves */
            rtcReleaseGeometry(geom);
            return SYL_ELIMIT;
        }
        rtcCommitGeometry(geom);
        rtcAttachGeometry(s->scene, geom);
        rtcReleaseGeometry(geom);
    }
    rtcCommitScene(s->scene);
    return rtcGetDeviceError(s->dev) == RTC_ERROR_NONE ? SYL_OK : SYL_ELIMIT;
}

static int render_checked(const SylMesh *m, const SylRenderOptions *opt, int n, const float (*toward)[3],
                          uint8_t *rgb);

/* Embree's BVH, its copy of the positions, the textures and the picture, counted against
 * the memory budget before any is built: about 150 bytes a triangle. */
int syl_render_draw_mesh(const SylMesh *m, const SylRenderOptions *opt, uint8_t *rgb) {
    static const SylRenderOptions defaults = {0};
    if (!opt) opt = &defaults;
    SylSink text;
    const SylSink *sink = diag_sink(&text, opt->diag, opt->sink);
    Budget own, *mem = budget_use(&own, opt->max_memory, opt->budget);
    uint64_t w = opt->width > 0 ? (uint64_t)opt->width : 1024, h = opt->height > 0 ? (uint64_t)opt->height : 1024;
    uint64_t tris = m ? m->nidx / 3 : 0, need = tris * 150 + (m ? m->nverts * 16 : 0) + w * h * 3 + (4u << 20);
    if (!budget_charge(mem, need)) {
        sink_error(sink, "rendering %llu triangles would need about %llu MB, more than "
                               "--max-memory allows (%llu MB in all); raise the limit with --max-memory\n",
                    (unsigned long long)tris, (unsigned long long)(need >> 20),
                    (unsigned long long)budget_limit_mb(mem));
        return SYL_ELIMIT;
    }
    int st = render_checked(m, opt, 1, NULL, rgb);
    budget_release(mem, need);
    return st;
}

/* The picture's size from the options, and a mesh Embree can take: SYL_OK, or SYL_EUSAGE /
 * SYL_ELIMIT, reported. */
static int check_request(const SylMesh *m, const SylRenderOptions *opt, int *width, int *height) {
    SylSink text;
    const SylSink *sink = diag_sink(&text, opt->diag, opt->sink);
    *width = opt->width > 0 ? opt->width : 1024, *height = opt->height > 0 ? opt->height : 1024;
    if (opt->width < 0 || opt->height < 0 || *width > 65536 || *height > 65536 ||
        (size_t)*width * (size_t)*height > (size_t)1 << 28) {
        sink_error(sink, "render: picture size %d x %d out of range", *width, *height);
        return SYL_EUSAGE;
    }
    size_t ntri = m ? m->nidx / 3 : 0;
    if (ntri > 0xffffffffu) {
        sink_error(sink, "render: too many triangles");
        return SYL_ELIMIT;
    }
    for (size_t i = 0; i < ntri * 3; i++)
        if (m->idx[i] >= m->nverts) {
            sink_error(sink, "render: mesh index %u out of range", m->idx[i]);
            return SYL_EUSAGE;
        }
    return SYL_OK;
}

/* Samples, ambient occlusion and shadows from the options, and the camera. */
static void set_sampling(Scene *s, const SylRenderOptions *opt) {
    s->samples = opt->samples > 0 ? (opt->samples > MAX_SAMPLES ? MAX_SAMPLES : opt->samples) : 4;
    /* Ambient occlusion rays are shared among a pixel's samples: each takes its share. */
    int ao = opt->ao_samples < 0 ? 0 : opt->ao_samples == 0 ? 8 : opt->ao_samples > MAX_AO ? MAX_AO : opt->ao_samples;
    s->ao = ao ? (ao + s->samples - 1) / s->samples : 0;
    s->shadows = opt->shadows;
    if (opt->toward) {
        if (!s->boxed) render_mesh_bounds(opt->frame ? opt->frame : s->m, s->box[0], s->box[1]);
        s->boxed = true;
        render_camera_toward_box(s->box[0], s->box[1], opt->toward, s->width, s->height, &s->cam);
    }
    else render_camera(opt->frame ? opt->frame : s->m, opt->view, s->width, s->height, &s->cam);
}

/* Materials, scale, light, sub-pixel positions, and the table from linear light to sRGB. */
int render_material_image(const SylMesh *m, int i) {
    const SylMaterial *mt = &m->materials[i];
    if (mt->kind > SYL_MATERIAL_FLOWER || (mt->kind == SYL_MATERIAL_LEAF && m->leaves == SYL_LEAVES_CLUSTERS)) return -1;
    return syl_material_image(m->images, mt) ? mt->image - 1 : -1;
}

void render_set_lighting(Scene *s) {
    const SylMesh *m = s->m;
    for (int i = 0; i < 256; i++) {
        s->mat_img[i] = (int8_t)(m ? render_material_image(m, i) : -1);
        /* an image of the model's own is the colour itself (white times the image) */
        for (int c = 0; c < 3; c++) s->mat_lin[i][c] = s->mat_img[i] >= 0 ? 1 : srgb_to_linear(m ? m->materials[i].rgb[c] : 0.5f);
        s->mat_kind[i] = m ? m->materials[i].kind : SYL_MATERIAL_PLAIN;
    }
    for (int c = 0; c < 3; c++) s->grass_lin[c] = srgb_to_linear(texture_grass_rgb()[c]);
    const float *lo = s->cam.lo, *hi = s->cam.hi;
    s->size = fmaxf(hi[0] - lo[0], fmaxf(hi[1] - lo[1], hi[2] - lo[2]));
    if (!(s->size > 0)) s->size = 1;
    float reach = fmaxf(fmaxf(fabsf(lo[0]), fabsf(hi[0])),
                        fmaxf(fmaxf(fabsf(lo[1]), fabsf(hi[1])), fmaxf(fabsf(lo[2]), fabsf(hi[2]))));
    s->eps = 1e-4f * s->size + 4e-6f * reach;
    s->ao_dist = 0.18f * s->size;
    s->fog_dist = 12 * s->size;
    s->ground_y = lo[1];
    s->ground_half = 40 * s->size;
    s->ground_c[0] = 0.5f * (lo[0] + hi[0]);
    s->ground_c[1] = 0.5f * (lo[2] + hi[2]);
    s->grass_tile = 0.35f * s->size;
    s->pixel_angle = 2 * s->cam.tany / (float)s->height;
    s->shadow_far = INFINITY;
    float sun[3] = {0.4f, 1.0f, 0.3f};
    normalize3(sun);
    memcpy(s->sun, sun, sizeof sun);
    for (int k = 0; k < s->samples; k++) { /* the R2 sequence: well spread for any count */
        float a = 0.5f + 0.7548776662f * (float)k, b = 0.5f + 0.5698402909f * (float)k;
        s->sub[k][0] = a - floorf(a);
        s->sub[k][1] = b - floorf(b);
    }
    for (int i = 0; i <= 4096; i++) s->lut[i] = srgb_byte_exact((float)i / 4096);
}

/* The textures of the kinds in use, and grass when the ground is drawn (not in an impostor's
 * bake), on threads of their own while Embree builds its hierarchy: SYL_OK, or the first
 * failure, reported. */
static int build_textures_and_scene(Scene *s, int threads, const SylSink *sink) {
    const SylMesh *m = s->m;
    TexJob jobs[4];
    int njobs = 0;
    bool used[4] = {false, false, false, s->ground};
    for (int g = 0; m && g < m->ngroups; g++) {
        int k = m->materials[m->groups[g].material].kind;
        if (k <= SYL_MATERIAL_FLOWER) used[k] = true;
    }
    for (int k = 0; k < 4; k++)
        if (used[k]) jobs[njobs++] = (TexJob){.tex = &s->tex[k], .kind = k == 3 ? -1 : k};
    Prepare prep = {s, threads, SYL_OK, sink, jobs};
    par_run(threads > 1 ? njobs + 1 : 1, prepare_part, &prep); /* one thread: the textures below */
    int status = prep.status;
    if (status == SYL_ELIMIT && sink) sink_error(sink, "render: cannot build the scene");
    for (int j = 0; j < njobs; j++) {
        if (threads <= 1) tex_job(&jobs[j]);
        if (!jobs[j].ok && !status) {
            sink_error(sink, "render: out of memory");
            status = SYL_ELIMIT;
        }
    }
    for (int i = 0; i < 256 && !status && m; i++) /* the images, decoded once each */
        if (s->mat_img[i] >= 0 && !s->img[s->mat_img[i]].levels)
            status = render_image_texture(&s->img[s->mat_img[i]], &m->images->img[s->mat_img[i]], sink);
    return status;
}

int render_image_texture(Texture *t, const SylImage *g, const SylSink *sink) {
    int w, h;
    bool alpha;
    uint8_t *rgba = NULL;
    char why[160];
    int status = SYL_OK;
    if (!pngin_decode(g->png, g->len, &w, &h, &alpha, &rgba, why, sizeof why) || !texture_from_rgba(t, rgba, w, h, TEX_SIZE)) {
        sink_error(sink, "render: the texture \"%s\": %s", g->name, rgba ? "out of memory" : why);
        status = SYL_ELIMIT;
    }
    free(rgba);
    return status;
}

/* The tiles to the workers; this thread works too. */
void render_all_tiles(Scene *s, int threads, const SylRenderOptions *opt) {
    s->progress = opt->progress;
    s->user = opt->user;
    pthread_mutex_init(&s->progress_lock, NULL);
    s->tiles_x = (s->width + TILE - 1) / TILE;
    s->ntiles = s->tiles_x * ((s->height + TILE - 1) / TILE);
    if (threads > s->ntiles) threads = s->ntiles;
    par_run(threads, worker, s); /* workers taking tiles in turn; this thread works too */
    pthread_mutex_destroy(&s->progress_lock);
}

/* Pictures of one scene: n views (toward: NULL, or a direction each), written one after
 * another into rgb, and alpha and normal when the options ask for them. */
static int render_checked(const SylMesh *m, const SylRenderOptions *opt, int n, const float (*toward)[3],
                          uint8_t *rgb) {
    SylSink text;
    const SylSink *sink = diag_sink(&text, opt->diag, opt->sink);
    int width, height;
    int status = check_request(m, opt, &width, &height);
    if (status) return status;
    Scene *s = calloc(1, sizeof *s);
    if (!s) {
        sink_error(sink, "render: out of memory");
        return SYL_ELIMIT;
    }
    s->m = m;
    s->width = s->full_w = width;
    s->height = s->full_h = height;
    s->ground = opt->ground >= 0;
    s->unlit = opt->unlit;
    s->adaptive = opt->adaptive;
    int threads = opt->threads > 0 ? opt->threads : render_cpu_count();
    if (threads > 256) threads = 256;
    size_t px = (size_t)width * (size_t)height;
    for (int v = 0; v < n && !status; v++) {
        SylRenderOptions o = *opt;
        if (toward) o.toward = toward[v];
        s->out = rgb + 3 * px * (size_t)v;
        s->alpha = opt->alpha ? opt->alpha + px * (size_t)v : NULL;
        s->normal = opt->normal ? opt->normal + 4 * px * (size_t)v : NULL;
        atomic_store(&s->next_tile, 0);
        atomic_store(&s->tiles_done, 0);
        set_sampling(s, &o);
        render_set_lighting(s);
        if (v == 0) status = build_textures_and_scene(s, threads, sink);
        if (!status) render_all_tiles(s, threads, &o);
    }
    render_scene_free(s);
    return status;
}

int syl_render_draw_views(const SylMesh *m, const SylRenderOptions *opt, int n, const float (*toward)[3], uint8_t *rgb) {
    if (n < 1) return SYL_OK;
    SylSink text;
    const SylSink *sink = diag_sink(&text, opt->diag, opt->sink);
    Budget own, *mem = budget_use(&own, opt->max_memory, opt->budget);
    uint64_t w = opt->width > 0 ? (uint64_t)opt->width : 1024, h = opt->height > 0 ? (uint64_t)opt->height : 1024;
    uint64_t tris = m ? m->nidx / 3 : 0, need = tris * 150 + (m ? m->nverts * 16 : 0) + w * h * 8 * (uint64_t)n + (4u << 20);
    if (!budget_charge(mem, need)) {
        sink_error(sink, "rendering %d views of %llu triangles would need about %llu MB, more than "
                               "--max-memory allows (%llu MB in all); raise the limit with --max-memory\n",
                    n, (unsigned long long)tris, (unsigned long long)(need >> 20), (unsigned long long)budget_limit_mb(mem));
        return SYL_ELIMIT;
    }
    int st = render_checked(m, opt, n, toward, rgb);
    budget_release(mem, need);
    return st;
}

int syl_render_write_png(const SylMesh *m, const SylRenderOptions *opt, const char *path) {
    static const SylRenderOptions defaults = {0};
    if (!opt) opt = &defaults;
    SylSink text;
    const SylSink *sink = diag_sink(&text, opt->diag, opt->sink);
    int w = opt->width > 0 ? opt->width : 1024, h = opt->height > 0 ? opt->height : 1024;
    uint8_t *rgb = malloc((size_t)w * (size_t)h * 3);
    if (!rgb) {
        sink_error(sink, "render: out of memory");
        return SYL_ELIMIT;
    }
    int status = syl_render_draw_mesh(m, opt, rgb);
    if (!status) status = syl_png_write(path, rgb, w, h, sink);
    free(rgb);
    return status;
}
