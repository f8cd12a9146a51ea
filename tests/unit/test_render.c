/* The renderer and the procedural textures: reproducible pictures of the right size, framing,
 * shadows on the ground, and textures with the structure seed 001 describes. Pictures are
 * small so the suite stays fast under the sanitizers. */
#include <math.h>
#include <stdbool.h>
#include <sys/stat.h>
#include <unistd.h>

#include "unit.h"
#include "render/render_internal.h"
#include "render_fixtures.h"
#include "texture/texture.h"

enum { W = 128, H = 128, MAT_RED = 3 };

static uint8_t *render(const SylMesh *m, SylRenderOptions o) {
    int w = o.width ? o.width : W, h = o.height ? o.height : H;
    o.width = w;
    o.height = h;
    uint8_t *rgb = malloc((size_t)w * h * 3);
    assert_non_null(rgb);
    assert_int_equal(syl_render_draw_mesh(m, &o, rgb), SYL_OK);
    return rgb;
}

static SylMesh *red_box(const float lo[3], const float hi[3]) {
    SylMesh *m = synth_new();
    assert_non_null(m);
    assert_true(synth_box(m, lo, hi, MAT_RED));
    return m;
}

/* Pixels that are clearly the red test material (the ground is green, the sky blue). */
static int red_pixels(const uint8_t *rgb, int n) {
    int count = 0;
    for (int i = 0; i < n; i++) {
        int r = rgb[3 * i], g = rgb[3 * i + 1], b = rgb[3 * i + 2];
        count += r > 40 && r > 2 * g && r > 2 * b;
    }
    return count;
}

static double luma_at(const uint8_t *rgb, int w, int h, float x, float y, int radius) {
    double sum = 0;
    int n = 0;
    for (int dy = -radius; dy <= radius; dy++)
        for (int dx = -radius; dx <= radius; dx++) {
            int px = (int)x + dx, py = (int)y + dy;
            if (px < 0 || py < 0 || px >= w || py >= h) continue;
            const uint8_t *p = rgb + 3 * ((size_t)py * w + px);
            sum += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
            n++;
        }
    assert_true(n > 0);
    return sum / n;
}

/* ---- pictures ---- */

static void same_picture_every_time(void **state) {
    (void)state;
    SylMesh *m = synth_tree(4000);
    assert_non_null(m);
    uint8_t *a = render(m, (SylRenderOptions){.threads = 2});
    uint8_t *b = render(m, (SylRenderOptions){.threads = 2});
    assert_memory_equal(a, b, (size_t)W * H * 3);
    free(a);
    free(b);
    syl_mesh_free(m);
}

static void thread_count_does_not_matter(void **state) {
    (void)state;
    SylMesh *m = synth_tree(4000);
    /* an odd size: partial tiles and blocks at the right and bottom edges */
    SylRenderOptions o = {.width = 101, .height = 75, .view = SYL_VIEW_FRONT, .threads = 1};
    uint8_t *a = render(m, o);
    o.threads = 4;
    uint8_t *b = render(m, o);
    o.threads = 3;
    uint8_t *c = render(m, o);
    assert_memory_equal(a, b, (size_t)101 * 75 * 3);
    assert_memory_equal(a, c, (size_t)101 * 75 * 3);
    free(a);
    free(b);
    free(c);
    syl_mesh_free(m);
}

static void png_has_the_requested_size(void **state) {
    (void)state;
    SylMesh *m = synth_tree(1000);
    char dir[] = "/tmp/sylva-render-XXXXXX";
    assert_non_null(mkdtemp(dir));
    char path[128];
    snprintf(path, sizeof path, "%s/p.png", dir);
    SylRenderOptions o = {.width = 96, .height = 64, .samples = 1};
    assert_int_equal(syl_render_write_png(m, &o, path), SYL_OK);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    uint8_t head[24];
    assert_int_equal(fread(head, 1, sizeof head, f), sizeof head);
    fclose(f);
    assert_memory_equal(head, "\x89PNG\r\n\x1a\n", 8);
    assert_memory_equal(head + 12, "IHDR", 4);
    uint32_t w = (uint32_t)head[16] << 24 | head[17] << 16 | head[18] << 8 | head[19];
    uint32_t h = (uint32_t)head[20] << 24 | head[21] << 16 | head[22] << 8 | head[23];
    assert_int_equal(w, 96);
    assert_int_equal(h, 64);
    /* no temporary file is left behind */
    char tmp[160];
    snprintf(tmp, sizeof tmp, "%s/p.png.tmp%ld", dir, (long)getpid());
    assert_int_not_equal(access(tmp, F_OK), 0);
    unlink(path);
    rmdir(dir);
    syl_mesh_free(m);
}

