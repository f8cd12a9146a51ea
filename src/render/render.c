/* The renderer: one Embree triangle geometry over the mesh's own buffers, a ground square
 * at the mesh's lowest point (intersected analytically: it is a plane and never occludes
 * anything), a sun with ray-traced shadows, sky light with ambient occlusion, procedural
 * textures and a sky gradient. Pictures are cut into 32 x 32 tiles that worker threads take
 * in turn; a pixel's value depends only on its coordinates (its random numbers are a hash of
 * the pixel index), so the output is the same for any number of threads. */
#include <cglm/cglm.h>
#include <embree3/rtcore.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#define HAVE_MXCSR 1
#endif

#include "render/render_internal.h"
#include "util/budget.h"
#include "util/coord.h"
#include "util/rng.h"

enum { TILE = 32, MAX_SAMPLES = 64, MAX_AO = 64, TEX_SIZE = 256 };

/* ---------------------------------------------------------------- camera */

static const float fit = 0.8f;            /* the plant fills this share of the frame */
static const float half_fov_y = 17.5f;    /* degrees: a 35 degree vertical field of view */

/* The points to frame in view coordinates (x right, y up, z depth from the centre): the
 * mesh's vertices, or the corners of its box when there are none or memory is short. */
typedef struct FitPoints {
    float (*v)[3];
    size_t n;
    float corners[8][3];
} FitPoints;

static void fit_points(FitPoints *f, const SylMesh *m, const float lo[3], const float hi[3], const float c[3],
                       const float right[3], const float up[3], const float fwd[3]) {
    const float *axes[3] = {right, up, fwd};
    for (int i = 0; i < 8; i++) {
        float q[3] = {(i & 1 ? hi[0] : lo[0]) - c[0], (i & 2 ? hi[1] : lo[1]) - c[1], (i & 4 ? hi[2] : lo[2]) - c[2]};
        for (int k = 0; k < 3; k++) f->corners[i][k] = q[0] * axes[k][0] + q[1] * axes[k][1] + q[2] * axes[k][2];
    }
    f->v = f->corners;
    f->n = 8;
    float (*v)[3] = m && m->nverts ? malloc(m->nverts * sizeof *v) : NULL;
    if (!v) return;
    size_t n = 0;
    for (size_t i = 0; i < m->nverts; i++) {
        const float *p = m->pos + 3 * i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) continue;
        float q[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
        for (int k = 0; k < 3; k++) v[n][k] = q[0] * axes[k][0] + q[1] * axes[k][1] + q[2] * axes[k][2];
        n++;
    }
    if (!n) {
        free(v);
        return;
    }
    f->v = v;
    f->n = n;
}

/* Extent of the points across the view, shifted by (cx, cy): divided by the depth when
 * dist >= 0 (tangents), plain (orthographic) when dist < 0. ext: xmin xmax ymin ymax. */
static void fit_extent(const FitPoints *f, float cx, float cy, float dist, float ext[4]) {
    ext[0] = ext[2] = INFINITY;
    ext[1] = ext[3] = -INFINITY;
    for (size_t i = 0; i < f->n; i++) {
        float x = f->v[i][0] - cx, y = f->v[i][1] - cy, z = f->v[i][2];
        if (dist >= 0) {
            if (!(dist + z > 0)) continue;
            x /= dist + z, y /= dist + z;
        }
        ext[0] = x < ext[0] ? x : ext[0], ext[1] = x > ext[1] ? x : ext[1];
        ext[2] = y < ext[2] ? y : ext[2], ext[3] = y > ext[3] ? y : ext[3];
    }
    if (!(ext[0] <= ext[1])) ext[0] = ext[1] = 0;
    if (!(ext[2] <= ext[3])) ext[2] = ext[3] = 0;
}

/* The least distance back from the centre at which all points fit. */
static float fit_distance(const FitPoints *f, float cx, float cy, float tanx, float tany, float size) {
    float need = 0, zmin = INFINITY, kx = 1 / (fit * tanx), ky = 1 / (fit * tany);
    for (size_t i = 0; i < f->n; i++) {
        float x = f->v[i][0] - cx, y = f->v[i][1] - cy, z = f->v[i][2];
        float ax = fabsf(x) * kx, ay = fabsf(y) * ky, a = (ax > ay ? ax : ay) - z;
        need = a > need ? a : need;
        zmin = z < zmin ? z : zmin;
    }
    if (!isfinite(zmin)) zmin = 0;
    return fmaxf(need, fmaxf(-zmin + 0.05f * size, 0.1f * size));
}

