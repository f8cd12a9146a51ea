/* The skeleton of Pafčo's tree (Pafčo 2007, §4.2–4.5; docs/pafco.md#how-a-tree-is-made): the
 * trunk's control points, the first generation in a quadrant spiral from the crown's trunk
 * points, up to two more generations, each branch bent by gravity and the sun and scattered,
 * diameters falling linearly to 0, and leaves in spherical clusters or as billboards. Every
 * random draw comes from one counter-based stream of the seed, so a tree is the same on any
 * machine and thread count. */
#include "pafco/pafco.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "skeleton/store.h"
#include "util/rng.h"

#define DEG (M_PI / 180.0)

typedef struct V3 {
    double x, y, z;
} V3;

static V3 v3(double x, double y, double z) { return (V3){x, y, z}; }
static V3 add(V3 a, V3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static V3 scale(V3 a, double k) { return v3(a.x * k, a.y * k, a.z * k); }
static double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static V3 cross(V3 a, V3 b) { return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x); }
static V3 norm(V3 a) {
    double n = sqrt(dot(a, a));
    return n > 0 ? scale(a, 1 / n) : v3(0, 1, 0);
}
/* A unit vector perpendicular to h (h a unit vector). */
static V3 perp(V3 h) { return norm(cross(fabs(h.y) < 0.99 ? v3(0, 1, 0) : v3(1, 0, 0), h)); }
/* h turned by angle a toward the unit vector t (t not parallel to h). */
static V3 turn_toward(V3 h, V3 t, double a) {
    V3 side = norm(add(t, scale(h, -dot(t, h))));
    return norm(add(scale(h, cos(a)), scale(side, sin(a))));
}

typedef struct Gen {
    const PafcoParams *P;
    SylSkeleton *sk;
    Rng rng;
    Rng leaf_rng;   /* leaves draw from their own stream: the same branches whatever the leaves */
    Budget *mem;
    uint64_t charged;
    int32_t axes;
    int quadrant;   /* the first generation's spiral: each branch in the next quadrant */
    int last_gen;   /* the generation billboards grow on */
    int nleafmat;   /* leaf materials: 1 + [0, nleafmat) */
    PafcoLog *log;
    bool failed;
} Gen;

static double uniform(Gen *g, double a, double b) { return a + (b - a) * rng_unit(&g->rng); }

/* Room for one more node or leaf within the budget, charged 64 kB at a time. */
static bool room(Gen *g) {
    uint64_t need = (uint64_t)(g->sk->nnodes + 1) * sizeof(SylNode) + (uint64_t)(g->sk->norgans + 1) * sizeof(SylOrgan);
    if (need <= g->charged) return true;
    uint64_t step = (need - g->charged + 65535) & ~(uint64_t)65535;
    if (!budget_charge(g->mem, step)) return g->failed = true, false;
    g->charged += step;
    return true;
}

static int32_t node(Gen *g, V3 p, V3 h, double r, int32_t parent, int32_t axis, int order, int kind) {
    if (g->failed || !room(g)) return -1;
    V3 l = perp(h), u = cross(h, l);
    SylNode n = {.pos = {(float)p.x, (float)p.y, (float)p.z}, .h = {(float)h.x, (float)h.y, (float)h.z},
                 .l = {(float)l.x, (float)l.y, (float)l.z}, .u = {(float)u.x, (float)u.y, (float)u.z},
                 .radius = (float)r, .parent = parent, .axis = axis, .order = (uint16_t)order,
                 .kind = (uint8_t)kind, .material = SYL_MATERIAL_BARK, .module = (uint32_t)axis};
    int32_t k = syl_skeleton_add_node(g->sk, &n);
    if (k < 0) g->failed = true;
    return k;
}

static void leaf(Gen *g, V3 p, V3 h, double size, int32_t at) {
    if (g->failed || !(size > 0) || !room(g)) return;
    V3 l = perp(h);
    double roll = 2 * M_PI * rng_unit(&g->leaf_rng); /* "the other angles are random" */
    V3 l2 = norm(add(scale(l, cos(roll)), scale(cross(h, l), sin(roll)))), u = cross(h, l2);
    int mat = 1 + (g->nleafmat > 1 ? (int)(rng_next(&g->leaf_rng) % (uint64_t)g->nleafmat) : 0);
    SylOrgan o = {.pos = {(float)p.x, (float)p.y, (float)p.z}, .h = {(float)h.x, (float)h.y, (float)h.z},
                  .l = {(float)l2.x, (float)l2.y, (float)l2.z}, .u = {(float)u.x, (float)u.y, (float)u.z},
                  .size = (float)size, .node = at, .kind = SYL_KIND_LEAF, .material = (uint8_t)mat};
    if (syl_skeleton_add_organ(g->sk, &o) < 0) g->failed = true;
}