static void bad_sizes_are_refused(void **state) {
    (void)state;
    uint8_t px[3];
    FILE *null = fopen("/dev/null", "w");
    SylRenderOptions o = {.width = -1, .height = 10, .diag = null};
    assert_int_equal(syl_render_draw_mesh(NULL, &o, px), SYL_EUSAGE);
    assert_int_equal(syl_png_write("/nonexistent-dir/x.png", px, 1, 1, &(SylSink){syl_diagnostic_print, null}), SYL_EIO);
    fclose(null);
}

static void box_covers_a_plausible_share(void **state) {
    (void)state;
    SylMesh *m = red_box((float[3]){-1, 0, -1}, (float[3]){1, 2, 1});
    for (int v = SYL_VIEW_ISO; v <= SYL_VIEW_TOP; v++) {
        uint8_t *rgb = render(m, (SylRenderOptions){.view = (SylView)v, .samples = 2, .ao_samples = 4});
        double share = (double)red_pixels(rgb, W * H) / (W * H);
        /* fitted to 80% of the frame: a square face 0.8^2 = 0.64 at most, the iso view's
         * hexagon about half of the frame */
        if (share < 0.25 || share > 0.75) fail_msg("view %d: the box covers %.3f of the frame", v, share);
        free(rgb);
    }
    syl_mesh_free(m);
}

/* Coverage with adaptive sampling: a box seen along +z from 100 radii away covers its face,
 * (2 / (2 sqrt 3))^2 = 1/3 of the frame (times (d / (d - 1))^2 for the face's nearness);
 * a tree's total coverage matches the full sampling's, and its edges stay soft. */
static double coverage(const SylMesh *m, bool adaptive, int *partial) {
    uint8_t alpha[W * H];
    uint8_t *rgb = render(m, (SylRenderOptions){.toward = (const float[3]){0, 0, 1}, .ground = -1, .unlit = true,
                                                 .ao_samples = -1, .shadows = -1, .alpha = alpha, .adaptive = adaptive});
    double sum = 0;
    *partial = 0;
    for (int i = 0; i < W * H; i++) sum += alpha[i] / 255.0, *partial += alpha[i] > 0 && alpha[i] < 255;
    free(rgb);
    return sum / (W * H);
}

static void adaptive_sampling_keeps_coverage(void **state) {
    (void)state;
    SylMesh *box = red_box((float[3]){-1, -1, -1}, (float[3]){1, 1, 1});
    double d = 100 * sqrt(3.0), want = (d / (d - 1)) * (d / (d - 1)) / 3;
    int partial;
    for (int a = 0; a < 2; a++) {
        double got = coverage(box, a, &partial);
        if (fabs(got - want) > 0.01 * want) fail_msg("adaptive %d: the box covers %.4f, want %.4f", a, got, want);
    }
    syl_mesh_free(box);
    SylMesh *tree = synth_tree(3000);
    int soft_full, soft_adaptive;
    double full = coverage(tree, false, &soft_full), adaptive = coverage(tree, true, &soft_adaptive);
    if (fabs(adaptive - full) > 0.03 * full) fail_msg("tree coverage %.4f adaptive, %.4f full", adaptive, full);
    if (soft_adaptive < soft_full / 2) fail_msg("edges: %d partial pixels adaptive, %d full", soft_adaptive, soft_full);
    syl_mesh_free(tree);
}

/* Alpha-tested cards: rays pass where the card's texture is transparent, with Embree's
 * triangles (full sampling) and with the quads the impostor bake pairs them into (adaptive).
 * A 2 x 2 card of the maple shape seen face on: the share of its opaque pixels is the share
 * of the texture's texels with alpha >= 1/2 (the card at the sphere's centre, so every texel
 * is magnified alike), and the two paths agree pixel by pixel. */