void render_camera(const SylMesh *m, SylView view, int width, int height, RenderCamera *cam) {
    memset(cam, 0, sizeof *cam);
    cam->width = width;
    cam->height = height;
    vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; m && i < m->nverts; i++)
        for (int k = 0; k < 3; k++) {
            float v = m->pos[3 * i + k];
            if (!isfinite(v)) continue;
            if (v < lo[k]) lo[k] = v;
            if (v > hi[k]) hi[k] = v;
        }
    if (!(lo[0] <= hi[0] && lo[1] <= hi[1] && lo[2] <= hi[2])) { /* nothing to frame */
        glm_vec3_copy((vec3){-0.5f, 0, -0.5f}, lo);
        glm_vec3_copy((vec3){0.5f, 1, 0.5f}, hi);
    }
    glm_vec3_copy(lo, cam->lo);
    glm_vec3_copy(hi, cam->hi);
    float size = fmaxf(hi[0] - lo[0], fmaxf(hi[1] - lo[1], hi[2] - lo[2]));
    if (!(size > 0)) size = 1;
    if (view == SYL_VIEW_AUTO) view = hi[2] - lo[2] < 0.05f * size ? SYL_VIEW_FRONT : SYL_VIEW_ISO;

    vec3 back, upref = {0, 1, 0};
    float el = glm_rad(35), az = glm_rad(45);
    switch (view) {
    case SYL_VIEW_FRONT: glm_vec3_copy((vec3){0, 0, 1}, back); break;
    case SYL_VIEW_SIDE: glm_vec3_copy((vec3){1, 0, 0}, back); break;
    case SYL_VIEW_TOP:
        glm_vec3_copy((vec3){0, 1, 0}, back);
        glm_vec3_copy((vec3){0, 0, -1}, upref);
        break;
    default: glm_vec3_copy((vec3){cosf(el) * sinf(az), sinf(el), cosf(el) * cosf(az)}, back); break;
    }
    vec3 fwd, right, up;
    glm_vec3_negate_to(back, fwd);
    glm_vec3_crossn(fwd, upref, right);
    glm_vec3_cross(right, fwd, up);
    cam->tany = tanf(glm_rad(half_fov_y));
    cam->tanx = cam->tany * (float)width / (float)height;

    /* Fit: centre the projected extent and pull back until every vertex projects inside
     * `fit` of the frame; a few rounds settle the perspective's asymmetry. */
    vec3 c;
    glm_vec3_center(lo, hi, c);
    FitPoints fp;
    fit_points(&fp, m, lo, hi, c, right, up, fwd);
    float cx, cy, dist, ext[4];
    fit_extent(&fp, 0, 0, -1, ext); /* orthographic: the middle */
    cx = 0.5f * (ext[0] + ext[1]);
    cy = 0.5f * (ext[2] + ext[3]);
    dist = fit_distance(&fp, cx, cy, cam->tanx, cam->tany, size);
    for (int round = 0; round < 3; round++) {
        fit_extent(&fp, cx, cy, dist, ext);
        cx += 0.5f * (ext[0] + ext[1]) * dist;
        cy += 0.5f * (ext[2] + ext[3]) * dist;
        dist = fit_distance(&fp, cx, cy, cam->tanx, cam->tany, size);
    }
    if (fp.v != fp.corners) free(fp.v);
    vec3 eye;
    glm_vec3_copy(c, eye);
    glm_vec3_muladds(right, cx, eye);
    glm_vec3_muladds(up, cy, eye);
    glm_vec3_muladds(fwd, -dist, eye);
    glm_vec3_copy(eye, cam->eye);
    glm_vec3_copy(fwd, cam->fwd);
    glm_vec3_copy(right, cam->right);
    glm_vec3_copy(up, cam->up);
}

bool render_project(const RenderCamera *cam, const float p[3], float *x, float *y) {
    float q[3] = {p[0] - cam->eye[0], p[1] - cam->eye[1], p[2] - cam->eye[2]};
    float z = q[0] * cam->fwd[0] + q[1] * cam->fwd[1] + q[2] * cam->fwd[2];
    if (!(z > 0)) return false;
    float sx = (q[0] * cam->right[0] + q[1] * cam->right[1] + q[2] * cam->right[2]) / (z * cam->tanx);
    float sy = (q[0] * cam->up[0] + q[1] * cam->up[1] + q[2] * cam->up[2]) / (z * cam->tany);
    *x = (sx + 1) * 0.5f * (float)cam->width;
    *y = (1 - sy) * 0.5f * (float)cam->height;
    return true;
}

/* ---------------------------------------------------------------- scene */

