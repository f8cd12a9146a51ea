/* What one render shares between its set-up (render.c) and its shading (shade.c). */
#ifndef SYL_RENDER_SCENE_H
#define SYL_RENDER_SCENE_H
#include "util/lazy_embree.h"
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>

#include "render/render_internal.h"
#include "texture/texture.h"

enum { TILE = 32, MAX_SAMPLES = 64, MAX_AO = 64, TEX_SIZE = 256 };

typedef struct AlphaTest AlphaTest; /* alphatest.c */

typedef struct Scene {
    const SylMesh *m;
    RenderCamera cam;
    RTCDevice dev;
    RTCScene scene;
    float *pos_copy;            /* when the mesh's vertex array has no room for Embree's padding */
    uint8_t *tri_mat;           /* material of each triangle */
    uint32_t (*quad_index)[4];  /* NULL, or the triangles paired into quads (quads.c) ... */
    uint32_t (*quad_halves)[2]; /* ... and the triangles each quad is made of */
    AlphaTest *alphatest;       /* leaf cards' and clusters' alpha (NULL: none) */
    Texture tex[4];             /* bark, leaf, flower, grass */
    Texture img[SYL_IMAGES_MAX]; /* the mesh's images of the model's own, those in use */
    int8_t mat_img[256];        /* per material: the image it wears (render_material_image), -1: none */
    float mat_lin[256][3];      /* material colours in linear light */
    uint8_t mat_kind[256];
    float grass_lin[3];
    float size, eps, ao_dist, fog_dist, ground_y, ground_half, ground_c[2], grass_tile;
    float pixel_angle;
    float shadow_far;           /* a sun ray's length: INFINITY, or with instances the scene's
                                   reach (a finite ray through each instance's transform) */
    float sun[3];
    int width, height, samples, ao, shadows;
    float sub[MAX_SAMPLES][2];  /* sub-pixel sample positions */
    uint8_t lut[4097];          /* linear 0..1 in 4096 steps -> sRGB byte */
    uint8_t *out;
    uint8_t *alpha;             /* NULL, or coverage per pixel */
    uint8_t *normal;            /* NULL, or normal and depth per pixel */
    bool ground, unlit, adaptive;
    bool boxed;                 /* box: the framed mesh's bounds, measured for the first view */
    float box[2][3];
    /* The picture may be a window of a bigger one (syl_render_draw_instances' tile): pixel (x, y)
     * of out is (x + ox, y + oy) of a full_w x full_h picture. */
    int ox, oy, full_w, full_h;
    /* Instances (instances.c): Embree instance i draws proto[inst_proto[i]], turned about y
     * by inst_cs[i] (cos, sin) and scaled by inst_scale[i]; each proto has its materials. */
    const SylMesh **proto;
    uint8_t **proto_tri_mat;
    float (*proto_lin)[256][3];
    uint8_t (*proto_kind)[256];
    int8_t (*proto_img)[256]; /* per material: its image in img[] (render_material_image), -1: none */
    const uint32_t *inst_proto;
    const float (*inst_cs)[2];
    const float *inst_scale;
    int tiles_x, ntiles;
    atomic_int next_tile, tiles_done;
    /* Whichever thread finishes a tile reports, under the lock: serial, increasing calls. */
    void (*progress)(void *user, double fraction);
    void *user;
    pthread_mutex_t progress_lock;
} Scene;

/* render.c's pieces that instances.c shares. */
void render_set_lighting(Scene *s); /* materials of s->m, scale from s->cam's bounds, the sun */
void render_all_tiles(Scene *s, int threads, const SylRenderOptions *opt);
/* Let rays through the transparent parts of s->m's leaf cards or clusters (on g, its
 * geometry, before it is committed). SYL_OK or SYL_ELIMIT. */
int render_alpha_test(Scene *s, RTCGeometry g);
/* The same for any mesh m whose triangles' materials are tri_mat (which must outlive it), on g
 * made of triangles (halves NULL) or of quads (halves: their triangles, render_quad_hit): *out
 * the test to free() after the render (NULL: m has no leaf cards or clusters). */
int render_alpha_attach(const SylMesh *m, const uint8_t *tri_mat, const uint32_t (*halves)[2], RTCGeometry g,
                        AlphaTest **out);
/* The image of the model's own material i of m is drawn with (SylMaterial.image; leaf clusters
 * draw their own cards): its index in m->images, -1 when none. */
int render_material_image(const SylMesh *m, int i);
/* t: image g decoded and mip-mapped for the shader. SYL_OK, or SYL_ELIMIT (reported). */
int render_image_texture(Texture *t, const SylImage *g, const SylSink *sink);
void render_alpha_free(AlphaTest *at);
/* Release a scene: its Embree scene and device, textures and copies. */
void render_scene_free(Scene *s);
int render_cpu_count(void);
void render_embree_error(void *user, enum RTCError code, const char *msg);

/* The mesh's triangles (tri_mat their materials) as Embree quads: index[q], the quad's
 * corners, and halves[q], its triangles for render_quad_hit; SYL_OK or SYL_ELIMIT. */
int render_quads(const SylMesh *m, const uint8_t *tri_mat, uint32_t (**index)[4], uint32_t (**halves)[2],
                 size_t *nquads);
/* Embree's hit of quad *prim at (*u, *v) as the hit of its triangle: the triangle's index
 * and barycentric u, v (the weights of its corners 1 and 2). */
void render_quad_hit(const uint32_t (*halves)[2], unsigned *prim, float *u, float *v);

/* Shade tile number `tile` (TILE x TILE pixels, row by row) into s->out. */
void render_tile(const Scene *s, int tile);

static inline float dot3(const float a[3], const float b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static inline void normalize3(float v[3]) {
    float l = sqrtf(dot3(v, v));
    if (l > 0) {
        float k = 1 / l;
        v[0] *= k, v[1] *= k, v[2] *= k;
    }
}

#endif
