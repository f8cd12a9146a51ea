/* The renderer's shading: a tile's pixels from packets of sixteen rays through Embree. */

/* Each camera ray finds a surface (the mesh with its texture, the ground, or the sky), which
 * is lit by the sun (with a shadow ray) and the sky (with ambient occlusion). A pixel's value
 * depends only on its coordinates. */
#include <math.h>
#include <string.h>

#include "render/scene.h"
#include "util/rng.h"

static const float sun_rgb[3] = {2.35f, 2.20f, 1.95f};
static const float sky_rgb[3] = {0.50f, 0.60f, 0.78f};     /* ambient light from the sky */
static const float horizon[3] = {0.62f, 0.74f, 0.90f};     /* background, linear */
static const float zenith[3] = {0.12f, 0.27f, 0.62f};

/* Two unit vectors perpendicular to n (Duff et al. 2017). */
static inline void basis(const float n[3], float t[3], float b[3]) {
    float s = copysignf(1.0f, n[2]);
    float a = -1.0f / (s + n[2]), c = n[0] * n[1] * a;
    t[0] = 1 + s * n[0] * n[0] * a, t[1] = s * c, t[2] = -s * n[0];
    b[0] = c, b[1] = s + n[1] * n[1] * a, b[2] = -n[1];
}

/* cos and sin of 2 pi u for u in 0..1, to about 1e-6: a polynomial on an octant, so it is
 * quick and the same everywhere. */
