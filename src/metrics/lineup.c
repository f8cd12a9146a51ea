/* Plants side by side with a height ruler, as one mesh: what `sylva compare --image` renders. */
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "util/font.h"
#include "mesh/store.h"
#include "sylva/metrics.h"

typedef struct Box {
    float lo[3], hi[3];
} Box;

typedef struct Boxes {
    Box *b;
    size_t n, cap;
} Boxes;

static bool add_box(Boxes *bx, float x0, float y0, float z0, float x1, float y1, float z1) {
    if (bx->n == bx->cap) {
        size_t cap = bx->cap ? 2 * bx->cap : 64;
        Box *b = realloc(bx->b, cap * sizeof *b);
        if (!b) return false;
        bx->b = b;
        bx->cap = cap;
    }
    bx->b[bx->n++] = (Box){{x0, y0, z0}, {x1, y1, z1}};
    return true;
}

/* Seven segments a (top), b, c (right, top to bottom), d (bottom), e, f (left, bottom to top)
 * and g (middle), bit 0 to 6. */
static const uint8_t digits[10] = {0x3F, 0x06, 0x5B, 0x4F, 0x66, 0x6D, 0x7D, 0x07, 0x7F, 0x6F};

/* Text of height h, its right end at x = right, its middle at y, in front of z. */
static bool add_text(Boxes *bx, const char *text, float right, float y, float z, float h) {
    float s = h / 7, w = 0.6f * h, gap = 0.3f * h, dot = 2 * s;
    float width = 0;
    for (const char *c = text; *c; c++) width += (*c == '.' ? dot : w) + (c[1] ? gap : 0);
    float x = right - width, y0 = y - h / 2, mid = y0 + h / 2, top = y0 + h, z1 = z + s;
    bool ok = true;
    for (const char *c = text; *c && ok; c++) {
        if (*c == '.') {
            ok = add_box(bx, x, y0, z, x + s, y0 + s, z1);
            x += dot + gap;
            continue;
        }
        if (*c < '0' || *c > '9') continue;
        uint8_t seg = digits[*c - '0'];
        if (seg & 0x01) ok = ok && add_box(bx, x, top - s, z, x + w, top, z1);
        if (seg & 0x02) ok = ok && add_box(bx, x + w - s, mid, z, x + w, top, z1);
        if (seg & 0x04) ok = ok && add_box(bx, x + w - s, y0, z, x + w, mid, z1);
        if (seg & 0x08) ok = ok && add_box(bx, x, y0, z, x + w, y0 + s, z1);
        if (seg & 0x10) ok = ok && add_box(bx, x, y0, z, x + s, mid, z1);
        if (seg & 0x20) ok = ok && add_box(bx, x, mid, z, x + s, top, z1);
        if (seg & 0x40) ok = ok && add_box(bx, x, mid - s / 2, z, x + w, mid + s / 2, z1);
        x += w + gap;
    }
    return ok;
}

/* Text in the 5 x 7 font, a box a dot, h high, centred on x, its foot at y = 0, its face at
 * z (toward +z, the camera's side). */
static bool add_words(Boxes *bx, const char *text, float x, float z, float h) {
    float s = h / 7, left = x - (float)font_text_width(text, 1) * s / 2;
    for (int i = 0; text[i]; i++) {
        const uint8_t *g = font_glyph(text[i]);
        for (int r = 0; r < 7; r++)
            for (int c = 0; c < 5; c++)
                if (g[r] >> (4 - c) & 1) {
                    float x0 = left + (float)(6 * i + c) * s, y0 = (float)(6 - r) * s;
                    if (!add_box(bx, x0, y0, z - s, x0 + s, y0 + s, z)) return false;
                }
    }
    return true;
}

/* 1, 2 or 5 times a power of ten, at least v. */
static double round_step(double v) {
    double e = pow(10, floor(log10(v))), f = v / e;
    return (f <= 1 ? 1 : f <= 2 ? 2 : f <= 5 ? 5 : 10) * e;
}

