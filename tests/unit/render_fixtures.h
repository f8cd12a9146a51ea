/* Meshes built by hand for the renderer tests: boxes, and a tree of tubes and leaves. */

/* They do not depend on the turtle and the mesher; a tree can have any size. Free them with
 * syl_mesh_free. */
#ifndef SYL_RENDER_FIXTURES_H
#define SYL_RENDER_FIXTURES_H
#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "mesh/store.h"

#include "sylva/mesh.h"
#include "util/rng.h"

static const SylMaterial palette[4] = {
    {.rgb = {0.40f, 0.28f, 0.18f}, .kind = SYL_MATERIAL_BARK},
    {.rgb = {0.22f, 0.50f, 0.14f}, .kind = SYL_MATERIAL_LEAF},
    {.rgb = {0.92f, 0.55f, 0.70f}, .kind = SYL_MATERIAL_FLOWER},
    {.rgb = {0.85f, 0.10f, 0.10f}, .kind = SYL_MATERIAL_PLAIN},
};

/* An empty mesh with materials 0 bark, 1 leaf, 2 flower, 3 plain red (repeating). */
static inline SylMesh *synth_new(void) {
    SylMesh *m = calloc(1, sizeof *m);
    if (!m) return NULL;
    for (int i = 0; i < 256; i++) m->materials[i] = palette[i % 4];
    m->nmaterials = 4;
    snprintf(m->name, sizeof m->name, "synthetic");
    return m;
}

/* Room for n vertices (or indices): first, doubled as often as needed. The arrays of a mesh
 * of n always have at least cap(n + 1, ...): the vertices one past the last, for Embree. */
static size_t fixture_cap(size_t n, size_t first) {
    size_t c = first;
    while (c < n) c *= 2;
    return c;
}

static bool reserve(SylMesh *m, size_t verts, size_t idx) {
    size_t cap = fixture_cap(m->nverts + verts + 1, 256);
    if (!m->pos || cap > fixture_cap(m->nverts + 1, 256)) {
        float *p = realloc(m->pos, cap * 3 * sizeof *p);
        if (p) m->pos = p;
        float *n = realloc(m->nrm, cap * 3 * sizeof *n);
        if (n) m->nrm = n;
        float *u = realloc(m->uv, cap * 2 * sizeof *u);
        if (u) m->uv = u;
        if (!p || !n || !u) return false;
    }
    if (!mesh_has_spare(m)) mesh_mark_spare(m); /* Embree reads the vertices in place */
    cap = fixture_cap(m->nidx + idx, 768);
    if (!m->idx || cap > fixture_cap(m->nidx, 768)) {
        uint32_t *i = realloc(m->idx, cap * sizeof *i);
        if (!i) return false;
        m->idx = i;
    }
    return true;
}

static uint32_t vert(SylMesh *m, const float p[3], const float n[3], float u, float v) {
    size_t i = m->nverts++;
    memcpy(m->pos + 3 * i, p, 3 * sizeof *p);
    memcpy(m->nrm + 3 * i, n, 3 * sizeof *n);
    m->uv[2 * i] = u;
    m->uv[2 * i + 1] = v;
    return (uint32_t)i;
}

/* Append a triangle of material mat; materials must come in increasing order. */
static bool tri(SylMesh *m, uint32_t a, uint32_t b, uint32_t c, uint8_t mat) {
    if (!m->ngroups || m->groups[m->ngroups - 1].material != mat) {
        SylMeshGroup *g = realloc(m->groups, (size_t)(m->ngroups + 1) * sizeof *g);
        if (!g) return false;
        m->groups = g;
        m->groups[m->ngroups++] = (SylMeshGroup){.first = (uint32_t)m->nidx, .count = 0, .material = mat};
    }
    m->idx[m->nidx++] = a;
    m->idx[m->nidx++] = b;
    m->idx[m->nidx++] = c;
    m->groups[m->ngroups - 1].count += 3;
    return true;
}