static void alpha_tested_card_shows_its_shape(void **state) {
    (void)state;
    SylMesh *card = synth_new();
    assert_true(reserve(card, 4, 6));
    const float n[3] = {0, 0, -1};
    uint32_t v[4];
    for (int k = 0; k < 4; k++)
        v[k] = vert(card, (const float[3]){k & 1 ? 1.0f : -1.0f, k & 2 ? 1.0f : -1.0f, 0}, n, (float)(k & 1),
                    (float)(k >> 1));
    assert_true(tri(card, v[0], v[1], v[3], 1) && tri(card, v[0], v[3], v[2], 1));
    enum { T = 256 };
    uint8_t *tex = malloc(4 * T * T);
    assert_true(syl_leaf_draw_card(SYL_LEAF_MAPLE, T, tex));
    double texels = 0;
    for (int i = 0; i < T * T; i++) texels += tex[4 * i + 3] >= 128;
    free(tex);
    texels /= T * T;
    int partial;
    card->leaves = SYL_LEAVES_MESH;
    double whole = coverage(card, false, &partial);
    card->leaves = SYL_LEAVES_CARDS, card->leaf_shape = SYL_LEAF_MAPLE;
    uint8_t alpha[2][W * H];
    for (int a = 0; a < 2; a++) {
        uint8_t *rgb = render(card, (SylRenderOptions){.toward = (const float[3]){0, 0, 1}, .ground = -1, .unlit = true,
                                                        .ao_samples = -1, .shadows = -1, .alpha = alpha[a],
                                                        .adaptive = a});
        free(rgb);
        double sum = 0;
        for (int i = 0; i < W * H; i++) sum += alpha[a][i] / 255.0;
        double share = sum / (W * H) / whole;
        if (fabs(share - texels) > 0.03 * texels)
            fail_msg("adaptive %d: the card shows %.4f of its area, its texture %.4f", a, share, texels);
    }
    int apart = 0, seen = 0;
    for (int i = 0; i < W * H; i++) {
        seen += alpha[0][i] > 0;
        apart += abs(alpha[0][i] - alpha[1][i]) > 128;
    }
    if (apart > seen / 100) fail_msg("%d of %d pixels differ by more than half between triangles and quads", apart, seen);
    syl_mesh_free(card);
}

static void tree_covers_a_plausible_share(void **state) {
    (void)state;
    SylMesh *m = synth_tree(6000);
    for (int i = 0; i < 3; i++) m->materials[i] = (SylMaterial){.rgb = {0.9f, 0.05f, 0.05f}, .kind = SYL_MATERIAL_PLAIN};
    uint8_t *rgb = render(m, (SylRenderOptions){0});
    double share = (double)red_pixels(rgb, W * H) / (W * H);
    if (share < 0.08 || share > 0.75) fail_msg("the tree covers %.3f of the frame", share);
    free(rgb);
    syl_mesh_free(m);
}

static void framing_fills_about_80_percent(void **state) {
    (void)state;
    SylMesh *m = synth_tree(3000);
    for (int v = SYL_VIEW_ISO; v <= SYL_VIEW_TOP; v++) {
        RenderCamera cam;
        render_camera(m, (SylView)v, 200, 100, &cam);
        float x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
        for (size_t i = 0; i < m->nverts; i++) {
            float x, y;
            assert_true(render_project(&cam, m->pos + 3 * i, &x, &y));
            x0 = fminf(x0, x), x1 = fmaxf(x1, x), y0 = fminf(y0, y), y1 = fmaxf(y1, y);
        }
        /* inside the frame, centred, and 80% of it in the tighter direction */
        assert_true(x0 >= 0 && x1 <= 200 && y0 >= 0 && y1 <= 100);
        double fx = (x1 - x0) / 200, fy = (y1 - y0) / 100, fill = fmax(fx, fy);
        if (fill < 0.78 || fill > 0.802) fail_msg("view %d fills %.3f", v, fill);
        assert_near((x0 + x1) / 2, 100, 2);
        assert_near((y0 + y1) / 2, 50, 1);
    }
    syl_mesh_free(m);
}

/* A table: a slab held up by a leg; the slab's shadow lies on the ground behind the leg,
 * away from the sun (0.4, 1, 0.3). */
static SylMesh *table(void) {
    SylMesh *m = synth_new();
    assert_true(synth_box(m, (float[3]){-0.1f, 0, -0.1f}, (float[3]){0.1f, 1, 0.1f}, 0));
    assert_true(synth_box(m, (float[3]){-1, 1, -1}, (float[3]){1, 1.15f, 1}, 0));
    return m;
}