/* A random unit vector (uniform on the sphere), from the leaves' stream. */
static V3 on_sphere(Gen *g) {
    double z = 2 * rng_unit(&g->leaf_rng) - 1, a = 2 * M_PI * rng_unit(&g->leaf_rng), s = sqrt(1 - z * z);
    return v3(s * cos(a), z, s * sin(a));
}

/* Spherical leaves (§4.4.1): LSPH_POCET squares on a sphere of LSPH_POLOMER around an end. */
static void cluster(Gen *g, V3 end, int32_t at) {
    const PafcoParams *P = g->P;
    long n = lround(P->sph_count);
    for (long i = 0; i < n && !g->failed; i++) {
        V3 d = on_sphere(g);
        leaf(g, add(end, scale(d, P->sph_radius)), on_sphere(g), P->leaf_size, at);
    }
}

double pafco_crown_profile(bool round, double f) {
    if (f < 0) f = 0;
    if (f > 1) f = 1;
    /* conical: widest at the crown's base, nothing at the top; round: a half sine from a
     * third of the width at the base, widest at 4/9 of the crown, nothing at the top */
    return round ? sin(M_PI * (0.1 + 0.9 * f)) : 1 - f;
}

static void log_branch(Gen *g, PafcoBranch b) {
    PafcoLog *L = g->log;
    if (!L || g->failed) return;
    if (L->n == L->cap) {
        int cap = L->cap ? 2 * L->cap : 64;
        PafcoBranch *nb = realloc(L->branches, (size_t)cap * sizeof *nb);
        if (!nb) return (void)(g->failed = true);
        L->branches = nb, L->cap = cap;
    }
    L->branches[L->n++] = b;
}

/* One branch of generation gen (1..3) from the parent's control point `from` (node index,
 * position p, the parent's radius there r_parent), heading dir, length len; its children,
 * its leaves. parent_branch: the parent's index in the log. */
static void branch(Gen *g, int gen, int32_t from, V3 p, double r_parent, V3 dir, double len, double bound,
                   int parent_branch, double f) {
    const PafcoParams *P = g->P;
    if (g->failed || !(len > 0)) return;
    long m = lround(P->seg_branch * len);
    if (m < 2) m = 2;
    double seg = len / (double)m;
    /* §4.3: the base diameter is length x VRV_POMER, never wider than the parent there */
    double r0 = fmin(0.5 * len * P->branch_dratio, r_parent);
    int32_t axis = g->axes++, first = -1, last = from;
    double grav = P->grav[gen - 1] * DEG, sun = P->sun[gen - 1] * DEG, scat = P->scatter * DEG;
    V3 *pts = malloc((size_t)(m + 1) * sizeof *pts);
    int32_t *ids = malloc((size_t)(m + 1) * sizeof *ids);
    V3 *hs = malloc((size_t)(m + 1) * sizeof *hs);
    if (!pts || !ids || !hs) {
        free(pts), free(ids), free(hs);
        g->failed = true;
        return;
    }
    pts[0] = p, ids[0] = from, hs[0] = dir;
    V3 h = dir;
    for (long k = 1; k <= m && !g->failed; k++) {
        /* gravity: down by VnG_GRAV at every segment (negative: up), never past vertical */
        double down = acos(fmax(-1, fmin(1, -h.y)));
        if (grav > 0 && down > 1e-9) h = turn_toward(h, v3(0, -1, 0), fmin(grav, down));
        else if (grav < 0 && M_PI - down > 1e-9) h = turn_toward(h, v3(0, 1, 0), fmin(-grav, M_PI - down));
        /* the sun: up toward the tip, by VnG_SUN at the last segment */
        double up = acos(fmax(-1, fmin(1, h.y))), s = sun * (double)k / (double)m;
        if (s > 0 && up > 1e-9) h = turn_toward(h, v3(0, 1, 0), fmin(s, up));
        else if (s < 0 && M_PI - up > 1e-9) h = turn_toward(h, v3(0, -1, 0), fmin(-s, M_PI - up));
        /* V_ROZPTYL: a random turn of at most that much about a random axis across h */
        if (scat > 0) {
            V3 a = perp(h), b = cross(h, a);
            double roll = uniform(g, 0, 2 * M_PI);
            h = turn_toward(h, add(scale(a, cos(roll)), scale(b, sin(roll))), uniform(g, 0, scat));
        }
        pts[k] = add(pts[k - 1], scale(h, seg));
        hs[k] = h;
        double r = r0 * (1 - (double)k / (double)m); /* linearly to 0 at the last point */
        last = ids[k] = node(g, pts[k], h, r, last, axis, gen, SYL_KIND_INTERNODE);
        if (k == 1) first = last;
    }
    int me = g->log ? g->log->n : -1;
    log_branch(g, (PafcoBranch){gen, first, last, parent_branch, from, (float)len, (float)bound, (float)f});
    /* children: generation 2 on the first NEXTG_POMER of a first-generation branch, 3 on all
     * of a second-generation one; one a control point, each in the next quadrant around the
     * parent, shorter toward the parent's tip (docs/pafco.md: the law is ours) */
    int child = gen + 1;
    if (child <= 3 && P->gen[child - 1] && !g->failed) {
        double extent = gen == 1 ? P->nextg : 1;
        for (long k = 1; k < m && !g->failed; k++) {
            double t = (double)k / (double)m;
            if (t > extent + 1e-9) break;
            double cb = fmin(P->maxlen[child - 1] * (1 - t), len);
            double cl = cb * uniform(g, 0.85, 1);
            double rk = r0 * (1 - t);
            V3 a = perp(hs[k]), b = cross(hs[k], a);
            double az = (g->quadrant++ % 4) * 90 * DEG + uniform(g, P->alfa_kor, 90 - P->alfa_kor) * DEG;
            V3 side = add(scale(a, cos(az)), scale(b, sin(az)));
            V3 cd = turn_toward(hs[k], side, P->angle[child - 1] * DEG);
            if (P->angle[child - 1] >= 180) cd = scale(hs[k], -1);
            branch(g, child, ids[k], pts[k], rk, cd, cl, cb, me, t);
        }
    }
    if (P->sph_leaves && !g->failed) cluster(g, pts[m], last);
    if (P->bil_leaves && gen == g->last_gen && !g->failed) /* §4.4.2: on the last generation's points */
        for (long k = 1; k <= m && !g->failed; k++) {
            V3 a = perp(hs[k]), b = cross(hs[k], a);
            double roll = 2 * M_PI * rng_unit(&g->leaf_rng);
            V3 side = add(scale(a, cos(roll)), scale(b, sin(roll)));
            V3 ld = P->bil_angle >= 180 ? scale(hs[k], -1) : turn_toward(hs[k], side, P->bil_angle * DEG);
            leaf(g, pts[k], ld, P->bil_length, ids[k]);
        }
    free(pts), free(ids), free(hs);
}