typedef struct Scene {
    const SylMesh *m;
    RenderCamera cam;
    RTCDevice dev;
    RTCScene scene;
    float *pos_copy;            /* when the mesh's vertex array has no room for Embree's padding */
    uint8_t *tri_mat;           /* material of each triangle */
    Texture tex[4];             /* bark, leaf, flower, grass */
    float mat_lin[256][3];      /* material colours in linear light */
    uint8_t mat_kind[256];
    float grass_lin[3];
    float size, eps, ao_dist, fog_dist, ground_y, ground_half, ground_c[2], grass_tile;
    float pixel_angle;
    float sun[3];
    int width, height, samples, ao, shadows;
    float sub[MAX_SAMPLES][2];  /* sub-pixel sample positions */
    uint8_t lut[4097];          /* linear 0..1 in 4096 steps -> sRGB byte */
    uint8_t *out;
    int tiles_x, ntiles;
    atomic_int next_tile, tiles_done;
    /* Whichever thread finishes a tile reports, under the lock: serial, increasing calls. */
    void (*progress)(void *user, double fraction);
    void *user;
    pthread_mutex_t progress_lock;
} Scene;

static const float sun_rgb[3] = {2.35f, 2.20f, 1.95f};
static const float sky_rgb[3] = {0.50f, 0.60f, 0.78f};     /* ambient light from the sky */
static const float horizon[3] = {0.62f, 0.74f, 0.90f};     /* background, linear */
static const float zenith[3] = {0.12f, 0.27f, 0.62f};

static void embree_error(void *user, enum RTCError code, const char *msg) {
    FILE *diag = user;
    if (diag) fprintf(diag, "sylva: error: embree: %s (code %d)\n", msg ? msg : "error", (int)code);
}

static inline float dot3(const float a[3], const float b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static inline void normalize3(float v[3]) {
    float l = sqrtf(dot3(v, v));
    if (l > 0) {
        float k = 1 / l;
        v[0] *= k, v[1] *= k, v[2] *= k;
    }
}

/* Two unit vectors perpendicular to n (Duff et al. 2017). */
static inline void basis(const float n[3], float t[3], float b[3]) {
    float s = copysignf(1.0f, n[2]);
    float a = -1.0f / (s + n[2]), c = n[0] * n[1] * a;
    t[0] = 1 + s * n[0] * n[0] * a, t[1] = s * c, t[2] = -s * n[0];
    b[0] = c, b[1] = s + n[1] * n[1] * a, b[2] = -n[1];
}

/* cos and sin of 2 pi u for u in 0..1, to about 1e-6: a polynomial on an octant, so it is
 * quick and the same everywhere. */
static inline void turn(float u, float *c, float *s) {
    float a = u * 8;
    int oct = (int)a;
    float x = (a - (float)oct) * 0.78539816f; /* 0..pi/4 */
    if (oct & 1) x = 0.78539816f - x;
    float x2 = x * x;
    float sn = x * (1 + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040))));
    float cs = 1 + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320))));
    /* octant: swap for 1, 2, 5, 6; signs by quadrant */
    float cc = (oct + 1) & 2 ? sn : cs, ss = (oct + 1) & 2 ? cs : sn;
    int q = (oct >> 1) & 3;
    *c = q == 1 || q == 2 ? -cc : cc;
    *s = q >= 2 ? -ss : ss;
}

static void sky(const float d[3], float out[3]) {
    float t = d[1] > 0 ? sqrtf(d[1]) : 0;
    for (int c = 0; c < 3; c++) out[c] = horizon[c] + t * (zenith[c] - horizon[c]);
}

/* Rays go to Embree sixteen at a time: the pixels of a 4 x 4 block for one sample index,
 * so camera rays and sun rays in a packet are nearly parallel. The packets a pixel belongs to
 * depend only on its coordinates, never on the threads. */
enum { BLOCK = 4, LANES = BLOCK * BLOCK };

/* What a camera ray found. */
typedef struct Surface {
    int what;            /* SKY, GROUND or MESH */
    float p[3], n[3];    /* point, geometric normal facing the viewer */
    float sn[3];         /* shading normal */
    float albedo[3];
    bool thin;           /* a leaf or petal: also lit through from behind */
    float fog;           /* ground: how much the distance fades it into the sky */
    float bg[3];         /* the sky along the ray */
} Surface;

enum { SKY, GROUND, MESH };

