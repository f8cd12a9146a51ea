/* Baking impostors with the renderer: one Embree scene, every view framing the bounding
 * sphere the same way, so a shader can place any view over any other. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sylva/impostor.h"
#include "sylva/render.h"
#include "util/budget.h"
#include "util/diag.h"

/* SylImpostor.store: what the atlases are counted against until syl_impostor_free */
struct SylImpostorStore {
    SylBudget *budget;
    uint64_t charged;
};

void syl_impostor_direction(int grid, int col, int row, float d[3]) {
    float ex = 2 * ((float)col + 0.5f) / (float)grid - 1, ey = 2 * ((float)row + 0.5f) / (float)grid - 1;
    float tx = 0.5f * (ex + ey), ty = 0.5f * (ex - ey);
    d[0] = tx, d[1] = 1 - fabsf(tx) - fabsf(ty), d[2] = ty;
    float l = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int c = 0; c < 3; c++) d[c] /= l;
}

/* Render n views of size x size into RGBA pictures (colour, coverage) and normal+depth. */
static int bake_views(const SylMesh *m, const SylImpostorOptions *o, int n, const float (*dirs)[3], int size,
                      uint8_t **rgba, uint8_t **nd) {
    size_t px = (size_t)size * (size_t)size * (size_t)n;
    uint8_t *rgb = malloc(3 * px), *alpha = malloc(px);
    *rgba = malloc(4 * px);
    *nd = malloc(4 * px);
    int status = rgb && alpha && *rgba && *nd ? SYL_OK : SYL_ELIMIT;
    /* Albedo, for the engine to light with the normals; 4 samples for smooth alpha edges. */
    SylRenderOptions ro = {.width = size, .height = size, .samples = 4, .ao_samples = -1, .shadows = -1, .unlit = true,
                           .ground = -1,
                           .threads = o->threads, .diag = o->diag, .sink = o->sink, .alpha = alpha, .normal = *nd, .adaptive = true};
    if (!status) status = syl_render_draw_views(m, &ro, n, dirs, rgb);
    for (size_t i = 0; !status && i < px; i++) {
        bool seen = alpha[i] > 0; /* outside the plant: black, so filtering bleeds no sky */
        for (int c = 0; c < 3; c++) (*rgba)[4 * i + (size_t)c] = seen ? rgb[3 * i + (size_t)c] : 0;
        (*rgba)[4 * i + 3] = alpha[i];
    }
    free(rgb), free(alpha);
    return status;
}

/* Copy view v (size x size, 4 bytes a pixel) to cell (col, row) of an atlas w pixels wide. */
static void place(uint8_t *atlas, int w, const uint8_t *views, int v, int size, int col, int row) {
    size_t line = (size_t)size * 4;
    const uint8_t *src = views + line * (size_t)size * (size_t)v;
    for (int y = 0; y < size; y++)
        memcpy(atlas + ((size_t)(row * size + y) * (size_t)w + (size_t)col * (size_t)size) * 4, src + line * (size_t)y,
               line);
}

static void bounds_sphere(const SylMesh *m, float c[3], float *r) {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < m->nverts; i++)
        for (int k = 0; k < 3; k++) lo[k] = fminf(lo[k], m->pos[3 * i + k]), hi[k] = fmaxf(hi[k], m->pos[3 * i + k]);
    float d2 = 0;
    for (int k = 0; k < 3; k++) c[k] = 0.5f * (lo[k] + hi[k]), d2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    *r = 0.5f * sqrtf(d2);
}

/* The billboard quads: for quad k, a front face seen by view 2k and a back face by view
 * 2k + 1, each mapped so u runs along the view's right and v down its up, as the picture. */
static SylMesh *billboard_mesh(const SylMesh *m, int k, const float c[3], float r) {
    SylMesh *b = calloc(1, sizeof *b);
    size_t nv = (size_t)k * 8;
    if (!b) return NULL;
    b->pos = calloc(3 * nv + 4, sizeof *b->pos);
    b->nrm = malloc(3 * nv * sizeof *b->nrm);
    b->uv = malloc(2 * nv * sizeof *b->uv);
    b->idx = malloc((size_t)k * 12 * sizeof *b->idx);
    b->groups = malloc(sizeof *b->groups);
    if (!b->pos || !b->nrm || !b->uv || !b->idx || !b->groups) {
        syl_mesh_free(b);
        return NULL;
    }
    memcpy(b->materials, m->materials, sizeof b->materials);
    b->images = syl_images_ref(m->images);
    b->materials[SYL_IMPOSTOR_MATERIAL] = (SylMaterial){.rgb = {1, 1, 1}, .kind = SYL_MATERIAL_PLAIN};
    b->nmaterials = 256;
    snprintf(b->name, sizeof b->name, "%s", m->name);
    for (int q = 0; q < 2 * k; q++) {
        float th = (float)M_PI * (float)(q / 2) / (float)k, side = q % 2 ? -1.0f : 1.0f;
        float n[3] = {side * sinf(th), 0, side * cosf(th)};
        float right[3] = {n[2], 0, -n[0]}; /* fwd x up with fwd = -n, up = +Y */
        for (int v = 0; v < 4; v++) {
            float u = (float)(v & 1), w = (float)(v >> 1); /* w: 0 top, 1 bottom */
            size_t at = (size_t)q * 4 + (size_t)v;
            for (int a = 0; a < 3; a++)
                b->pos[3 * at + (size_t)a] = c[a] + (2 * u - 1) * r * right[a] + (a == 1 ? (1 - 2 * w) * r : 0);
            memcpy(b->nrm + 3 * at, n, sizeof n);
            b->uv[2 * at] = ((float)q + u) / (float)(2 * k); /* the view's column in the atlas row */
            b->uv[2 * at + 1] = w;
        }
        /* counter-clockwise seen from +n: top-left, bottom-left, bottom-right, top-right */
        uint32_t o = (uint32_t)q * 4, t[6] = {o, o + 2, o + 3, o, o + 3, o + 1};
        memcpy(b->idx + (size_t)q * 6, t, sizeof t);
    }
    b->nverts = nv;
    b->nidx = (size_t)k * 12;
    b->groups[0] = (SylMeshGroup){0, (uint32_t)b->nidx, SYL_IMPOSTOR_MATERIAL};
    b->ngroups = 1;
    return b;
}