static inline void sincos_2pi(float u, float *c, float *s) {
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
enum { BLOCK = SYL_RENDER_BLOCK, LANES = BLOCK * BLOCK };

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

/* The shading normal as n * 0.5 + 0.5, and the depth across the framed sphere. */
static void normal_depth(const Scene *s, const Surface *f, float t, uint8_t out[4]) {
    for (int c = 0; c < 3; c++) out[c] = (uint8_t)lrintf(127.5f * (f->sn[c] + 1));
    float z = s->cam.depth > 0 ? (t - s->cam.near) / s->cam.depth : 0;
    out[3] = (uint8_t)lrintf(255 * (z < 0 ? 0 : z > 1 ? 1 : z));
}

/* Texture level of detail: log2 of texels per sample footprint. */
static inline float lod_of(const Scene *s, float t, float cosv, float uv_per_world, int tex_size) {
    float c = cosv > 0.05f ? cosv : 0.05f;
    float texels = t * s->pixel_angle / (c * sqrtf((float)s->samples)) * uv_per_world * (float)tex_size;
    return texels > 1 ? log2f(texels) : 0;
}

/* Fill sf from lane l of a packet that hit the mesh. */
static inline void turn(const float cs[2], float v[3]) {
    float x = v[0], z = v[2];
    v[0] = cs[0] * x + cs[1] * z, v[2] = -cs[1] * x + cs[0] * z;
}

static void mesh_surface(const Scene *s, const struct RTCRayHit16 *rh, int l, const float d[3], Surface *sf) {
    const SylMesh *m = s->m;
    const uint8_t *tri_mat = s->tri_mat;
    const float(*mat_lin)[3] = s->mat_lin;
    const uint8_t *mat_kind = s->mat_kind;
    const int8_t *mat_img = s->mat_img;
    const float *cs = NULL;
    float scale = 1;
    unsigned inst = rh->hit.instID[0][l];
    if (inst != RTC_INVALID_GEOMETRY_ID && s->proto) { /* an instance: its prototype, turned */
        uint32_t k = s->inst_proto[inst];
        m = s->proto[k], tri_mat = s->proto_tri_mat[k], mat_lin = s->proto_lin[k], mat_kind = s->proto_kind[k];
        mat_img = s->proto_img[k];
        cs = s->inst_cs[inst], scale = s->inst_scale[inst];
    }
    float t = rh->ray.tfar[l], u = rh->hit.u[l], v = rh->hit.v[l], w = 1 - u - v;
    uint32_t tri = rh->hit.primID[l];
    const uint32_t *ix = m->idx + 3 * (size_t)tri;
    const float *e = s->cam.eye;
    sf->what = MESH;
    for (int c = 0; c < 3; c++) sf->p[c] = e[c] + t * d[c];
    float *ng = sf->n, *sn = sf->sn;
    if (cs) { /* Embree gives an instance's normal in its own space: from the triangle, turned */
        const float *a = m->pos + 3 * (size_t)ix[0], *b = m->pos + 3 * (size_t)ix[1], *c = m->pos + 3 * (size_t)ix[2];
        float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        ng[0] = e1[1] * e2[2] - e1[2] * e2[1], ng[1] = e1[2] * e2[0] - e1[0] * e2[2], ng[2] = e1[0] * e2[1] - e1[1] * e2[0];
        turn(cs, ng);
    } else ng[0] = rh->hit.Ng_x[l], ng[1] = rh->hit.Ng_y[l], ng[2] = rh->hit.Ng_z[l];
    normalize3(ng);
    bool flip = dot3(ng, d) > 0; /* both sides of a surface are drawn */
    if (flip) ng[0] = -ng[0], ng[1] = -ng[1], ng[2] = -ng[2];
    if (m->nrm) {
        const float *n0 = m->nrm + 3 * (size_t)ix[0], *n1 = m->nrm + 3 * (size_t)ix[1], *n2 = m->nrm + 3 * (size_t)ix[2];
        for (int c = 0; c < 3; c++) sn[c] = w * n0[c] + u * n1[c] + v * n2[c];
        if (cs) turn(cs, sn);
        if (flip) sn[0] = -sn[0], sn[1] = -sn[1], sn[2] = -sn[2];
        normalize3(sn);
        if (!(dot3(sn, d) < 0) || !(dot3(sn, ng) > 0)) memcpy(sn, ng, 3 * sizeof *sn);
    } else memcpy(sn, ng, 3 * sizeof *sn);
    int mat = tri_mat[tri], kind = mat_kind[mat];
    memcpy(sf->albedo, mat_lin[mat], sizeof sf->albedo);
    sf->thin = kind == SYL_MATERIAL_LEAF || kind == SYL_MATERIAL_FLOWER;
    if (m->uv && kind <= SYL_MATERIAL_FLOWER) {
        const float *a = m->uv + 2 * (size_t)ix[0], *b = m->uv + 2 * (size_t)ix[1], *c = m->uv + 2 * (size_t)ix[2];
        float tu = w * a[0] + u * b[0] + v * c[0], tv = w * a[1] + u * b[1] + v * c[1];
        /* uv units per world unit, from the triangle's areas in uv and in space */
        const float *p0 = m->pos + 3 * (size_t)ix[0], *p1 = m->pos + 3 * (size_t)ix[1], *p2 = m->pos + 3 * (size_t)ix[2];
        float e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        float cr[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        float aw = sqrtf(dot3(cr, cr)) * scale * scale;
        float auv = fabsf((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
        float density = aw > 0 ? sqrtf(auv / aw) : 0;
        const Texture *tx = mat_img[mat] >= 0 ? &s->img[mat_img[mat]] : &s->tex[kind];
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

/* Adaptive: after one sample each, the pixels of a mixed block that take the others — those
 * with a neighbour in the block (of the 8 around) that disagrees with them on hitting the mesh.
 * A pixel whose neighbours all agree is almost surely inside or outside (its alpha 0 or 255). */
static void edge_pixels(const int valid[LANES], const int hits[LANES], int more[LANES]) {
    for (int l = 0; l < LANES; l++) {
        int bx = l % BLOCK, by = l / BLOCK, edge = 0;
        for (int ny = by - 1; ny <= by + 1; ny++)
            for (int nx = bx - 1; nx <= bx + 1; nx++) {
                int j = ny * BLOCK + nx;
                if (nx >= 0 && ny >= 0 && nx < BLOCK && ny < BLOCK && valid[j] && !hits[j] != !hits[l]) edge = 1;
            }
        more[l] = edge;
    }
}

/* Render the pixels of the block at (x0, y0) into acc (linear light, summed over samples),
 * with the samples each pixel took in taken (fewer than s->samples only when adaptive). */
static void render_block(const Scene *s, int x0, int y0, float acc[LANES][3], int hits[LANES], uint8_t nd[LANES][4],
                         int taken[LANES]) {
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
    /* Impostor views (adaptive) look into foliage of sub-pixel leaves: a packet's rays part
     * within a few levels of the hierarchy, and Embree's incoherent mode (single rays once
     * few lanes share a node) takes about 10% less time there. */
    struct RTCIntersectContext *camera_rays = s->adaptive ? &incoherent : &coherent;
    int more[LANES]; /* the pixels still sampled */
    for (int l = 0; l < LANES; l++) more[l] = 1;
    memset(acc, 0, LANES * sizeof *acc);
    memset(hits, 0, LANES * sizeof *hits);
    memset(nd, 0, LANES * sizeof *nd);
    int k = 0;
    for (; k < s->samples; k++) {
        if (k == 1 && s->adaptive) { /* one sample each so far: do they all agree? */
            int seen = 0, n = 0;
            for (int l = 0; l < LANES; l++) seen += valid[l] && hits[l], n += valid[l] != 0;
            if (seen == 0 || seen == n) break;
            edge_pixels(valid, hits, more);
        }
        /* Camera rays, and the ground by hand (a plane: tfar stops Embree there). */
        for (int l = 0; l < LANES; l++) {
            int x = x0 + l % BLOCK, y = y0 + l / BLOCK;
            valid[l] = x < s->width && y < s->height && more[l] ? -1 : 0;
            x += s->ox, y += s->oy; /* in the whole picture: a tile's pixels are the picture's */
            rng[l] = rng_stream(0x5e1fa, (uint64_t)y * (uint64_t)s->full_w + (uint64_t)x, 0, (uint64_t)k);
            float sx = (2 * ((float)x + s->sub[k][0]) / (float)s->full_w - 1) * cam->tanx;
            float sy = (1 - 2 * ((float)y + s->sub[k][1]) / (float)s->full_h) * cam->tany;
            float *d = dirs[l];
            for (int i = 0; i < 3; i++) d[i] = cam->fwd[i] + sx * cam->right[i] + sy * cam->up[i];
            normalize3(d);
            float tg = INFINITY;
            if (s->ground && d[1] < 0 && cam->eye[1] > s->ground_y) {
                float t = (s->ground_y - cam->eye[1]) / d[1];
                float gx = cam->eye[0] + t * d[0], gz = cam->eye[2] + t * d[2];
                if (fabsf(gx - s->ground_c[0]) <= s->ground_half && fabsf(gz - s->ground_c[1]) <= s->ground_half) tg = t;
            }
            set_ray16(&rh.ray, l, cam->eye, d, tg);
            rh.hit.geomID[l] = rh.hit.primID[l] = rh.hit.instID[0][l] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect16(valid, s->scene, camera_rays, &rh);
        for (int l = 0; s->quad_halves && l < LANES; l++)
            if (valid[l] && rh.hit.geomID[l] != RTC_INVALID_GEOMETRY_ID)
                render_quad_hit(s->quad_halves, &rh.hit.primID[l], &rh.hit.u[l], &rh.hit.v[l]);

        /* Surfaces, and rays toward the sun. */
        for (int l = 0; l < LANES; l++) {
            lit[l] = 0;
            direct[l] = 0;
            if (!valid[l]) continue;
            Surface *f = &sf[l];
            if (rh.hit.geomID[l] != RTC_INVALID_GEOMETRY_ID) {
                mesh_surface(s, &rh, l, dirs[l], f);
                if (!hits[l]++ && s->normal) normal_depth(s, f, rh.ray.tfar[l], nd[l]);
            } else if (rh.ray.tfar[l] < INFINITY) {
                ground_surface(s, rh.ray.tfar[l], dirs[l], f);
                sky(dirs[l], f->bg);
            } else {
                f->what = SKY;
                sky(dirs[l], f->bg);
                continue;
            }
            if (s->unlit) continue; /* albedo only: no light to trace */
            float ndl = dot3(f->sn, s->sun), o[3];
            if (ndl > 0) {
                direct[l] = ndl;
                for (int c = 0; c < 3; c++) o[c] = f->p[c] + f->n[c] * s->eps;
            } else if (f->thin && ndl < 0) { /* light through the leaf */
                direct[l] = -0.35f * ndl;
                for (int c = 0; c < 3; c++) o[c] = f->p[c] - f->n[c] * s->eps;
            } else continue;
            lit[l] = -1;
            set_ray16(&sr, l, o, s->sun, s->shadow_far);
        }
        if (s->shadows >= 0) {
            /* coherent packets through instances hang Embree 3.13: those go as incoherent rays */
            rtcOccluded16(lit, s->scene, s->proto ? &incoherent : &coherent, &sr);
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
                sincos_2pi(u1, &cp, &sp);
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
                for (int c = 0; c < 3; c++) acc[l][c] += s->unlit ? 0 : f->bg[c];
                continue;
            }
            float ao = s->ao ? (float)open[l] / (float)s->ao : 1;
            for (int c = 0; c < 3; c++) {
                float v = f->albedo[c] * (sun_rgb[c] * direct[l] + sky_rgb[c] * ao);
                if (s->unlit) v = f->albedo[c]; /* no ground either: a mesh hit */
                if (f->what == GROUND) v += f->fog * (f->bg[c] - v);
                acc[l][c] += v;
            }
        }
    }
    for (int l = 0; l < LANES; l++) taken[l] = more[l] ? k : 1;
}

void render_tile(const Scene *s, int tile) {
    int x0 = (tile % s->tiles_x) * TILE, y0 = (tile / s->tiles_x) * TILE;
    float acc[LANES][3];
    int hits[LANES], taken[LANES];
    uint8_t nd[LANES][4];
    for (int by = y0; by < y0 + TILE && by < s->height; by += BLOCK)
        for (int bx = x0; bx < x0 + TILE && bx < s->width; bx += BLOCK) {
            render_block(s, bx, by, acc, hits, nd, taken);
            for (int l = 0; l < LANES; l++) {
                int x = bx + l % BLOCK, y = by + l / BLOCK;
                if (x >= s->width || y >= s->height) continue;
                int n = taken[l];
                float inv = 1.0f / (float)n;
                if (s->normal) memcpy(s->normal + 4 * ((size_t)y * (size_t)s->width + (size_t)x), nd[l], 4);
                if (s->alpha) /* coverage: the share of the pixel's samples that saw the plant */
                    s->alpha[(size_t)y * (size_t)s->width + (size_t)x] = (uint8_t)((255 * hits[l] + n / 2) / n);
                uint8_t *o = s->out + 3 * ((size_t)y * (size_t)s->width + (size_t)x);
                for (int c = 0; c < 3; c++) {
                    /* unlit: the colour of what was hit, not mixed with the background */
                    float v = acc[l][c] * (s->unlit ? (hits[l] ? 1.0f / (float)hits[l] : 0) : inv);
                    if (!s->unlit) v = v / (1 + 0.12f * v); /* a gentle shoulder for sunlit highlights */
                    v = v < 0 ? 0 : v > 1 ? 1 : v;
                    o[c] = s->lut[(int)(v * 4096 + 0.5f)];
                }
            }
        }
}