static void shadow_on_the_ground(void **state) {
    (void)state;
    SylMesh *m = table();
    SylRenderOptions o = {.view = SYL_VIEW_FRONT, .ao_samples = -1};
    uint8_t *lit = render(m, o);
    o.shadows = -1;
    uint8_t *unshadowed = render(m, o);
    RenderCamera cam;
    render_camera(m, SYL_VIEW_FRONT, W, H, &cam);
    /* in the slab's shadow (under it, offset by -0.4, -0.3 per unit of height) and far from it */
    float shade[3] = {-0.45f, 0, 0.5f}, sunny[3] = {0.9f, 0, 1.6f}, x, y;
    assert_true(render_project(&cam, shade, &x, &y));
    double in_shadow = luma_at(lit, W, H, x, y, 1), without = luma_at(unshadowed, W, H, x, y, 1);
    assert_true(render_project(&cam, sunny, &x, &y));
    assert_true(x >= 0 && x < W && y >= 0 && y < H);
    double in_sun = luma_at(lit, W, H, x, y, 1);
    if (!(in_shadow < 0.8 * in_sun)) fail_msg("shadow %.1f, sunlit ground %.1f", in_shadow, in_sun);
    if (!(in_shadow < 0.8 * without)) fail_msg("shadow %.1f, the same spot without shadows %.1f", in_shadow, without);
    free(lit);
    free(unshadowed);
    syl_mesh_free(m);
}

static void ambient_occlusion_darkens_the_foot(void **state) {
    (void)state;
    /* Beside a wall's foot the sky is half hidden; the same spot without AO is brighter. */
    SylMesh *m = red_box((float[3]){-0.2f, 0, -1}, (float[3]){0.2f, 1.5f, 1});
    SylRenderOptions o = {.view = SYL_VIEW_FRONT, .shadows = -1, .ao_samples = 16, .samples = 4};
    uint8_t *with = render(m, o);
    o.ao_samples = -1;
    uint8_t *without = render(m, o);
    RenderCamera cam;
    render_camera(m, SYL_VIEW_FRONT, W, H, &cam);
    float foot[3] = {0.3f, 0, 0.9f}, x, y;
    assert_true(render_project(&cam, foot, &x, &y));
    double a = luma_at(with, W, H, x, y, 1), b = luma_at(without, W, H, x, y, 1);
    if (!(a < b - 3)) fail_msg("with AO %.1f, without %.1f", a, b);
    free(with);
    free(without);
    syl_mesh_free(m);
}

static void empty_mesh_draws_ground_and_sky(void **state) {
    (void)state;
    SylMesh *m = synth_new();
    uint8_t *rgb = render(m, (SylRenderOptions){.view = SYL_VIEW_FRONT, .samples = 1});
    /* top row: sky (blue above green); bottom row: grass (green above blue) */
    const uint8_t *top = rgb + 3 * (W / 2), *bottom = rgb + 3 * ((size_t)(H - 1) * W + W / 2);
    assert_true(top[2] > top[1] && top[2] > top[0]);
    assert_true(bottom[1] > bottom[2] && bottom[1] > bottom[0]);
    free(rgb);
    syl_mesh_free(m);
}

static void bare_meshes_render(void **state) {
    (void)state;
    /* no normals and no uvs: flat shading, untextured — the same red silhouette as with them */
    SylMesh *m = red_box((float[3]){-1, 0, -1}, (float[3]){1, 2, 1});
    uint8_t *full = render(m, (SylRenderOptions){.width = 48, .height = 48, .samples = 1});
    free(m->nrm);
    free(m->uv);
    m->nrm = m->uv = NULL;
    m->store->spare = false; /* and no room past the last vertex: Embree gets a padded copy */
    uint8_t *rgb = render(m, (SylRenderOptions){.width = 48, .height = 48, .samples = 1});
    int bare = red_pixels(rgb, 48 * 48), with = red_pixels(full, 48 * 48);
    assert_true(bare > 48 * 48 / 8);
    assert_true(abs(bare - with) <= 48);
    const uint8_t *c = rgb + 3 * (24 * 48 + 24);
    assert_true(c[0] > 40 && c[0] > 2 * c[1] && c[0] > 2 * c[2]);
    free(rgb);
    free(full);
    syl_mesh_free(m);
    /* no mesh at all: sky at the top, grass at the bottom */
    rgb = render(NULL, (SylRenderOptions){.width = 16, .height = 16, .view = SYL_VIEW_FRONT, .samples = 1});
    const uint8_t *top = rgb + 3 * 8, *bottom = rgb + 3 * (15 * 16 + 8);
    assert_true(top[2] > top[1] && top[2] > top[0]);
    assert_true(bottom[1] > bottom[2] && bottom[1] > bottom[0]);
    free(rgb);
    /* an index past the last vertex is refused */
    m = red_box((float[3]){0, 0, 0}, (float[3]){1, 1, 1});
    m->idx[5] = (uint32_t)m->nverts;
    uint8_t px[16 * 16 * 3];
    FILE *null = fopen("/dev/null", "w");
    assert_int_equal(syl_render_draw_mesh(m, &(SylRenderOptions){.width = 16, .height = 16, .diag = null}, px), SYL_EUSAGE);
    fclose(null);
    syl_mesh_free(m);
}