/* Texture level of detail: log2 of texels per sample footprint. */
static inline float lod_of(const Scene *s, float t, float cosv, float uv_per_world, int tex_size) {
    float c = cosv > 0.05f ? cosv : 0.05f;
    float texels = t * s->pixel_angle / (c * sqrtf((float)s->samples)) * uv_per_world * (float)tex_size;
    return texels > 1 ? log2f(texels) : 0;
}

/* Fill sf from lane l of a packet that hit the mesh. */
static void mesh_surface(const Scene *s, const struct RTCRayHit16 *rh, int l, const float d[3], Surface *sf) {
    const SylMesh *m = s->m;
    float t = rh->ray.tfar[l], u = rh->hit.u[l], v = rh->hit.v[l], w = 1 - u - v;
    uint32_t tri = rh->hit.primID[l];
    const uint32_t *ix = m->idx + 3 * (size_t)tri;
    const float *e = s->cam.eye;
    sf->what = MESH;
    for (int c = 0; c < 3; c++) sf->p[c] = e[c] + t * d[c];
    float *ng = sf->n, *sn = sf->sn;
    ng[0] = rh->hit.Ng_x[l], ng[1] = rh->hit.Ng_y[l], ng[2] = rh->hit.Ng_z[l];
    normalize3(ng);
    bool flip = dot3(ng, d) > 0; /* both sides of a surface are drawn */
    if (flip) ng[0] = -ng[0], ng[1] = -ng[1], ng[2] = -ng[2];
    if (m->nrm) {
        const float *n0 = m->nrm + 3 * (size_t)ix[0], *n1 = m->nrm + 3 * (size_t)ix[1], *n2 = m->nrm + 3 * (size_t)ix[2];
        for (int c = 0; c < 3; c++) sn[c] = w * n0[c] + u * n1[c] + v * n2[c];
        if (flip) sn[0] = -sn[0], sn[1] = -sn[1], sn[2] = -sn[2];
        normalize3(sn);
        if (!(dot3(sn, d) < 0) || !(dot3(sn, ng) > 0)) memcpy(sn, ng, 3 * sizeof *sn);
    } else memcpy(sn, ng, 3 * sizeof *sn);
    int mat = s->tri_mat[tri], kind = s->mat_kind[mat];
    memcpy(sf->albedo, s->mat_lin[mat], sizeof sf->albedo);
    sf->thin = kind == SYL_MATERIAL_LEAF || kind == SYL_MATERIAL_FLOWER;
    if (m->uv && kind <= SYL_MATERIAL_FLOWER) {
        const float *a = m->uv + 2 * (size_t)ix[0], *b = m->uv + 2 * (size_t)ix[1], *c = m->uv + 2 * (size_t)ix[2];
        float tu = w * a[0] + u * b[0] + v * c[0], tv = w * a[1] + u * b[1] + v * c[1];
        /* uv units per world unit, from the triangle's areas in uv and in space */
        const float *p0 = m->pos + 3 * (size_t)ix[0], *p1 = m->pos + 3 * (size_t)ix[1], *p2 = m->pos + 3 * (size_t)ix[2];
        float e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        float cr[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        float aw = sqrtf(dot3(cr, cr));
        float auv = fabsf((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
        float density = aw > 0 ? sqrtf(auv / aw) : 0;
        const Texture *tx = &s->tex[kind];
        float tex[3];
        texture_sample(tx, tu, tv, lod_of(s, t, -dot3(ng, d), density, tx->size[0]), tex);
        for (int c = 0; c < 3; c++) sf->albedo[c] *= tex[c];
    }
}

static void ground_surface(const Scene *s, float t, const float d[3], Surface *sf) {
    const float *e = s->cam.eye;
    sf->what = GROUND;
    sf->p[0] = e[0] + t * d[0], sf->p[1] = s->ground_y, sf->p[2] = e[2] + t * d[2];
    sf->n[0] = sf->n[2] = sf->sn[0] = sf->sn[2] = 0;
    sf->n[1] = sf->sn[1] = 1;
    sf->thin = false;
    /* The grass at two scales, turned against each other, so its tiling does not show. */
    const Texture *tx = &s->tex[3];
    float a[3], b[3], k = 1 / s->grass_tile, x = sf->p[0] * k, z = sf->p[2] * k;
    float lod = lod_of(s, t, -d[1], k, tx->size[0]);
    texture_sample(tx, x, z, lod, a);
    texture_sample(tx, 0.2f * (0.8f * x - 0.6f * z) + 0.31f, 0.2f * (0.6f * x + 0.8f * z) + 0.17f, lod - 2.32f, b);
    for (int c = 0; c < 3; c++) sf->albedo[c] = s->grass_lin[c] * a[c] * (0.55f + 0.5f * b[c]);
    sf->fog = 1 - expf(-t / s->fog_dist);
}

static inline void set_ray16(struct RTCRay16 *r, int l, const float o[3], const float d[3], float tfar) {
    r->org_x[l] = o[0], r->org_y[l] = o[1], r->org_z[l] = o[2], r->tnear[l] = 0;
    r->dir_x[l] = d[0], r->dir_y[l] = d[1], r->dir_z[l] = d[2], r->time[l] = 0;
    r->tfar[l] = tfar, r->mask[l] = 0xffffffffu, r->id[l] = (unsigned)l, r->flags[l] = 0;
}

/* Render the pixels of the block at (x0, y0) into acc (linear light, summed over samples). */
static void render_block(const Scene *s, int x0, int y0, float acc[LANES][3]) {
    const RenderCamera *cam = &s->cam;
    _Alignas(64) int valid[LANES], lit[LANES], open_valid[LANES];
    _Alignas(64) struct RTCRayHit16 rh;
    _Alignas(64) struct RTCRay16 sr;
    Surface sf[LANES];
    float dirs[LANES][3], direct[LANES];
    int open[LANES];
    Rng rng[LANES];
    struct RTCIntersectContext coherent, incoherent;
    rtcInitIntersectContext(&coherent);
    coherent.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcInitIntersectContext(&incoherent);
    memset(acc, 0, LANES * sizeof *acc);
    for (int k = 0; k < s->samples; k++) {
        /* Camera rays, and the ground by hand (a plane: tfar stops Embree there). */
        for (int l = 0; l < LANES; l++) {
            int x = x0 + l % BLOCK, y = y0 + l / BLOCK;
            valid[l] = x < s->width && y < s->height ? -1 : 0;
            rng[l] = rng_stream(0x5e1fa, (uint64_t)y * (uint64_t)s->width + (uint64_t)x, 0, (uint64_t)k);
            float sx = (2 * ((float)x + s->sub[k][0]) / (float)s->width - 1) * cam->tanx;
            float sy = (1 - 2 * ((float)y + s->sub[k][1]) / (float)s->height) * cam->tany;
            float *d = dirs[l];
            for (int i = 0; i < 3; i++) d[i] = cam->fwd[i] + sx * cam->right[i] + sy * cam->up[i];
            normalize3(d);
            float tg = INFINITY;
            if (d[1] < 0 && cam->eye[1] > s->ground_y) {
                float t = (s->ground_y - cam->eye[1]) / d[1];
                float gx = cam->eye[0] + t * d[0], gz = cam->eye[2] + t * d[2];
                if (fabsf(gx - s->ground_c[0]) <= s->ground_half && fabsf(gz - s->ground_c[1]) <= s->ground_half) tg = t;
            }
            set_ray16(&rh.ray, l, cam->eye, d, tg);
            rh.hit.geomID[l] = rh.hit.primID[l] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect16(valid, s->scene, &coherent, &rh);

        /* Surfaces, and rays toward the sun. */
        for (int l = 0; l < LANES; l++) {
            lit[l] = 0;
            direct[l] = 0;
            if (!valid[l]) continue;
            Surface *f = &sf[l];
            if (rh.hit.geomID[l] != RTC_INVALID_GEOMETRY_ID) mesh_surface(s, &rh, l, dirs[l], f);
            else if (rh.ray.tfar[l] < INFINITY) {
                ground_surface(s, rh.ray.tfar[l], dirs[l], f);
                sky(dirs[l], f->bg);
            } else {
                f->what = SKY;
                sky(dirs[l], f->bg);
                continue;
            }
            float ndl = dot3(f->sn, s->sun), o[3];
            if (ndl > 0) {
                direct[l] = ndl;
                for (int c = 0; c < 3; c++) o[c] = f->p[c] + f->n[c] * s->eps;
            } else if (f->thin && ndl < 0) { /* light through the leaf */
                direct[l] = -0.35f * ndl;
                for (int c = 0; c < 3; c++) o[c] = f->p[c] - f->n[c] * s->eps;
            } else continue;
            lit[l] = -1;
            set_ray16(&sr, l, o, s->sun, INFINITY);
        }
        if (s->shadows >= 0) {
            rtcOccluded16(lit, s->scene, &coherent, &sr);
            for (int l = 0; l < LANES; l++)
                if (lit[l] && sr.tfar[l] < 0) direct[l] = 0;
        }

        /* Ambient occlusion: cosine-weighted, stratified in azimuth over the pixel's samples. */
        float tan1[LANES][3], tan2[LANES][3], org[LANES][3];
        for (int l = 0; l < LANES; l++) {
            open_valid[l] = valid[l] && sf[l].what != SKY ? -1 : 0;
            open[l] = 0;
            if (!open_valid[l] || !s->ao) continue;
            basis(sf[l].n, tan1[l], tan2[l]);
            for (int c = 0; c < 3; c++) org[l][c] = sf[l].p[c] + sf[l].n[c] * s->eps;
        }
        for (int i = 0; i < s->ao; i++) {
            for (int l = 0; l < LANES; l++) {
                if (!open_valid[l]) continue;
                const float *n = sf[l].n, *t = tan1[l], *b = tan2[l];
                uint64_t bits = rng_next(&rng[l]); /* two 24-bit uniforms */
                float r1 = (float)(bits >> 40) * 0x1p-24f, u2 = (float)(bits & 0xffffff) * 0x1p-24f;
                float u1 = ((float)i + ((float)k + r1) / (float)s->samples) / (float)s->ao;
                float r = sqrtf(u2), z = sqrtf(1 - u2), cp, sp;
                turn(u1, &cp, &sp);
                cp *= r, sp *= r;
                float d[3] = {t[0] * cp + b[0] * sp + n[0] * z, t[1] * cp + b[1] * sp + n[1] * z,
                              t[2] * cp + b[2] * sp + n[2] * z};
                set_ray16(&sr, l, org[l], d, s->ao_dist);
            }
            rtcOccluded16(open_valid, s->scene, &incoherent, &sr);
            for (int l = 0; l < LANES; l++)
                if (open_valid[l] && sr.tfar[l] >= 0) open[l]++;
        }

        for (int l = 0; l < LANES; l++) {
            if (!valid[l]) continue;
            const Surface *f = &sf[l];
            if (f->what == SKY) {
                for (int c = 0; c < 3; c++) acc[l][c] += f->bg[c];
                continue;
            }
            float ao = s->ao ? (float)open[l] / (float)s->ao : 1;
            for (int c = 0; c < 3; c++) {
                float v = f->albedo[c] * (sun_rgb[c] * direct[l] + sky_rgb[c] * ao);
                if (f->what == GROUND) v += f->fog * (f->bg[c] - v);
                acc[l][c] += v;
            }
        }
    }
}

static void render_tile(Scene *s, int tile) {
    int x0 = (tile % s->tiles_x) * TILE, y0 = (tile / s->tiles_x) * TILE;
    float acc[LANES][3];
    float inv = 1.0f / (float)s->samples;
    for (int by = y0; by < y0 + TILE && by < s->height; by += BLOCK)
        for (int bx = x0; bx < x0 + TILE && bx < s->width; bx += BLOCK) {
            render_block(s, bx, by, acc);
            for (int l = 0; l < LANES; l++) {
                int x = bx + l % BLOCK, y = by + l / BLOCK;
                if (x >= s->width || y >= s->height) continue;
                uint8_t *o = s->out + 3 * ((size_t)y * (size_t)s->width + (size_t)x);
                for (int c = 0; c < 3; c++) {
                    float v = acc[l][c] * inv;
                    v = v / (1 + 0.12f * v); /* a gentle shoulder for sunlit highlights */
                    v = v < 0 ? 0 : v > 1 ? 1 : v;
                    o[c] = s->lut[(int)(v * 4096 + 0.5f)];
                }
            }
        }
}

/* Embree wants denormals flushed to zero (much faster); each worker sets it for itself and
 * the calling thread puts its own mode back afterwards. */
static unsigned fast_floats(void) {
#ifdef HAVE_MXCSR
    unsigned old = _mm_getcsr();
    _mm_setcsr(old | 0x8040); /* flush to zero, denormals are zero */
    return old;
#else
    return 0;
#endif
}

static void restore_floats(unsigned old) {
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

static void *worker(void *arg) {
    Scene *s = arg;
    fast_floats();
    render_tiles(s);
    return NULL;
}

static void scene_free(Scene *s) {
    if (s->scene) rtcReleaseScene(s->scene);
    if (s->dev) rtcReleaseDevice(s->dev);
    for (int i = 0; i < 4; i++) texture_free(&s->tex[i]);
    free(s->tri_mat);
    free(s->pos_copy);
    free(s);
}

static int cpu_count(void) {
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > 256 ? 256 : (int)n;
}

/* Textures are made on threads of their own while Embree builds its hierarchy. */
typedef struct TexJob {
    Texture *tex;
    int kind;
    bool ok;
    bool started;
    pthread_t thread;
} TexJob;

static void *tex_job(void *arg) {
    TexJob *j = arg;
    j->ok = texture_build(j->tex, j->kind, TEX_SIZE);
    return NULL;
}

/* Embree: the mesh as one triangle geometry on the mesh's own arrays. */
static int build_scene(Scene *s, int threads, FILE *diag) {
    const SylMesh *m = s->m;
    size_t ntri = m ? m->nidx / 3 : 0;
    if (m && !coord_check(m->pos, m->nverts, 3, "the model", diag)) return SYL_EMODEL;
    char config[64];
    snprintf(config, sizeof config, "threads=%d,verbose=0", threads);
    s->dev = rtcNewDevice(config);
    if (!s->dev) {
        if (diag) fprintf(diag, "sylva: error: render: cannot start Embree (error %d)\n", (int)rtcGetDeviceError(NULL));
        return SYL_ELIMIT;
    }
    rtcSetDeviceErrorFunction(s->dev, embree_error, diag);
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
        if (m->vert_cap <= m->nverts) {
            s->pos_copy = malloc((m->nverts * 3 + 4) * sizeof(float));
            if (!s->pos_copy) return SYL_ELIMIT;
            memcpy(s->pos_copy, m->pos, m->nverts * 3 * sizeof(float));
            memset(s->pos_copy + m->nverts * 3, 0, 4 * sizeof(float));
            pos = s->pos_copy;
        }
        RTCGeometry geom = rtcNewGeometry(s->dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, pos, 0, 3 * sizeof(float),
                                   m->nverts);
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m->idx, 0, 3 * sizeof(uint32_t),
                                   ntri);
        rtcCommitGeometry(geom);
        rtcAttachGeometry(s->scene, geom);
        rtcReleaseGeometry(geom);
    }
    rtcCommitScene(s->scene);
    return rtcGetDeviceError(s->dev) == RTC_ERROR_NONE ? SYL_OK : SYL_ELIMIT;
}

static int render_checked(const SylMesh *m, const SylRenderOptions *opt, uint8_t *rgb);

/* Embree's BVH, its copy of the positions, the textures and the picture, counted against
 * the memory budget before any is built: about 150 bytes a triangle. */
int syl_render(const SylMesh *m, const SylRenderOptions *opt, uint8_t *rgb) {
    static const SylRenderOptions defaults = {0};
    if (!opt) opt = &defaults;
    Budget own;
    budget_init(&own, opt->max_memory);
    Budget *mem = opt->budget ? opt->budget : &own;
    uint64_t w = opt->width > 0 ? (uint64_t)opt->width : 1024, h = opt->height > 0 ? (uint64_t)opt->height : 1024;
    uint64_t tris = m ? m->nidx / 3 : 0, need = tris * 150 + (m ? m->nverts * 16 : 0) + w * h * 3 + (4u << 20);
    if (!budget_charge(mem, need)) {
        if (opt->diag)
            fprintf(opt->diag, "sylva: error: rendering %llu triangles would need about %llu MB, more than "
                               "--max-memory allows (%llu MB in all); raise the limit with --max-memory\n",
                    (unsigned long long)tris, (unsigned long long)(need >> 20),
                    (unsigned long long)budget_limit_mb(mem));
        return SYL_ELIMIT;
    }
    int st = render_checked(m, opt, rgb);
    budget_release(mem, need);
    return st;
}

static int render_checked(const SylMesh *m, const SylRenderOptions *opt, uint8_t *rgb) {
    FILE *diag = opt->diag;
    int width = opt->width > 0 ? opt->width : 1024, height = opt->height > 0 ? opt->height : 1024;
    if (opt->width < 0 || opt->height < 0 || width > 65536 || height > 65536 ||
        (size_t)width * (size_t)height > (size_t)1 << 28) {
        if (diag) fprintf(diag, "sylva: error: render: picture size %d x %d out of range\n", width, height);
        return SYL_EUSAGE;
    }
    size_t ntri = m ? m->nidx / 3 : 0;
    if (ntri > 0xffffffffu) {
        if (diag) fprintf(diag, "sylva: error: render: too many triangles\n");
        return SYL_ELIMIT;
    }
    for (size_t i = 0; i < ntri * 3; i++)
        if (m->idx[i] >= m->nverts) {
            if (diag) fprintf(diag, "sylva: error: render: mesh index %u out of range\n", m->idx[i]);
            return SYL_EUSAGE;
        }
    Scene *s = calloc(1, sizeof *s);
    if (!s) {
        if (diag) fprintf(diag, "sylva: error: render: out of memory\n");
        return SYL_ELIMIT;
    }
    s->m = m;
    s->width = width;
    s->height = height;
    s->samples = opt->samples > 0 ? (opt->samples > MAX_SAMPLES ? MAX_SAMPLES : opt->samples) : 4;
    /* Ambient occlusion rays are shared among a pixel's samples: each takes its share. */
    int ao = opt->ao_samples < 0 ? 0 : opt->ao_samples == 0 ? 8 : opt->ao_samples > MAX_AO ? MAX_AO : opt->ao_samples;
    s->ao = ao ? (ao + s->samples - 1) / s->samples : 0;
    s->shadows = opt->shadows;
    s->out = rgb;
    int threads = opt->threads > 0 ? opt->threads : cpu_count();
    if (threads > 256) threads = 256;
    render_camera(m, opt->view, width, height, &s->cam);

    /* Materials, scale, light, samples. */
    for (int i = 0; i < 256; i++) {
        for (int c = 0; c < 3; c++) s->mat_lin[i][c] = srgb_to_linear(m ? m->materials[i].rgb[c] : 0.5f);
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
    s->pixel_angle = 2 * s->cam.tany / (float)height;
    float sun[3] = {0.4f, 1.0f, 0.3f};
    normalize3(sun);
    memcpy(s->sun, sun, sizeof sun);
    for (int k = 0; k < s->samples; k++) { /* the R2 sequence: well spread for any count */
        float a = 0.5f + 0.7548776662f * (float)k, b = 0.5f + 0.5698402909f * (float)k;
        s->sub[k][0] = a - floorf(a);
        s->sub[k][1] = b - floorf(b);
    }
    for (int i = 0; i <= 4096; i++) s->lut[i] = (uint8_t)lrintf(255 * linear_to_srgb((float)i / 4096));

    /* Textures (of the kinds in use, and grass) while Embree builds. */
    TexJob jobs[4];
    int njobs = 0;
    bool used[4] = {false, false, false, true};
    for (int g = 0; m && g < m->ngroups; g++) {
        int k = m->materials[m->groups[g].material].kind;
        if (k <= SYL_MATERIAL_FLOWER) used[k] = true;
    }
    for (int k = 0; k < 4; k++)
        if (used[k]) jobs[njobs++] = (TexJob){.tex = &s->tex[k], .kind = k == 3 ? -1 : k};
    for (int j = 0; j < njobs; j++)
        jobs[j].started = threads > 1 && pthread_create(&jobs[j].thread, NULL, tex_job, &jobs[j]) == 0;
    int status = build_scene(s, threads, diag);
    if (status == SYL_ELIMIT && diag) fprintf(diag, "sylva: error: render: cannot build the scene\n");
    for (int j = 0; j < njobs; j++) {
        if (jobs[j].started) pthread_join(jobs[j].thread, NULL);
        else tex_job(&jobs[j]);
        if (!jobs[j].ok && !status) {
            if (diag) fprintf(diag, "sylva: error: render: out of memory\n");
            status = SYL_ELIMIT;
        }
    }
    if (status) {
        scene_free(s);
        return status;
    }

    /* Tiles to the workers; this thread works too. */
    s->progress = opt->progress;
    s->user = opt->user;
    pthread_mutex_init(&s->progress_lock, NULL);
    s->tiles_x = (width + TILE - 1) / TILE;
    s->ntiles = s->tiles_x * ((height + TILE - 1) / TILE);
    if (threads > s->ntiles) threads = s->ntiles;
    pthread_t tid[256];
    int started = 0;
    for (int i = 1; i < threads; i++)
        if (pthread_create(&tid[started], NULL, worker, s) == 0) started++;
    unsigned csr = fast_floats();
    render_tiles(s);
    restore_floats(csr);
    for (int i = 0; i < started; i++) pthread_join(tid[i], NULL);
    pthread_mutex_destroy(&s->progress_lock);
    scene_free(s);
    return SYL_OK;
}

int syl_render_png(const SylMesh *m, const SylRenderOptions *opt, const char *path) {
    static const SylRenderOptions defaults = {0};
    if (!opt) opt = &defaults;
    int w = opt->width > 0 ? opt->width : 1024, h = opt->height > 0 ? opt->height : 1024;
    uint8_t *rgb = malloc((size_t)w * (size_t)h * 3);
    if (!rgb) {
        if (opt->diag) fprintf(opt->diag, "sylva: error: render: out of memory\n");
        return SYL_ELIMIT;
    }
    int status = syl_render(m, opt, rgb);
    if (!status) status = syl_write_png(path, rgb, w, h, opt->diag);
    free(rgb);
    return status;
}
