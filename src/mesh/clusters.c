/* Leaf clusters (Pafčo 2007's spherical clusters, docs/mesh.md#leaf-clusters): the leaves and
 * needles that lie close together are drawn as one alpha-tested card whose texture shows
 * several leaves (texture's syl_leaf_draw_cluster). Leaves are grouped by cells of a grid, per
 * material, the cell size found by bisection so there is about one card per
 * SylMeshOptions.cluster_leaves leaves. Each card lies in its group's best-fitting plane (the
 * least spread of its leaves' bases and tips), square, at the group's centre, and is as large
 * as it must be to show the group's leaf area through the texture's alpha. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/mesh_internal.h"
#include "sylva/texture.h"

typedef struct Leaf {
    float c[3], base[3], tip[3], area, u[3];
    int32_t node;
    uint8_t mat;
} Leaf;

static bool clustered(const SylOrgan *o) { return o->kind == SYL_KIND_LEAF || o->kind == SYL_KIND_NEEDLE; }

/* A cell and material as one key (0 is the empty slot). */
static uint64_t cell_key(const float c[3], const float lo[3], float h, uint8_t mat) {
    uint64_t k = mat;
    for (int a = 0; a < 3; a++) {
        double q = floor((double)(c[a] - lo[a]) / (double)h);
        uint64_t i = q < 0 ? 0 : q > 0xfffff ? 0xfffff : (uint64_t)q;
        k = k << 20 | i;
    }
    return k + 1;
}

typedef struct Table {
    uint64_t *key;
    uint32_t *val;
    size_t mask;
} Table;

static uint32_t *table_slot(Table *t, uint64_t k, bool *fresh) {
    uint64_t h = k; /* splitmix64's finalizer: every bit of the key reaches the low bits */
    h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ull;
    h = (h ^ (h >> 27)) * 0x94d049bb133111ebull;
    h ^= h >> 31;
    for (size_t i = (size_t)h & t->mask;; i = (i + 1) & t->mask) {
        if (t->key[i] == k) return *fresh = false, &t->val[i];
        if (!t->key[i]) {
            t->key[i] = k;
            return *fresh = true, &t->val[i];
        }
    }
}

/* Groups of leaves for cell size h: group[i] of leaf i, numbered in the order of their
 * first leaf; returns how many. Without grp, it stops counting above limit (the table then
 * needs room for limit + 1 keys only). */
static size_t group(const Leaf *lf, size_t n, const float lo[3], float h, Table *t, uint32_t *grp, size_t limit) {
    memset(t->key, 0, (t->mask + 1) * sizeof *t->key);
    size_t ng = 0;
    for (size_t i = 0; i < n && (grp || ng <= limit); i++) {
        bool fresh;
        uint32_t *v = table_slot(t, cell_key(lf[i].c, lo, h, lf[i].mat), &fresh);
        if (fresh) *v = (uint32_t)ng++;
        if (grp) grp[i] = *v;
    }
    return ng;
}

/* The unit eigenvectors of a symmetric 3 x 3 matrix, by Jacobi rotations: columns of v,
 * eigenvalues in d. */
static void eigen3(double a[3][3], double v[3][3], double d[3]) {
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) v[i][j] = i == j;
    for (int sweep = 0; sweep < 32; sweep++) {
        double off = fabs(a[0][1]) + fabs(a[0][2]) + fabs(a[1][2]);
        if (off < 1e-30) break;
        for (int p = 0; p < 2; p++)
            for (int q = p + 1; q < 3; q++) {
                if (fabs(a[p][q]) < 1e-300) continue;
                double th = (a[q][q] - a[p][p]) / (2 * a[p][q]);
                double t = (th >= 0 ? 1 : -1) / (fabs(th) + sqrt(th * th + 1)), c = 1 / sqrt(t * t + 1), s = t * c;
                for (int k = 0; k < 3; k++) { /* a = J^T a J */
                    double x = a[k][p], y = a[k][q];
                    a[k][p] = c * x - s * y, a[k][q] = s * x + c * y;
                }
                for (int k = 0; k < 3; k++) {
                    double x = a[p][k], y = a[q][k];
                    a[p][k] = c * x - s * y, a[q][k] = s * x + c * y;
                }
                for (int k = 0; k < 3; k++) {
                    double x = v[k][p], y = v[k][q];
                    v[k][p] = c * x - s * y, v[k][q] = s * x + c * y;
                }
            }
    }
    for (int i = 0; i < 3; i++) d[i] = a[i][i];
}