/* Whether a texture's file name has one of the words "a|b|c". */
static bool named(const char *name, const char *const *words, size_t n) {
    for (size_t i = 0; i < n; i++)
        if (strstr(name, words[i])) return true;
    return false;
}
static const char *const flower_words[] = {"flower", "blossom", "petal", "kvet"};
static const char *const needle_words[] = {"needle", "ihlic", "ihla"};

static void materials(Gen *g) {
    const PafcoParams *P = g->P;
    SylSkeleton *sk = g->sk;
    int n = P->ntex;
    if (P->ltex_count > 0 && P->ltex_count < n) n = P->ltex_count;
    g->nleafmat = n > 0 ? n : 1;
    static const float green[3] = {0.22f, 0.45f, 0.13f}, blossom[3] = {0.93f, 0.62f, 0.75f},
                       needle[3] = {0.10f, 0.26f, 0.10f};
    for (int i = 0; i < g->nleafmat; i++) {
        bool fl = n > 0 && named(P->tex_files[i], flower_words, 4), ne = n > 0 && named(P->tex_files[i], needle_words, 3);
        SylMaterial *mt = &sk->materials[1 + i];
        mt->kind = fl ? SYL_MATERIAL_FLOWER : SYL_MATERIAL_LEAF;
        /* leaf textures of their own are not read yet: a colour a file, by what its name says */
        const float *rgb = fl ? blossom : ne ? needle : green;
        for (int c = 0; c < 3; c++) mt->rgb[c] = rgb[c] * (1.0f - 0.12f * (float)(i % 3));
        if (P->bil_leaves) mt->translucency = (uint8_t)lround(255 * P->transluc); /* BIL_TRANSLUC */
    }
    sk->nmaterials = 1 + g->nleafmat;
    /* the leaves' surface: squares (§4.4.1), or LBIL_SIRKA x LBIL_DLZKA billboards */
    float width = P->bil_leaves && P->bil_length > 0 ? (float)(P->bil_width / P->bil_length) : 1.0f;
    if (!(width > 0)) width = 1.0f;
    for (int i = 0; i < g->nleafmat; i++) {
        SylMaterial *mt = &sk->materials[1 + i];
        mt->leaf_outline = SYL_LEAF_OUTLINE_SQUARE;
        mt->leaf_tris = 2;
        mt->leaf_width = width;
    }
    for (int o = 0; o < 4; o++) /* the stems' (all bark) rings: Table T.1 */
        sk->materials[SYL_MATERIAL_BARK].ring_sides[o] = (uint8_t)pafco_ring_points(P->detail, o);
}