static void materials_set_the_colours(void **state) {
    (void)state;
    SylMesh *m = red_box((float[3]){-1, 0, -1}, (float[3]){1, 2, 1});
    uint8_t *red = render(m, (SylRenderOptions){.samples = 1, .ao_samples = -1});
    m->materials[MAT_RED].rgb[0] = 0.05f, m->materials[MAT_RED].rgb[2] = 0.9f;
    uint8_t *blue = render(m, (SylRenderOptions){.samples = 1, .ao_samples = -1});
    const uint8_t *r = red + 3 * (H / 2 * W + W / 2), *b = blue + 3 * (H / 2 * W + W / 2);
    assert_true(r[0] > r[2] + 40);
    assert_true(b[2] > b[0] + 40);
    free(red);
    free(blue);
    syl_mesh_free(m);
}

typedef struct ProgressLog {
    double last;
    int calls;
    bool not_increasing;
} ProgressLog;

static void log_progress(void *user, double f) {
    ProgressLog *p = user;
    if (!(f > p->last)) p->not_increasing = true;
    p->last = f;
    p->calls++;
}

static void progress_is_reported(void **state) {
    (void)state;
    SylMesh *m = synth_tree(1000);
    ProgressLog log = {.last = -1};
    uint8_t *rgb = render(m, (SylRenderOptions){.width = 100, .height = 100, .samples = 1, .threads = 3,
                                                 .progress = log_progress, .user = &log});
    /* One call per 32 x 32 tile (4 x 4 of them), whichever thread renders it. */
    assert_int_equal(log.calls, 16);
    assert_false(log.not_increasing);
    assert_true(log.last == 1.0);
    free(rgb);
    syl_mesh_free(m);
}

/* ---- textures ---- */

enum { TS = 128 };

static double luma(const uint8_t *p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

static void textures_are_reproducible(void **state) {
    (void)state;
    static const int kinds[] = {SYL_MATERIAL_BARK, SYL_MATERIAL_LEAF, SYL_MATERIAL_FLOWER, -1};
    uint8_t *a = malloc(TS * TS * 3), *b = malloc(TS * TS * 3), *prev = malloc(TS * TS * 3);
    for (int k = 0; k < 4; k++) {
        syl_texture_draw(kinds[k], NULL, TS, a);
        syl_texture_draw(kinds[k], NULL, TS, b);
        assert_memory_equal(a, b, TS * TS * 3);
        if (k) assert_memory_not_equal(a, prev, TS * TS * 3);
        memcpy(prev, a, TS * TS * 3);
    }
    /* a colour multiplies the pattern */
    syl_texture_draw(SYL_MATERIAL_BARK, (float[3]){1, 0, 0}, TS, a);
    for (int i = 0; i < TS * TS; i++) assert_true(a[3 * i + 1] == 0 && a[3 * i + 2] == 0);
    free(a);
    free(b);
    free(prev);
}

/* Mean absolute difference between neighbours across (x) and along (y). */
static void gradients(const uint8_t *img, int size, double *across, double *along) {
    double gx = 0, gy = 0;
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
            const uint8_t *p = img + 3 * (y * size + x);
            gx += fabs(luma(p) - luma(img + 3 * (y * size + (x + 1) % size)));
            gy += fabs(luma(p) - luma(img + 3 * (((y + 1) % size) * size + x)));
        }
    *across = gx / (size * size);
    *along = gy / (size * size);
}

static void bark_cracks_run_along_the_branch(void **state) {
    (void)state;
    uint8_t *img = malloc(TS * TS * 3);
    syl_texture_draw(SYL_MATERIAL_BARK, NULL, TS, img);
    double across, along;
    gradients(img, TS, &across, &along);
    if (!(across > 1.8 * along)) fail_msg("bark varies %.2f across, %.2f along", across, along);
    /* there are dark cracks: a real spread of brightness */
    double lo = 255, hi = 0;
    for (int i = 0; i < TS * TS; i++) lo = fmin(lo, luma(img + 3 * i)), hi = fmax(hi, luma(img + 3 * i));
    assert_true(hi - lo > 100);
    free(img);
}