static void unit(float v[3]) {
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int a = 0; a < 3; a++) v[a] = l > 0 ? v[a] / l : 0;
}

static void cross(const float a[3], const float b[3], float out[3]) {
    out[0] = a[1] * b[2] - a[2] * b[1], out[1] = a[2] * b[0] - a[0] * b[2], out[2] = a[0] * b[1] - a[1] * b[0];
}

/* The card of the leaves of one group (idx: their numbers). */
static MeshCluster card_of(const Leaf *lf, const uint32_t *idx, size_t n, float fill) {
    MeshCluster k = {.node = lf[idx[0]].node, .mat = lf[idx[0]].mat};
    double area = 0, m[3] = {0, 0, 0}, cov[3][3] = {{0}};
    for (size_t i = 0; i < n; i++) area += lf[idx[i]].area;
    for (size_t i = 0; i < n; i++)
        for (int a = 0; a < 3; a++) m[a] += lf[idx[i]].c[a] / (double)n;
    for (size_t i = 0; i < n; i++)
        for (int e = 0; e < 2; e++) {
            const float *p = e ? lf[idx[i]].tip : lf[idx[i]].base;
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++) cov[a][b] += (p[a] - m[a]) * (p[b] - m[b]);
        }
    double v[3][3], d[3];
    eigen3(cov, v, d);
    int lo = 0, hi = 0;
    for (int i = 1; i < 3; i++) {
        if (d[i] < d[lo]) lo = i;
        if (d[i] > d[hi]) hi = i;
    }
    float along[3], nrm[3], u[3] = {0, 0, 0};
    for (int a = 0; a < 3; a++) along[a] = (float)v[a][hi], nrm[a] = (float)v[a][lo], k.c[a] = (float)m[a];
    for (size_t i = 0; i < n; i++)
        for (int a = 0; a < 3; a++) u[a] += lf[idx[i]].u[a];
    if (n == 1 || lo == hi) { /* one leaf: its own frame */
        const Leaf *l = &lf[idx[0]];
        for (int a = 0; a < 3; a++) along[a] = l->tip[a] - l->base[a], nrm[a] = l->u[a];
    }
    /* facing the way its leaves face (the card is double-sided: this is for shading) */
    if (nrm[0] * u[0] + nrm[1] * u[1] + nrm[2] * u[2] < 0)
        for (int a = 0; a < 3; a++) nrm[a] = -nrm[a];
    unit(nrm);
    float dn = along[0] * nrm[0] + along[1] * nrm[1] + along[2] * nrm[2];
    for (int a = 0; a < 3; a++) along[a] -= dn * nrm[a];
    unit(along);
    float across[3];
    cross(nrm, along, across);
    float half = 0.5f * (float)sqrt(area / (double)fill);
    for (int a = 0; a < 3; a++) k.a[a] = half * along[a], k.b[a] = half * across[a], k.n[a] = nrm[a];
    return k;
}

/* The leaves the mesher would draw, with their one-side areas. */
static size_t gather(const MeshPlan *pl, Leaf *lf, float lo[3], float hi[3], size_t *needles) {
    const SylSkeleton *s = pl->skel;
    size_t n = 0;
    *needles = 0;
    for (int a = 0; a < 3; a++) lo[a] = INFINITY, hi[a] = -INFINITY;
    for (size_t i = 0; i < s->norgans; i++) {
        const SylOrgan *o = &s->organs[i];
        float h[3], l[3], u[3];
        if (!clustered(o) || !mesh_organ_frame(o, h, l, u)) continue;
        Leaf *f = &lf[n++];
        for (int a = 0; a < 3; a++) {
            f->base[a] = o->pos[a], f->tip[a] = o->pos[a] + o->size * h[a];
            f->c[a] = o->pos[a] + 0.5f * o->size * h[a], f->u[a] = u[a];
            lo[a] = fminf(lo[a], f->c[a]), hi[a] = fmaxf(hi[a], f->c[a]);
        }
        f->area = mesh_organ_side_area(pl, o);
        f->node = o->node, f->mat = o->material;
        *needles += o->kind == SYL_KIND_NEEDLE;
    }
    return n;
}

/* The smallest cell size (to 1/2^12 of the 14 octaves searched) with at most want groups, by
 * bisection in log scale; counting stops above want, so a small table (want's) serves. */