/* Append an axis-aligned box with material mat; materials must be appended in increasing
 * order (groups stay sorted). */
static inline bool synth_box(SylMesh *m, const float lo[3], const float hi[3], uint8_t mat) {
    if (!reserve(m, 24, 36)) return false;
    for (int axis = 0; axis < 3; axis++)
        for (int side = 0; side < 2; side++) {
            int a = (axis + 1) % 3, b = (axis + 2) % 3;
            float n[3] = {0, 0, 0};
            n[axis] = side ? 1.0f : -1.0f;
            uint32_t v[4];
            for (int k = 0; k < 4; k++) {
                float p[3];
                p[axis] = side ? hi[axis] : lo[axis];
                p[a] = (k == 1 || k == 2) ? hi[a] : lo[a];
                p[b] = k >= 2 ? hi[b] : lo[b];
                v[k] = vert(m, p, n, (k == 1 || k == 2) ? 1.0f : 0.0f, k >= 2 ? 1.0f : 0.0f);
            }
            /* counter-clockwise seen from outside: (a, b) is right-handed with the axis */
            bool ccw = side == 1;
            if (!(ccw ? tri(m, v[0], v[1], v[2], mat) && tri(m, v[0], v[2], v[3], mat)
                      : tri(m, v[0], v[2], v[1], mat) && tri(m, v[0], v[3], v[2], mat)))
                return false;
        }
    return true;
}

/* ---- the tree ---- */

typedef struct Seg {
    float a[3], b[3], ra, rb, v0;
    int sides;
} Seg;

typedef struct Leaf {
    float p[3], h[3], l[3], size;
} Leaf;

typedef struct Tree {
    Seg *segs;
    size_t nsegs, seg_cap;
    Leaf *leaves;
    size_t nleaves, leaf_cap;
    double leaves_per_twig;
    int depth;
    bool ok;
    long bark_tris;
    long twigs;
    long leaf_count;
} Tree;

static void push_seg(Tree *t, const Seg *s) {
    if (t->nsegs == t->seg_cap) {
        size_t cap = t->seg_cap ? 2 * t->seg_cap : 256;
        Seg *n = realloc(t->segs, cap * sizeof *n);
        if (!n) {
            t->ok = false;
            return;
        }
        t->segs = n;
        t->seg_cap = cap;
    }
    t->segs[t->nsegs++] = *s;
    t->bark_tris += 2 * s->sides;
}

static void push_leaf(Tree *t, const Leaf *l) {
    if (t->nleaves == t->leaf_cap) {
        size_t cap = t->leaf_cap ? 2 * t->leaf_cap : 256;
        Leaf *n = realloc(t->leaves, cap * sizeof *n);
        if (!n) {
            t->ok = false;
            return;
        }
        t->leaves = n;
        t->leaf_cap = cap;
    }
    t->leaves[t->nleaves++] = *l;
}

static void any_perp(const vec3 d, vec3 out) {
    vec3 a = {1, 0, 0};
    if (fabsf(d[0]) > 0.9f) glm_vec3_copy((vec3){0, 0, 1}, a);
    glm_vec3_crossn((float *)d, a, out);
}