static void leaf_is_brightest_along_its_vein(void **state) {
    (void)state;
    uint8_t *img = malloc(TS * TS * 3);
    syl_texture_draw(SYL_MATERIAL_LEAF, NULL, TS, img);
    double column[TS] = {0}, mean = 0;
    for (int y = 0; y < TS; y++)
        for (int x = 0; x < TS; x++) column[x] += luma(img + 3 * (y * TS + x)) / TS;
    for (int x = 0; x < TS; x++) mean += column[x] / TS;
    double vein = fmax(column[TS / 2 - 1], column[TS / 2]);
    for (int x = 0; x < TS; x++)
        if (abs(x - TS / 2) > 3 && column[x] >= vein) fail_msg("column %d (%.1f) outshines the vein (%.1f)", x, column[x], vein);
    assert_true(vein > mean + 15);
    /* darker edges */
    assert_true(column[0] < mean - 10 && column[TS - 1] < mean - 10);
    /* side veins: along the blade, halfway to the edge, brightness rises and falls */
    double lo = 255, hi = 0;
    for (int y = 0; y < TS; y++) {
        double l = luma(img + 3 * (y * TS + TS / 4));
        lo = fmin(lo, l), hi = fmax(hi, l);
    }
    assert_true(hi - lo > 12);
    free(img);
}

static void textures_tile(void **state) {
    (void)state;
    static const int kinds[] = {SYL_MATERIAL_BARK, -1};
    uint8_t *img = malloc(TS * TS * 3);
    for (int k = 0; k < 2; k++) {
        syl_texture_draw(kinds[k], NULL, TS, img);
        double across, along, seam_x = 0, seam_y = 0;
        gradients(img, TS, &across, &along);
        for (int i = 0; i < TS; i++) {
            seam_x += fabs(luma(img + 3 * (i * TS + TS - 1)) - luma(img + 3 * (i * TS))) / TS;
            seam_y += fabs(luma(img + 3 * ((TS - 1) * TS + i)) - luma(img + 3 * i)) / TS;
        }
        /* across the seams no bigger a step than between any two neighbours */
        assert_true(seam_x < 2.5 * across + 1);
        assert_true(seam_y < 2.5 * along + 1);
    }
    free(img);
}

static void grass_is_green_and_varied(void **state) {
    (void)state;
    uint8_t *img = malloc(TS * TS * 3);
    syl_texture_draw(-1, NULL, TS, img);
    double r = 0, g = 0, b = 0, lo = 255, hi = 0;
    for (int i = 0; i < TS * TS; i++) {
        r += img[3 * i], g += img[3 * i + 1], b += img[3 * i + 2];
        lo = fmin(lo, luma(img + 3 * i)), hi = fmax(hi, luma(img + 3 * i));
    }
    assert_true(g > r && g > b);
    assert_true(hi - lo > 20);
    free(img);
}

static void noise_is_bounded_and_periodic(void **state) {
    (void)state;
    double sum = 0, sq = 0;
    int n = 0;
    for (int i = 0; i < 200; i++)
        for (int j = 0; j < 200; j++) {
            float x = (float)i * 0.037f, y = (float)j * 0.041f, v = noise2(x, y, 4, 4, 7);
            assert_true(v >= -1.0001f && v <= 1.0001f);
            assert_near(v, noise2(x + 4, y - 8, 4, 4, 7), 1e-4);
            sum += v, sq += (double)v * v, n++;
        }
    assert_near(sum / n, 0, 0.1);
    assert_true(sq / n > 0.02); /* not flat */
    assert_near(noise2(3, 5, 0, 0, 1), 0, 1e-6); /* zero on the lattice */
}

static void textures_written_for_exporters(void **state) {
    (void)state;
    char dir[] = "/tmp/sylva-tex-XXXXXX";
    assert_non_null(mkdtemp(dir));
    char prefix[64], path[96];
    snprintf(prefix, sizeof prefix, "%s/plant", dir);
    static const char *const names[] = {"bark", "leaf", "flower", "grass"};
    /* a mesh with bark only: only the bark texture */
    SylMesh *m = synth_new();
    assert_true(synth_box(m, (float[3]){0, 0, 0}, (float[3]){1, 1, 1}, 0));
    assert_int_equal(syl_mesh_write_textures(m, prefix, NULL), SYL_OK);
    for (int k = 0; k < 4; k++) {
        snprintf(path, sizeof path, "%s_%s.png", prefix, names[k]);
        assert_int_equal(access(path, F_OK) == 0, k == 0);
        unlink(path);
    }
    /* NULL: all four */
    assert_int_equal(syl_mesh_write_textures(NULL, prefix, NULL), SYL_OK);
    for (int k = 0; k < 4; k++) {
        snprintf(path, sizeof path, "%s_%s.png", prefix, names[k]);
        struct stat st;
        assert_int_equal(stat(path, &st), 0);
        assert_true(st.st_size > 1000);
        unlink(path);
    }
    assert_string_equal(syl_texture_name(SYL_MATERIAL_LEAF), "leaf");
    assert_null(syl_texture_name(SYL_MATERIAL_PLAIN));
    rmdir(dir);
    syl_mesh_free(m);
}