/* The ruler's boxes: the pole's right side at x = right. */
static bool ruler(Boxes *bx, double tallest, double wide, float right) {
    double step = round_step(tallest / 5);
    int ticks = (int)ceil(tallest / step - 1e-9);
    if (ticks < 1) ticks = 1;
    float top = (float)(ticks * step);
    float w = (float)(0.006 * fmax(top, wide)), text = fminf(5 * w, (float)(0.45 * step));
    if (w > text / 2) w = text / 2;
    if (!add_box(bx, right - w, 0, -w / 2, right, top, w / 2)) return false;
    for (int i = 0; i <= ticks; i++) {
        float y = (float)(i * step);
        char label[32];
        snprintf(label, sizeof label, "%g", i * step);
        float y0 = i ? y - w / 2 : 0, ymid = fmaxf(y, text / 2);
        if (!add_box(bx, right - 4 * w, y0, -w / 2, right, y0 + w, w / 2) ||
            !add_text(bx, label, right - 5.5f * w, ymid, -w / 2, text))
            return false;
    }
    return true;
}

static const float face_n[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};

/* The 24 vertices and 12 triangles of a box, counter-clockwise seen from outside. */
static void emit_box(SylMesh *m, const Box *b) {
    for (int f = 0; f < 6; f++) {
        int axis = f / 2, u = (axis + 1) % 3, v = (axis + 2) % 3;
        float c = f % 2 ? b->hi[axis] : b->lo[axis];
        uint32_t base = (uint32_t)m->nverts;
        for (int k = 0; k < 4; k++) {
            float *p = m->pos + 3 * m->nverts;
            p[axis] = c;
            p[u] = (k == 1 || k == 2) ? b->hi[u] : b->lo[u];
            p[v] = k >= 2 ? b->hi[v] : b->lo[v];
            memcpy(m->nrm + 3 * m->nverts, face_n[f], sizeof face_n[f]);
            m->uv[2 * m->nverts] = (float)(k == 1 || k == 2);
            m->uv[2 * m->nverts + 1] = (float)(k >= 2);
            m->nverts++;
        }
        /* (u, v) corners 0 (lo, lo), 1 (hi, lo), 2 (hi, hi), 3 (lo, hi): u x v is +axis */
        static const uint32_t out[6] = {0, 1, 2, 0, 2, 3}, in[6] = {0, 2, 1, 0, 3, 2};
        const uint32_t *o = f % 2 ? out : in;
        for (int k = 0; k < 6; k++) m->idx[m->nidx++] = base + o[k];
    }
}

static int find_material(SylMaterial *mats, int *n, const SylMaterial *want) {
    for (int i = 0; i < *n; i++)
        if (mats[i].kind == want->kind && !memcmp(mats[i].rgb, want->rgb, sizeof want->rgb)) return i;
    if (*n == 255) return 0; /* the last one is the ruler's */
    mats[*n] = *want;
    return (*n)++;
}