/* A branch from p along unit d; count: only count triangles (no leaves stored). */
static void branch(Tree *t, const vec3 p0, const vec3 d0, float len, float r, int depth, uint64_t id, bool count) {
    if (!t->ok) return;
    Rng rng = rng_stream(2024, (uint64_t)depth, 0, id);
    vec3 p, d;
    glm_vec3_copy((float *)p0, p);
    glm_vec3_copy((float *)d0, d);
    int nseg = 4, sides = depth == 0 ? 12 : depth <= 2 ? 8 : depth <= 4 ? 6 : 4;
    float rend = r * 0.62f, v = 0;
    for (int i = 0; i < nseg; i++) {
        vec3 q, axis;
        /* a slight random bend and a pull upward */
        any_perp(d, axis);
        glm_vec3_rotate(axis, (float)rng_unit(&rng) * 6.2831853f, d);
        glm_vec3_rotate(d, ((float)rng_unit(&rng) - 0.5f) * 0.25f, axis);
        d[1] += 0.04f;
        glm_vec3_normalize(d);
        glm_vec3_copy(p, q);
        glm_vec3_muladds(d, len / (float)nseg, q);
        float ra = r + (rend - r) * (float)i / (float)nseg, rb = r + (rend - r) * (float)(i + 1) / (float)nseg;
        Seg s = {.ra = ra, .rb = rb, .v0 = v, .sides = sides};
        glm_vec3_copy(p, s.a);
        glm_vec3_copy(q, s.b);
        push_seg(t, &s);
        v += len / (float)nseg / (6.2831853f * r);
        if (depth >= t->depth - 1) { /* leaves along the outer branches */
            /* rounded up or down at random, so the count comes out right on average */
            Rng lr = rng_stream(2025, (uint64_t)depth, (uint64_t)i, id); /* apart from the branching */
            double rate = t->leaves_per_twig / nseg / (depth == t->depth ? 1 : 2);
            int nl = (int)(rate + rng_unit(&lr));
            if (depth == t->depth) t->twigs += i == 0;
            if (count) {
                t->leaf_count += nl;
                nl = 0;
            }
            for (int k = 0; k < nl; k++) {
                Leaf l;
                float f = ((float)k + 0.5f) / (float)nl;
                glm_vec3_lerp(p, q, f, l.p);
                vec3 side;
                any_perp(d, side);
                glm_vec3_rotate(side, (float)k * 2.3999632f + (float)rng_unit(&lr), d);
                vec3 h;
                glm_vec3_copy(d, h);
                glm_vec3_rotate(h, 0.9f, side); /* leaning out from the twig */
                glm_vec3_cross(h, side, l.l);
                glm_vec3_normalize(l.l);
                glm_vec3_copy(h, l.h);
                l.size = 0.06f + 0.03f * (float)rng_unit(&lr);
                push_leaf(t, &l);
            }
        }
        glm_vec3_copy(q, p);
    }
    if (depth == t->depth) return;
    vec3 side;
    any_perp(d, side);
    float turn = (float)rng_unit(&rng) * 6.2831853f;
    for (int k = 0; k < 3; k++) {
        vec3 cd, axis;
        glm_vec3_copy(side, axis);
        glm_vec3_rotate(axis, turn + (float)k * 2.0943951f, d);
        glm_vec3_copy(d, cd);
        glm_vec3_rotate(cd, k == 0 ? 0.25f : 0.65f, axis);
        branch(t, p, cd, len * (k == 0 ? 0.8f : 0.7f), rend, depth + 1, id * 3 + (uint64_t)k + 1, count);
    }
}

static bool emit_seg(SylMesh *m, const Seg *s) {
    if (!reserve(m, 2 * (size_t)(s->sides + 1), 6 * (size_t)s->sides)) return false;
    vec3 d, x, y;
    glm_vec3_sub((float *)s->b, (float *)s->a, d);
    float len = glm_vec3_norm(d);
    glm_vec3_normalize(d);
    any_perp(d, x);
    glm_vec3_cross(d, x, y);
    uint32_t first = (uint32_t)m->nverts;
    float v1 = s->v0 + len / (6.2831853f * s->ra);
    for (int i = 0; i <= s->sides; i++) {
        float a = 6.2831853f * (float)i / (float)s->sides;
        vec3 n, pa, pb;
        glm_vec3_scale(x, cosf(a), n);
        glm_vec3_muladds(y, sinf(a), n);
        glm_vec3_copy((float *)s->a, pa);
        glm_vec3_muladds(n, s->ra, pa);
        glm_vec3_copy((float *)s->b, pb);
        glm_vec3_muladds(n, s->rb, pb);
        float u = (float)i / (float)s->sides;
        vert(m, pa, n, u, s->v0);
        vert(m, pb, n, u, v1);
    }
    for (int i = 0; i < s->sides; i++) {
        uint32_t a = first + 2 * (uint32_t)i, b = a + 2;
        if (!tri(m, a, b, b + 1, 0) || !tri(m, a, b + 1, a + 1, 0)) return false;
    }
    return true;
}