/* syl_render_draw_instances' windows (what sylva render --plants deals over MPI ranks): windows
 * whose corners are at multiples of SYL_RENDER_BLOCK, rendered in one call on one scene, are
 * the whole picture's pixels, crop for crop; the same windows rendered one call each too. */
static void windows_are_crops_of_the_picture(void **state) {
    (void)state;
    SylMesh *ground = synth_new(), *tree = synth_tree(2000);
    assert_non_null(ground);
    assert_non_null(tree);
    assert_true(synth_box(ground, (float[3]){-6, -0.1f, -6}, (float[3]){6, 0, 6}, 0));
    SylRenderProto proto = {.mesh = tree};
    SylRenderInstance inst[5];
    for (int i = 0; i < 5; i++)
        inst[i] = (SylRenderInstance){.t = {-4.0f + 2 * i, 0, (float)(i % 2) - 0.5f}, .yaw = 0.7f * i, .scale = 1.5f};
    SylRenderCamera cam = {.eye = {4, 6, 12}, .target = {0, 1, 0}, .fov = 40};
    enum { W = 44, H = 30 };
    SylRenderOptions o = {.width = W, .height = H, .samples = 2, .ao_samples = 2, .shadows = true, .threads = 2};
    static uint8_t whole[W * H * 3], parts[2 * W * H * 3], one[W * H * 3]; /* the windows overlap */
    assert_int_equal(syl_render_draw_instances(ground, &proto, 1, inst, 5, &cam, &o, NULL, 0, whole, NULL), SYL_OK);
    /* three bands (the last not a whole row of packets), then a block of columns */
    const int win[4][4] = {{0, 0, W, 8}, {0, 8, W, 24}, {0, 24, W, H}, {12, 4, 32, 29}};
    assert_int_equal(syl_render_draw_instances(ground, &proto, 1, inst, 5, &cam, &o, win, 4, parts, NULL), SYL_OK);
    size_t at = 0;
    for (int k = 0; k < 4; k++) {
        size_t row = (size_t)(win[k][2] - win[k][0]) * 3;
        for (int y = win[k][1]; y < win[k][3]; y++, at += row)
            assert_memory_equal(parts + at, whole + ((size_t)y * W + (size_t)win[k][0]) * 3, row);
        assert_int_equal(syl_render_draw_instances(ground, &proto, 1, inst, 5, &cam, &o, &win[k], 1, one, NULL), SYL_OK);
        assert_memory_equal(one, parts + at - row * (size_t)(win[k][3] - win[k][1]), row * (size_t)(win[k][3] - win[k][1]));
    }
    /* a window outside the picture, or a negative count, is refused */
    const int out[1][4] = {{0, 0, W + 1, 4}};
    assert_int_equal(syl_render_draw_instances(ground, &proto, 1, inst, 5, &cam, &o, out, 1, one, NULL), SYL_EUSAGE);
    assert_int_equal(syl_render_draw_instances(ground, &proto, 1, inst, 5, &cam, &o, win, -1, one, NULL), SYL_EUSAGE);
    syl_mesh_free(ground);
    syl_mesh_free(tree);
}

/* A leaf card facing +z: the quad x -1..1, y 0..2 carrying the whole card texture. */
static SylMesh *one_card(int leaves) {
    SylMesh *m = synth_new();
    assert_non_null(m);
    assert_true(reserve(m, 4, 6));
    const float n[3] = {0, 0, 1};
    uint32_t a = vert(m, (float[3]){-1, 0, 0}, n, 0, 0), b = vert(m, (float[3]){1, 0, 0}, n, 1, 0),
             c = vert(m, (float[3]){1, 2, 0}, n, 1, 1), d = vert(m, (float[3]){-1, 2, 0}, n, 0, 1);
    assert_true(tri(m, a, b, c, 1) && tri(m, a, c, d, 1));
    m->leaves = (uint8_t)leaves, m->leaf_shape = 0;
    return m;
}