SylMesh *syl_metrics_build_lineup(const SylMesh *const *meshes, const double *ground, const char *const *names, int n) {
    SylMesh *m = calloc(1, sizeof *m);
    float(*lo)[3] = calloc((size_t)n + 1, sizeof *lo), (*hi)[3] = calloc((size_t)n + 1, sizeof *hi);
    float(*shift)[3] = calloc((size_t)n + 1, sizeof *shift);
    int ngroups = 0;
    for (int i = 0; i < n; i++) ngroups += meshes[i]->ngroups;
    int *map = calloc((size_t)ngroups + 1, sizeof *map);
    size_t *bases = calloc((size_t)n + 1, sizeof *bases);
    Boxes bx = {0};
    bool ok = m && lo && hi && shift && map && bases;
    if (!ok) goto done;

    /* Where each plant goes. */
    double tallest = 0, widest = 0;
    for (int i = 0; i < n; i++) {
        const SylMesh *p = meshes[i];
        for (int k = 0; k < 3; k++) lo[i][k] = hi[i][k] = 0;
        for (size_t v = 0; v < p->nverts; v++)
            for (int k = 0; k < 3; k++) {
                float c = p->pos[3 * v + k];
                if (!v || c < lo[i][k]) lo[i][k] = c;
                if (!v || c > hi[i][k]) hi[i][k] = c;
            }
        tallest = fmax(tallest, hi[i][1] - ground[i]);
        widest = fmax(widest, hi[i][0] - lo[i][0]);
    }
    if (!(tallest > 0)) tallest = widest > 0 ? widest : 1;
    float gap = (float)(0.15 * fmax(tallest, widest)), x = 0;
    for (int i = 0; i < n; i++) {
        shift[i][0] = x - lo[i][0];
        shift[i][1] = (float)-ground[i];
        shift[i][2] = -(lo[i][2] + hi[i][2]) / 2;
        x += hi[i][0] - lo[i][0] + gap;
    }
    ok = ruler(&bx, tallest, x - gap, -gap / 2);
    /* each name as tall as a ruler's figure, at most a plant's width for its length */
    for (int i = 0; ok && names && i < n; i++) {
        float width = hi[i][0] - lo[i][0] + 0.6f * gap, h = (float)(0.035 * fmax(tallest, x - gap));
        float len = (float)font_text_width(names[i], 1) / 7;
        if (len * h > width) h = width / len;
        ok = add_words(&bx, names[i], shift[i][0] + (lo[i][0] + hi[i][0]) / 2, (hi[i][2] - lo[i][2]) / 2 + 0.1f * gap, h);
    }
    if (!ok) goto done;

    /* Materials: shared when equal; the ruler's last. */
    int nmat = 0;
    for (int i = 0, g0 = 0; i < n; g0 += meshes[i]->ngroups, i++)
        for (int g = 0; g < meshes[i]->ngroups; g++)
            map[g0 + g] = find_material(m->materials, &nmat, &meshes[i]->materials[meshes[i]->groups[g].material]);
    int rmat = nmat;
    m->materials[rmat] = (SylMaterial){.rgb = {0.85f, 0.12f, 0.08f}, .kind = SYL_MATERIAL_PLAIN};
    m->nmaterials = rmat + 1;
    snprintf(m->name, sizeof m->name, "lineup");

    /* Vertices, moved; then triangles material by material. */
    size_t nv = 24 * bx.n, ni = 36 * bx.n;
    for (int i = 0; i < n; i++) nv += meshes[i]->nverts, ni += meshes[i]->nidx;
    m->pos = malloc((nv + 2) * 3 * sizeof *m->pos); /* room past the end for Embree */
    m->nrm = malloc((nv + 1) * 3 * sizeof *m->nrm);
    m->uv = malloc((nv + 1) * 2 * sizeof *m->uv);
    m->idx = malloc((ni + 1) * sizeof *m->idx);
    m->groups = calloc((size_t)m->nmaterials, sizeof *m->groups);
    ok = m->pos && m->nrm && m->uv && m->idx && m->groups && nv <= UINT32_MAX && ni <= UINT32_MAX;
    if (!ok) goto done;
    mesh_mark_spare(m);
    for (int i = 0; i < n; i++) {
        const SylMesh *p = meshes[i];
        bases[i] = m->nverts;
        for (size_t v = 0; v < p->nverts; v++, m->nverts++)
            for (int k = 0; k < 3; k++) m->pos[3 * m->nverts + k] = p->pos[3 * v + k] + shift[i][k];
        memcpy(m->nrm + 3 * bases[i], p->nrm, p->nverts * 3 * sizeof *p->nrm);
        memcpy(m->uv + 2 * bases[i], p->uv, p->nverts * 2 * sizeof *p->uv);
    }
    for (int mat = 0; mat < rmat; mat++) {
        SylMeshGroup *grp = &m->groups[m->ngroups];
        grp->first = (uint32_t)m->nidx;
        grp->material = (uint8_t)mat;
        for (int i = 0, g0 = 0; i < n; g0 += meshes[i]->ngroups, i++)
            for (int g = 0; g < meshes[i]->ngroups; g++) {
                if (map[g0 + g] != mat) continue;
                const SylMeshGroup *src = &meshes[i]->groups[g];
                for (uint32_t k = 0; k < src->count; k++)
                    m->idx[m->nidx++] = meshes[i]->idx[src->first + k] + (uint32_t)bases[i];
            }
        grp->count = (uint32_t)(m->nidx - grp->first);
        if (grp->count) m->ngroups++;
    }
    SylMeshGroup *grp = &m->groups[m->ngroups++];
    grp->first = (uint32_t)m->nidx;
    grp->material = (uint8_t)rmat;
    for (size_t b = 0; b < bx.n; b++) emit_box(m, &bx.b[b]);
    grp->count = (uint32_t)(m->nidx - grp->first);
done:
    free(lo);
    free(hi);
    free(shift);
    free(map);
    free(bases);
    free(bx.b);
    if (!ok) {
        syl_mesh_free(m);
        return NULL;
    }
    return m;
}