int syl_impostor_bake(const SylMesh *m, const SylImpostorOptions *o, SylImpostor *out) {
    memset(out, 0, sizeof *out);
    int g = o->grid > 0 ? o->grid : o->grid < 0 ? 0 : 8, v = o->view > 0 ? o->view : 256, k = o->billboards;
    if (g > 64 || v > 4096 || (k && (k < 2 || k > 4)) || (!g && !k) || !m->nverts) return SYL_EUSAGE;
    int nviews = g * g + 2 * k;
    float (*dirs)[3] = malloc((size_t)nviews * sizeof *dirs);
    if (!dirs) return SYL_ELIMIT;
    for (int row = 0; row < g; row++)
        for (int col = 0; col < g; col++) syl_impostor_direction(g, col, row, dirs[row * g + col]);
    for (int q = 0; q < 2 * k; q++) {
        float th = (float)M_PI * (float)(q / 2) / (float)k, side = q % 2 ? -1.0f : 1.0f;
        float *d = dirs[g * g + q];
        d[0] = side * sinf(th), d[1] = 0, d[2] = side * cosf(th);
    }
    /* the views' pictures (RGB, alpha, RGBA, normal and depth: 12 bytes a pixel), then the
     * two atlases and the billboards' row: counted before anything is drawn */
    size_t side = (size_t)g * (size_t)v;
    uint64_t views = 12ull * (uint64_t)v * (uint64_t)v * (uint64_t)nviews,
             atlases = 8ull * side * side + 8ull * (uint64_t)k * (uint64_t)v * (uint64_t)v;
    struct SylImpostorStore *store = o->budget ? malloc(sizeof *store) : NULL;
    if (o->budget && !store) {
        sink_error(opt_sink(o), "out of memory baking the impostor");
        free(dirs);
        return SYL_ELIMIT;
    }
    if (!budget_charge(o->budget, views + atlases)) {
        sink_error(opt_sink(o),
                   "the impostor would need %llu MB (%d views of %dx%d pixels and a %zux%zu atlas), "
                   "more than --max-memory allows (%llu MB in all); raise the limit with --max-memory, or use a "
                   "smaller --impostor-grid or --impostor-view",
                    (unsigned long long)((views + atlases) >> 20), nviews, v, v, side, side,
                    (unsigned long long)budget_limit_mb(o->budget));
        free(dirs), free(store);
        return SYL_ELIMIT;
    }
    uint8_t *rgba = NULL, *nd = NULL;
    int status = bake_views(m, o, nviews, (const float (*)[3])dirs, v, &rgba, &nd);
    *out = (SylImpostor){.grid = g, .view = v, .size = g * v, .billboards = k, .bb_width = 2 * k * v};
    if (store) *store = (struct SylImpostorStore){o->budget, views + atlases}, out->store = store;
    bounds_sphere(m, out->centre, &out->radius);
    if (!status) {
        out->color = g ? malloc(4 * side * side) : NULL;
        out->normal = g ? malloc(4 * side * side) : NULL;
        out->bb_color = k ? malloc(4 * (size_t)out->bb_width * (size_t)v) : NULL;
        if (k) out->bb_mesh = billboard_mesh(m, k, out->centre, out->radius);
        if ((g && (!out->color || !out->normal)) || (k && (!out->bb_color || !out->bb_mesh))) status = SYL_ELIMIT;
    }
    for (int row = 0; !status && row < g; row++)
        for (int col = 0; col < g; col++) {
            place(out->color, g * v, rgba, row * g + col, v, col, row);
            place(out->normal, g * v, nd, row * g + col, v, col, row);
        }
    for (int q = 0; !status && q < 2 * k; q++) place(out->bb_color, out->bb_width, rgba, g * g + q, v, q, 0);
    free(rgba), free(nd), free(dirs);
    if (status) sink_error(opt_sink(o), "out of memory baking the impostor");
    if (status) syl_impostor_free(out);
    else if (out->store) /* the views are freed */
        budget_release(out->store->budget, views), out->store->charged = atlases;
    return status;
}

void syl_impostor_free(SylImpostor *imp) {
    free(imp->color), free(imp->normal), free(imp->bb_color);
    syl_mesh_free(imp->bb_mesh);
    if (imp->store) budget_release(imp->store->budget, imp->store->charged);
    free(imp->store);
    memset(imp, 0, sizeof *imp);
}