static bool emit_leaf(SylMesh *m, const Leaf *l) {
    if (!reserve(m, 5, 12)) return false;
    vec3 n, base, tip, left, right, mid;
    glm_vec3_cross((float *)l->h, (float *)l->l, n);
    glm_vec3_copy((float *)l->p, base);
    glm_vec3_copy(base, tip);
    glm_vec3_muladds((float *)l->h, 2 * l->size, tip);
    glm_vec3_lerp(base, tip, 0.45f, mid);
    glm_vec3_muladds(n, -0.12f * l->size, mid); /* folded along the vein */
    glm_vec3_copy(mid, left);
    glm_vec3_muladds((float *)l->l, 0.5f * l->size, left);
    glm_vec3_muladds(n, 0.12f * l->size, left);
    glm_vec3_copy(mid, right);
    glm_vec3_muladds((float *)l->l, -0.5f * l->size, right);
    glm_vec3_muladds(n, 0.12f * l->size, right);
    uint32_t b = vert(m, base, n, 0.5f, 0), lf = vert(m, left, n, 0, 0.45f), md = vert(m, mid, n, 0.5f, 0.45f),
             rt = vert(m, right, n, 1, 0.45f), tp = vert(m, tip, n, 0.5f, 1);
    return tri(m, b, md, lf, 1) && tri(m, b, rt, md, 1) && tri(m, lf, md, tp, 1) && tri(m, md, rt, tp, 1);
}

/* A branching tree of tubes (bark) with folded leaves, about `triangles` triangles (at
 * least 500), the same every time; its base at the origin, about 2.5 units tall. */
static inline SylMesh *synth_tree(long triangles) {
    if (triangles < 500) triangles = 500;
    Tree t = {.ok = true};
    /* The deepest tree whose bark is at most a third of the triangles; leaves make the rest. */
    for (int depth = 1; depth < 14; depth++) {
        Tree probe = {.ok = true, .depth = depth};
        branch(&probe, (vec3){0, 0, 0}, (vec3){0, 1, 0}, 1, 0.06f, 0, 0, true);
        free(probe.segs);
        if (depth > 1 && probe.bark_tris > triangles / 3) break;
        t.depth = depth;
        t.bark_tris = probe.bark_tris;
        t.twigs = probe.twigs;
    }
    /* Leaves (4 triangles each) make up the rest: guess how many per twig, count, and
     * correct the guess once. */
    double want = (double)(triangles - t.bark_tris) / 4, per = want / (double)(t.twigs ? t.twigs : 1);
    for (int round = 0; round < 2; round++) {
        Tree probe = {.ok = true, .depth = t.depth, .leaves_per_twig = per};
        branch(&probe, (vec3){0, 0, 0}, (vec3){0, 1, 0}, 1, 0.06f, 0, 0, true);
        free(probe.segs);
        if (probe.leaf_count > 0) per *= want / (double)probe.leaf_count;
    }
    t.leaves_per_twig = per;
    t.bark_tris = 0;
    t.twigs = 0;
    branch(&t, (vec3){0, 0, 0}, (vec3){0, 1, 0}, 1, 0.06f, 0, 0, false);
    SylMesh *m = t.ok ? synth_new() : NULL;
    bool ok = m != NULL;
    for (size_t i = 0; ok && i < t.nsegs; i++) ok = emit_seg(m, &t.segs[i]);
    for (size_t i = 0; ok && i < t.nleaves; i++) ok = emit_leaf(m, &t.leaves[i]);
    free(t.segs);
    free(t.leaves);
    if (!ok) {
        syl_mesh_free(m);
        return NULL;
    }
    return m;
}

#endif