static float cell_size(const Leaf *lf, size_t n, const float lo[3], float extent, size_t want, Table *big) {
    size_t cap = 16;
    while (cap < 2 * (want + 1)) cap *= 2;
    Table t = cap <= big->mask + 1 ? (Table){big->key, big->val, cap - 1} : *big;
    float a = extent * 1e-4f, b = extent * 2;
    for (int it = 0; it < 12; it++) {
        float h = sqrtf(a * b);
        if (group(lf, n, lo, h, &t, NULL, want) > want) a = h;
        else b = h;
    }
    return b;
}

bool mesh_plan_clusters(MeshPlan *pl, float per_card) {
    const SylSkeleton *s = pl->skel;
    Leaf *lf = malloc((s->norgans + 1) * sizeof *lf);
    uint32_t *grp = malloc((s->norgans + 1) * sizeof *grp), *first = NULL, *order = NULL;
    float lo[3], hi[3];
    size_t needles = 0, n = lf ? gather(pl, lf, lo, hi, &needles) : 0, cap = 16;
    while (cap < 2 * n) cap *= 2;
    Table t = {.key = malloc(cap * sizeof *t.key), .val = malloc(cap * sizeof *t.val), .mask = cap - 1};
    bool ok = lf && grp && t.key && t.val;
    pl->cluster_shape = needles * 2 > n ? SYL_CLUSTER_NEEDLES : pl->leaf_shape;
    float fill = ok && n ? syl_leaf_cluster_fill(pl->cluster_shape) : 1;
    ok = ok && fill > 0;
    if (ok && n) {
        float extent = fmaxf(fmaxf(hi[0] - lo[0], hi[1] - lo[1]), fmaxf(hi[2] - lo[2], 1e-6f));
        size_t want = (size_t)((double)n / (double)(per_card >= 1 ? per_card : 1) + 0.5);
        size_t ng = group(lf, n, lo, cell_size(lf, n, lo, extent, want ? want : 1, &t), &t, grp, n);
        /* the leaves of each group together, groups in the order of their first leaf */
        first = calloc(ng + 1, sizeof *first), order = malloc(n * sizeof *order);
        ok = first && order && mesh_reserve((void **)&pl->clusters, &pl->clusters_cap, 0, ng, sizeof *pl->clusters) &&
             mesh_reserve((void **)&pl->items, &pl->items_cap, pl->nitems, ng, sizeof *pl->items);
        for (size_t i = 0; ok && i < n; i++) first[grp[i] + 1]++;
        for (size_t g = 0; ok && g < ng; g++) first[g + 1] += first[g];
        for (size_t i = 0; ok && i < n; i++) order[first[grp[i]]++] = (uint32_t)i;
        for (size_t g = ng; ok && g > 0; g--) first[g] = first[g - 1];
        if (ok) first[0] = 0;
        for (size_t g = 0; ok && g < ng; g++) {
            pl->clusters[g] = card_of(lf, order + first[g], first[g + 1] - first[g], fill);
            if (!mesh_add_run(pl, pl->clusters[g].mat, 2)) ok = false;
            else
                pl->items[pl->nitems++] = (MeshItem){.vert = pl->nverts, .index = (uint32_t)g, .run = (uint32_t)pl->nruns - 1,
                                                     .verts = 4, .node = pl->clusters[g].node, .cluster = true};
            pl->nverts += 4;
        }
        pl->nclusters = ok ? ng : 0;
    }
    free(lf), free(grp), free(first), free(order), free(t.key), free(t.val);
    return ok;
}

void mesh_emit_cluster(const MeshCluster *k, float *pos, float *nrm, float *uv, uint32_t *idx, uint32_t v0) {
    static const float corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int i = 0; i < 4; i++) {
        for (int a = 0; a < 3; a++) {
            pos[3 * i + a] = k->c[a] + corner[i][0] * k->a[a] + corner[i][1] * k->b[a];
            nrm[3 * i + a] = k->n[a];
        }
        uv[2 * i] = 0.5f + 0.5f * corner[i][1], uv[2 * i + 1] = 0.5f + 0.5f * corner[i][0];
    }
    static const uint32_t tri[6] = {0, 1, 2, 0, 2, 3};
    for (int i = 0; i < 6; i++) idx[i] = v0 + tri[i];
}