/* The share of the card's pixels drawn (unlit: a miss is black) in an instanced render of
 * one card seen head on; the card's own pixels are those whose centres project inside it. */
static double instanced_card_share(const SylMesh *card, int threads, uint8_t *rgb, int w, int h) {
    SylRenderProto proto = {.mesh = card};
    SylRenderInstance inst = {.t = {0, 0, 0}, .scale = 1};
    SylRenderCamera cam = {.eye = {0, 1, 8}, .target = {0, 1, 0}, .fov = 20};
    SylRenderOptions o = {.width = w, .height = h, .samples = 1, .ao_samples = -1, .unlit = true, .threads = threads};
    assert_int_equal(syl_render_draw_instances(NULL, &proto, 1, &inst, 1, &cam, &o, NULL, 0, rgb, NULL), SYL_OK);
    float x0, y0, x1, y1;
    assert_true(syl_render_project(&cam, w, h, (float[3]){-1, 2, 0}, &x0, &y0));
    assert_true(syl_render_project(&cam, w, h, (float[3]){1, 0, 0}, &x1, &y1));
    long inside = 0, drawn = 0, outside = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const uint8_t *p = rgb + 3 * ((size_t)y * w + x);
            bool hit = p[0] || p[1] || p[2], in = x + 0.5f > x0 && x + 0.5f < x1 && y + 0.5f > y0 && y + 0.5f < y1;
            inside += in, drawn += in && hit, outside += !in && hit;
        }
    assert_true(inside > 1000);
    assert_true(outside <= inside / 50); /* only the edge's rounding */
    return (double)drawn / (double)inside;
}

/* Alpha-tested leaves in an instanced render (ecosystem views): a card prototype covers the
 * card texture's opaque share of its quad (alpha >= 1/2, syl_leaf_draw_card), as the single-mesh
 * renderer and a viewer of the .glb draw it, and not the whole quad, which the same quad drawn
 * as a plain leaf mesh covers; the same bytes for 1 and 3 threads. */
static void instanced_cards_are_alpha_tested(void **state) {
    (void)state;
    enum { CW = 96, CH = 96, TS = 256 };
    static uint8_t rgba[TS * TS * 4], a[CW * CH * 3], b[CW * CH * 3];
    assert_true(syl_leaf_draw_card(0, TS, rgba));
    long opaque = 0;
    for (int i = 0; i < TS * TS; i++) opaque += rgba[4 * i + 3] >= 128;
    double share = (double)opaque / (TS * TS);
    assert_true(share > 0.2 && share < 0.9); /* a leaf, not a square */
    SylMesh *card = one_card(SYL_LEAVES_CARDS), *plain = one_card(SYL_LEAVES_MESH);
    double got = instanced_card_share(card, 1, a, CW, CH);
    assert_true(fabs(got - share) < 0.03);
    assert_true(instanced_card_share(card, 3, b, CW, CH) == got);
    assert_memory_equal(a, b, sizeof a);
    assert_true(instanced_card_share(plain, 1, b, CW, CH) > 0.98);
    syl_mesh_free(card);
    syl_mesh_free(plain);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(same_picture_every_time),
        cmocka_unit_test(thread_count_does_not_matter),
        cmocka_unit_test(png_has_the_requested_size),
        cmocka_unit_test(bad_sizes_are_refused),
        cmocka_unit_test(box_covers_a_plausible_share),
        cmocka_unit_test(tree_covers_a_plausible_share),
        cmocka_unit_test(framing_fills_about_80_percent),
        cmocka_unit_test(shadow_on_the_ground),
        cmocka_unit_test(ambient_occlusion_darkens_the_foot),
        cmocka_unit_test(empty_mesh_draws_ground_and_sky),
        cmocka_unit_test(bare_meshes_render),
        cmocka_unit_test(materials_set_the_colours),
        cmocka_unit_test(progress_is_reported),
        cmocka_unit_test(textures_are_reproducible),
        cmocka_unit_test(bark_cracks_run_along_the_branch),
        cmocka_unit_test(leaf_is_brightest_along_its_vein),
        cmocka_unit_test(textures_tile),
        cmocka_unit_test(grass_is_green_and_varied),
        cmocka_unit_test(noise_is_bounded_and_periodic),
        cmocka_unit_test(textures_written_for_exporters),
        cmocka_unit_test(adaptive_sampling_keeps_coverage),
        cmocka_unit_test(alpha_tested_card_shows_its_shape),
        cmocka_unit_test(windows_are_crops_of_the_picture),
        cmocka_unit_test(instanced_cards_are_alpha_tested),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