int pafco_build(const PafcoParams *P, uint64_t seed, Budget *mem, SylSkeleton *sk, PafcoLog *log,
                const SylCancel *cancel) {
    Gen g = {.P = P, .sk = sk, .rng = rng_stream(seed, 0, 0x9afc02007ull, 0),
             .leaf_rng = rng_stream(seed, 1, 0x9afc02007ull, 0), .mem = mem, .log = log};
    /* the most the tree can hold, charged and reserved at once: past the budget, nothing is made */
    double nodes, leaves, bytes;
    if (!pafco_fits(P, mem, &nodes, &leaves, &bytes, NULL) || !budget_charge(mem, (uint64_t)bytes)) return SYL_ELIMIT;
    g.charged = (uint64_t)bytes;
    if (!skeleton_reserve_nodes(sk, sk->nnodes + (size_t)nodes) ||
        (leaves > 0 && !skeleton_reserve_organs(sk, sk->norgans + (size_t)leaves)))
        return SYL_ELIMIT;
    if (syl_cancelled(cancel)) return SYL_ECANCELED; /* before the trunk */
    g.last_gen = P->gen[1] ? (P->gen[2] ? 3 : 2) : 1;
    materials(&g);
    const double H = P->height;
    /* §4.2: round(SEG_KMEN x VYSKA_STROMU) control points; the top's deviation at most
     * MAX_ROZPTYL_KMEN, its largest falling linearly to 0 at the base */
    long n = lround(P->seg_trunk * H);
    if (n < 2) n = 2;
    double r0 = 0.5 * H * P->trunk_dratio;
    V3 *tp = malloc((size_t)(n + 1) * sizeof *tp);
    int32_t *tid = malloc((size_t)(n + 1) * sizeof *tid);
    if (!tp || !tid) {
        free(tp), free(tid);
        return SYL_ELIMIT;
    }
    for (long i = 0; i <= n; i++) {
        double a = uniform(&g, 0, 2 * M_PI), d = sqrt(rng_unit(&g.rng)) * P->trunk_dev * (double)i / (double)n;
        tp[i] = v3(d * cos(a), H * (double)i / (double)n, d * sin(a));
    }
    g.axes = 1;
    int32_t prev = -1;
    for (long i = 0; i <= n; i++) {
        V3 h = norm(i < n ? add(tp[i + 1], scale(tp[i], -1)) : add(tp[i], scale(tp[i - 1], -1)));
        prev = tid[i] = node(&g, tp[i], h, r0 * (1 - (double)i / (double)n), prev, 0, 0,
                             i ? SYL_KIND_INTERNODE : SYL_KIND_ROOT);
    }
    log_branch(&g, (PafcoBranch){0, tid[0], tid[n], -1, -1, (float)H, (float)H, 0});
    /* the crown: KORUNA_KMEN of the height (above 1: the appendix's height / crown) */
    double crown = P->crown_ratio <= 1 ? P->crown_ratio * H : H / P->crown_ratio, base = H - crown;
    double longest = P->width_ratio * H;
    bool stopped = false;
    for (long i = 1; i < n && !g.failed; i++) {
        if (tp[i].y < base - 1e-9) continue;
        if (syl_cancelled(cancel)) { /* before each whorl of first-generation branches */
            stopped = g.failed = true;
            break;
        }
        double f = crown > 0 ? (tp[i].y - base) / crown : 1;
        V3 th = norm(add(tp[i + 1], scale(tp[i - 1], -1)));
        V3 a = perp(th), b = cross(th, a);
        double angle = fmax(0, fmin(180, P->angle[0] + P->uhp * f)) * DEG;
        double bound = longest * pafco_crown_profile(P->round_crown, f);
        for (int w = 0; w < P->whorl && !g.failed; w++) {
            /* the quadrant spiral: α = rand(ALFA_KOR, 90° − ALFA_KOR) in the next quadrant */
            double az = (g.quadrant++ % 4) * 90 * DEG + uniform(&g, P->alfa_kor, 90 - P->alfa_kor) * DEG;
            double len = bound * uniform(&g, 0.8, 1);
            V3 side = add(scale(a, cos(az)), scale(b, sin(az)));
            V3 dir = angle >= M_PI ? scale(th, -1) : turn_toward(th, side, angle);
            if (len >= 0.01) branch(&g, 1, tid[i], tp[i], r0 * (1 - (double)i / (double)n), dir, len, bound, 0, f);
        }
    }
    if (P->sph_leaves && !g.failed) cluster(&g, tp[n], tid[n]); /* the trunk's end has its cluster too */
    free(tp), free(tid);
    return stopped ? SYL_ECANCELED : g.failed ? SYL_ELIMIT : SYL_OK;
}
