/* The growth engine: Borchert–Honda conservation, apical dominance against lambda,
 * obstacles, shedding, the pipe model, competition between neighbours, L-system plants as
 * shadow casters, determinism (reruns, threads), directives and their errors, phyllotaxis
 * and gravimorphism. */
#include <math.h>
#include <sys/stat.h>
#include <unistd.h>

#include "unit.h"

#include "env/objread.h"
#include "sot/allocate.h"
#include "sot/forest.h"
#include "sot/forest_internal.h"
#include "sot/phyllotaxis.h"
#include "sot/shed.h"
#include "sylva/grow.h"

/* A plain broadleaf: shadow propagation, no randomness in the directions. */
#define TREE(extra)                                                                    \
    "grow T {\n  years 9\n  internode 0.3\n  buds alternate angle 45\n"                \
    "  light shadow a 0.2 b 3 depth 5\n  sensitivity 1.2\n  shoot relative max 3\n"   \
    "  direction bud 1 light 0.3 tropism 0.1 trunk 0.4 jitter 0\n" extra "}\n"

static GrowParams params_of(const char *text) {
    char *diag = NULL;
    SylProgram *p = unit_compile(text, &diag, NULL);
    if (!p) fail_msg("%s", diag);
    free(diag);
    GrowParams P;
    assert_int_equal(grow_params_read(p, &P, stderr), 0);
    syl_program_free(p);
    return P;
}

/* A forest of one tree, grown for P's years. */
static void grow_one(Forest *f, GrowParams *P, int threads) {
    assert_int_equal(forest_init(f, threads, stderr, NULL), SYL_OK);
    const float base[3] = {0, 0, 0};
    assert_int_equal(forest_add_tree(f, P, base, P->years), SYL_OK);
    assert_int_equal(forest_setup(f, 0, P->sun, false), SYL_OK);
    assert_int_equal(forest_run(f, NULL, NULL), SYL_OK);
}

static char *skeleton_csv(const SylSkeleton *sk) {
    char *out = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&out, &len);
    syl_skeleton_write_csv(sk, mem);
    fclose(mem);
    return out;
}

/* Grow a model (or its file's scene) from text; the skeleton as CSV, or NULL. */
static char *grow_text(const char *path, const char *text, bool scene, int threads, char **diag) {
    size_t dlen = 0;
    char *d = NULL;
    FILE *mem = open_memstream(&d, &dlen);
    SylCompileOptions co = {.diag = mem, .validate = syl_validate};
    int st;
    SylProgram *p = syl_compile(path, text, strlen(text), &co, &st);
    char *csv = NULL;
    if (p) {
        SylGrowOptions go = {.years = -1, .threads = threads, .diag = mem};
        SylSkeleton *sk = NULL;
        st = scene ? syl_grow_build_scene(p, &go, &sk, NULL) : syl_grow_build(p, &go, &sk);
        if (!st) csv = skeleton_csv(sk);
        syl_skeleton_free(sk);
        syl_program_free(p);
    }
    fclose(mem);
    if (diag) *diag = d;
    else free(d);
    return csv;
}

/* One skeleton CSV row: false at the end. */
typedef struct Row {
    int id, parent, order;
    double x, y, z, r;
    char kind[16];
} Row;

static bool next_row(char **at, Row *row) {
    char *line = *at;
    if (!line || !*line) return false;
    char *eol = strchr(line, '\n');
    *at = eol ? eol + 1 : NULL;
    return sscanf(line, "%d,%d,%lf,%lf,%lf,%lf,%d,%15[a-z]", &row->id, &row->parent, &row->x, &row->y, &row->z,
                  &row->r, &row->order, row->kind) == 8;
}

/* ---- Borchert–Honda ---- */

typedef struct Kids {
    int32_t *first, *next;
} Kids;

static Kids kids_of(const Tree *t) {
    Kids k = {malloc(t->n * sizeof(int32_t)), malloc(t->n * sizeof(int32_t))};
    for (size_t i = 0; i < t->n; i++) k.first[i] = -1;
    for (size_t i = t->n; i-- > 1;) {
        int32_t p = t->nodes[i].parent;
        k.next[i] = k.first[p];
        k.first[p] = (int32_t)i;
    }
    return k;
}

/* Demand of the subtree of i (candidate buds' z), by recursion over child lists. */
static double subtree_demand(const Tree *t, const Kids *k, int32_t i, int year) {
    double q = 0;
    for (size_t b = 0; b < t->nb; b++)
        if (t->buds[b].node == i && alloc_candidate(&t->buds[b], year)) q += t->buds[b].z;
    for (int32_t c = k->first[i]; c >= 0; c = k->next[c]) q += subtree_demand(t, k, c, year);
    return q;
}

/* The resource bud v's of subtree i add up to what BH sends into node i, at every node. */
static void check_fork(const Tree *t, const Kids *k, int32_t i, double v, int year, double lambda, double *worst) {
    double M = 0, L = 0;
    for (size_t b = 0; b < t->nb; b++)
        if (t->buds[b].node == i && alloc_candidate(&t->buds[b], year)) {
            if (t->buds[b].kind == BUD_APICAL) M += t->buds[b].z;
            else L += t->buds[b].z;
        }
    for (int32_t c = k->first[i]; c >= 0; c = k->next[c]) {
        double q = subtree_demand(t, k, c, year);
        if (c == t->nodes[i].main) M += q;
        else L += q;
    }
    double den = lambda * M + (1 - lambda) * L, out = 0;
    for (size_t b = 0; b < t->nb; b++)
        if (t->buds[b].node == i && alloc_candidate(&t->buds[b], year)) {
            double want = den > 0 ? v * (t->buds[b].kind == BUD_APICAL ? lambda : 1 - lambda) * t->buds[b].z / den : 0;
            *worst = fmax(*worst, fabs(t->buds[b].v - want) / fmax(v, 1e-12));
            out += want;
        }
    for (int32_t c = k->first[i]; c >= 0; c = k->next[c]) {
        double q = subtree_demand(t, k, c, year);
        double vc = den > 0 ? v * (c == t->nodes[i].main ? lambda : 1 - lambda) * q / den : 0;
        out += vc;
        check_fork(t, k, c, vc, year, lambda, worst);
    }
    if (fabs(out - v) > 1e-9 * fmax(v, 1)) fail_msg("node %d: %.17g in, %.17g out", i, v, out);
}

static void bh_conserves_at_every_fork(void **state) {
    (void)state;
    GrowParams P = params_of(TREE("  allocate bh lambda 0.53 alpha 2\n"));
    P.years = 6;
    Forest f;
    grow_one(&f, &P, 1);
    Tree *t = &f.trees[0];
    int year = 7;
    assert_int_equal(forest_light(&f, year), SYL_OK);
    alloc_demand(t, year);
    assert_true(alloc_resources(t, year));
    Kids k = kids_of(t);
    double total = subtree_demand(t, &k, 0, year), worst = 0, sum = 0;
    assert_true(total > 0);
    check_fork(t, &k, 0, 2 * total, year, t->P.lambda, &worst);
    if (!(worst < 1e-9)) fail_msg("a bud's resource differs by %g of its node's", worst);
    for (size_t b = 0; b < t->nb; b++) sum += t->buds[b].v;
    assert_near(sum, 2 * total, 1e-9 * total); /* alpha * Q at the base, all of it delivered */
    free(k.first);
    free(k.next);
    forest_free(&f);
}

/* ---- apical dominance ---- */

static double trunk_share(double lambda) {
    GrowParams P = params_of(TREE(""));
    P.lambda = (float)lambda;
    P.years = 8;
    P.sensitivity = 2;
    Forest f;
    grow_one(&f, &P, 1);
    const Tree *t = &f.trees[0];
    size_t trunk = 0;
    for (size_t i = 1; i < t->n; i++) trunk += t->nodes[i].order == 0;
    double share = (double)trunk / (double)(t->n - 1);
    forest_free(&f);
    return share;
}

static void lambda_raises_apical_dominance(void **state) {
    (void)state;
    double prev = -1;
    for (int k = 0; k <= 4; k++) {
        double lambda = 0.46 + 0.02 * k, share = trunk_share(lambda);
        if (!(share > prev)) fail_msg("lambda %.2f: trunk share %.4f, not above %.4f", lambda, share, prev);
        prev = share;
    }
}

/* ---- obstacles ---- */

static char tmpdir[64];

static void write_file(const char *name, const char *text) { unit_write_file(tmpdir, name, text); }

static int setup_dir(void **state) {
    (void)state;
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sylva-sot-XXXXXX");
    if (!mkdtemp(tmpdir)) return -1;
    /* a wall along z = 0 (x -3..3, y 0..4, 0.2 thick) with a hole x -0.6..0.6, y 1.5..2.7 */
    const float boxes[4][4] = {{-3, -0.6f, 0, 4}, {0.6f, 3, 0, 4}, {-0.6f, 0.6f, 0, 1.5f}, {-0.6f, 0.6f, 2.7f, 4}};
    char buf[8192];
    size_t used = 0;
    for (int b = 0; b < 4; b++) {
        for (int v = 0; v < 8; v++)
            used += (size_t)snprintf(buf + used, sizeof buf - used, "v %g %g %g\n", boxes[b][(v >> 2) & 1],
                                     boxes[b][2 + ((v >> 1) & 1)], (v & 1) ? 0.1 : -0.1);
        static const int q[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
        for (int f = 0; f < 6; f++)
            used += (size_t)snprintf(buf + used, sizeof buf - used, "f %d %d %d %d\n", 8 * b + q[f][0] + 1,
                                     8 * b + q[f][1] + 1, 8 * b + q[f][2] + 1, 8 * b + q[f][3] + 1);
    }
    write_file("wall.obj", buf);
    write_file("bad.obj", "v 0 0 0\nv 1 0 0 oops\n");
    return 0;
}

static int teardown_dir(void **state) {
    (void)state;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    return system(cmd) == 0 ? 0 : -1;
}

/* Möller–Trumbore: does segment a-b cross triangle (p, q, r)? */
static bool segment_hits(const double a[3], const double b[3], const double p[3], const double q[3], const double r[3]) {
    double d[3], e1[3], e2[3], h[3], s[3], qq[3];
    for (int k = 0; k < 3; k++) d[k] = b[k] - a[k], e1[k] = q[k] - p[k], e2[k] = r[k] - p[k];
    h[0] = d[1] * e2[2] - d[2] * e2[1], h[1] = d[2] * e2[0] - d[0] * e2[2], h[2] = d[0] * e2[1] - d[1] * e2[0];
    double det = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
    if (fabs(det) < 1e-12) return false;
    double inv = 1 / det;
    for (int k = 0; k < 3; k++) s[k] = a[k] - p[k];
    double u = inv * (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]);
    if (u < 0 || u > 1) return false;
    qq[0] = s[1] * e1[2] - s[2] * e1[1], qq[1] = s[2] * e1[0] - s[0] * e1[2], qq[2] = s[0] * e1[1] - s[1] * e1[0];
    double v = inv * (d[0] * qq[0] + d[1] * qq[1] + d[2] * qq[2]);
    if (v < 0 || u + v > 1) return false;
    double t = inv * (e2[0] * qq[0] + e2[1] * qq[1] + e2[2] * qq[2]);
    return t >= 0 && t <= 1;
}

static void no_segment_enters_an_obstacle(void **state) {
    (void)state;
    char path[128];
    snprintf(path, sizeof path, "%s/scene.syl", tmpdir);
    const char *text = TREE("  space bud markers 8 occupancy 2 perception 5 cone 100\n"
                            "  direction bud 1 space 0.6 light 0.2 trunk 0.3 jitter 10\n")
        "scene {\n  obstacle \"wall.obj\"\n  plant T at (0.2, 0, -0.8) years 12\n}\n";
    /* the TREE macro's direction line comes first: drop it so the second one counts */
    char *fixed = strdup(text);
    char *first = strstr(fixed, "  direction bud 1 light 0.3");
    assert_non_null(first);
    memset(first, ' ', strchr(first, '\n') - first);
    char *diag = NULL;
    char *csv = grow_text(path, fixed, true, 1, &diag);
    if (!csv) fail_msg("%s", diag);
    free(diag);
    /* read the skeleton back */
    double (*pos)[3] = malloc(100000 * sizeof *pos);
    int *parent = malloc(100000 * sizeof *parent);
    int n = 0, behind = 0;
    char *at = strchr(csv, '\n') + 1;
    Row row;
    while (n < 100000 && next_row(&at, &row) && (!strcmp(row.kind, "internode") || !strcmp(row.kind, "root"))) {
        pos[n][0] = row.x, pos[n][1] = row.y, pos[n][2] = row.z;
        parent[n++] = row.parent;
        behind += row.z > 0.1;
    }
    assert_true(n > 500);
    /* the wall's triangles, by an independent reading of the file */
    ObjMesh wall;
    char wpath[128];
    snprintf(wpath, sizeof wpath, "%s/wall.obj", tmpdir);
    assert_int_equal(obj_read(wpath, &wall, NULL), SYL_OK);
    int hits = 0;
    for (int i = 0; i < n; i++) {
        if (parent[i] < 0) continue;
        for (size_t t = 0; t < wall.nt; t++) {
            double p[3][3];
            for (int v = 0; v < 3; v++)
                for (int k = 0; k < 3; k++) p[v][k] = wall.v[3 * wall.tri[3 * t + v] + k];
            hits += segment_hits(pos[parent[i]], pos[i], p[0], p[1], p[2]);
        }
    }
    assert_int_equal(hits, 0);
    assert_true(behind > 0); /* some shoots found the hole */
    obj_free(&wall);
    free(pos);
    free(parent);
    free(csv);
    free(fixed);
}

static void malformed_obstacle_is_reported(void **state) {
    (void)state;
    char path[128];
    snprintf(path, sizeof path, "%s/scene.syl", tmpdir);
    const char *text = TREE("") "scene {\n  obstacle \"bad.obj\"\n  plant T at (0, 0, 0)\n}\n";
    char *diag = NULL;
    char *csv = grow_text(path, text, true, 1, &diag);
    assert_null(csv);
    assert_contains(diag, "bad.obj:2:9: error: unexpected 'oops' after a vertex's coordinates");
    assert_contains(diag, "scene.syl:11:12: error: cannot use the obstacle \"bad.obj\"");
    free(diag);
}

/* ---- shedding ---- */

static int32_t add(Tree *t, int32_t parent, bool lateral, float light) {
    Node nd = t->nodes[parent];
    nd.parent = parent;
    nd.main = -1;
    nd.flags = lateral ? NODE_LATERAL : 0;
    nd.order = (uint16_t)(t->nodes[parent].order + lateral);
    nd.light = light;
    nd.pos[1] += 1;
    int32_t id = tree_add_node(t, &nd);
    if (!lateral) t->nodes[parent].main = id;
    return id;
}

static void shedding_by_light_ratio(void **state) {
    (void)state;
    GrowParams P = params_of(TREE("  shed threshold 0.4\n"));
    Tree t;
    const float base[3] = {0, 0, 0};
    assert_true(tree_init(&t, &P, 0, base, 0));
    int32_t a = add(&t, 0, false, 1), b = add(&t, a, false, 1), c = add(&t, b, false, 1);
    /* a branch is everything above its base. L1 at a: 0.9, 0.6 and its twig L2 (0.1, 0.2):
     * 1.8 / 4 = 0.45, kept; L2 alone: 0.15, shed */
    int32_t l1 = add(&t, a, true, 0.9f), l1b = add(&t, l1, false, 0.6f);
    int32_t l2 = add(&t, l1, true, 0.1f), l2b = add(&t, l2, false, 0.2f);
    /* L3 at b: 0.3, 0.9, 0.1 -> 0.43 kept; L4 at c: 0.35 alone -> shed */
    int32_t l3 = add(&t, b, true, 0.3f), l3b = add(&t, l3, false, 0.9f), l3c = add(&t, l3b, false, 0.1f);
    int32_t l4 = add(&t, c, true, 0.35f);
    /* L5 at c: 0.1 with a bright twig L6 (0.9): 0.5 overall, kept with its twig */
    int32_t l5 = add(&t, c, true, 0.1f), l6 = add(&t, l5, true, 0.9f);
    /* L7 at b: 0.2 with a bright twig (0.5): 0.35 overall: shed whole, twig and all */
    int32_t l7 = add(&t, b, true, 0.2f), l8 = add(&t, l7, true, 0.5f);
    size_t marked = shed_mark(&t, NULL);
    const int32_t dead[] = {l2, l2b, l4, l7, l8}, alive[] = {0, a, b, c, l1, l1b, l3, l3b, l3c, l5, l6};
    for (size_t i = 0; i < sizeof dead / sizeof *dead; i++)
        if (!(t.nodes[dead[i]].flags & NODE_DEAD)) fail_msg("node %d should be shed", dead[i]);
    for (size_t i = 0; i < sizeof alive / sizeof *alive; i++)
        if (t.nodes[alive[i]].flags & NODE_DEAD) fail_msg("node %d should stay", alive[i]);
    assert_int_equal(marked, 5);
    assert_int_equal(t.shed_branches, 3);
    /* the pipe model remembers them */
    assert_true(t.nodes[l1].pipe > 0 && t.nodes[c].pipe > 0 && t.nodes[b].pipe > 0);
    assert_true(tree_compact(&t, NULL));
    assert_int_equal(t.n, 11);
    tree_free(&t);
}

static void bare_trunk_clears_low_branches(void **state) {
    (void)state;
    GrowParams P = params_of(TREE("  shed bare_trunk 2.5\n"));
    P.years = 10;
    Forest f;
    grow_one(&f, &P, 1);
    const Tree *t = &f.trees[0];
    size_t kept = 0;
    for (size_t i = 1; i < t->n; i++) {
        const Node *nd = &t->nodes[i];
        if ((nd->flags & NODE_LATERAL) && t->nodes[nd->parent].order == 0) {
            assert_true(t->nodes[nd->parent].pos[1] >= 2.5f);
            kept++;
        }
    }
    assert_true(kept > 0);
    forest_free(&f);
}

/* ---- pipe model ---- */

static void pipe_model_at_every_fork(void **state) {
    (void)state;
    for (int shed = 0; shed < 2; shed++) {
        GrowParams P = params_of(TREE("  pipe exponent 2.5 tip 0.004\n"));
        if (shed) P.shed_threshold = 0.3f;
        Forest f;
        grow_one(&f, &P, 1);
        Tree *t = &f.trees[0];
        if (shed) assert_true(t->shed_branches > 0);
        assert_true(pipe_areas(t));
        const double *A = t->acc;
        int forks = 0;
        for (size_t i = 1; i < t->n; i++) {
            double r = pipe_radius(&t->P, A[i]), sum = 0;
            int kids = 0;
            for (size_t c = i + 1; c < t->n; c++)
                if (t->nodes[c].parent == (int32_t)i) {
                    double rc = pipe_radius(&t->P, A[c]);
                    sum += pow(rc, 2.5);
                    kids++;
                }
            if (!kids) {
                assert_near(r, 0.004 * pow(1 + t->nodes[i].pipe / pow(0.004, 2.5), 1 / 2.5), 1e-6);
                continue;
            }
            sum += t->nodes[i].pipe; /* the shed branches' share */
            forks += kids > 1;
            if (fabs(pow(r, 2.5) - sum) > 1e-5 * sum) fail_msg("node %zu: r^n %.9g, children %.9g", i, pow(r, 2.5), sum);
        }
        assert_true(forks > 20);
        forest_free(&f);
    }
}

/* ---- neighbours ---- */

static void neighbours_grow_apart(void **state) {
    (void)state;
    char path[128];
    snprintf(path, sizeof path, "%s/pair.syl", tmpdir);
    const char *text = TREE("") "scene {\n  plant T at (-1.2, 0, 0) years 14\n  plant T at (1.2, 0, 0) years 14\n}\n";
    char *diag = NULL;
    char *csv = grow_text(path, text, true, 1, &diag);
    if (!csv) fail_msg("%s", diag);
    free(diag);
    double sum[2] = {0}, count[2] = {0};
    int tree = -1;
    char *at = strchr(csv, '\n') + 1;
    Row row;
    while (next_row(&at, &row)) {
        if (!strcmp(row.kind, "root")) tree++;
        if (strcmp(row.kind, "internode") || tree < 0 || tree > 1 || row.y < 1.5) continue;
        sum[tree] += row.x - (tree ? 1.2 : -1.2);
        count[tree]++;
    }
    if (!(count[0] > 200 && count[1] > 200)) fail_msg("%g and %g metamers above 1.5 m", count[0], count[1]);
    double left = sum[0] / count[0], right = sum[1] / count[1];
    if (!(left < -0.1 && right > 0.1)) fail_msg("crowns: left %+.3f, right %+.3f from their trunks", left, right);
    free(csv);
}

/* An L-system plant casts shadow: a flat roof of short segments (a zigzag of 16 rows, 4 m by
 * 4 m, 2 m up) over a tree whose shoots grow with the light they get (vigor) leaves it fewer
 * metamers. */
static size_t below(char *csv, double height) {
    size_t n = 0;
    int plant = -1;
    char *at = strchr(csv, '\n') + 1;
    Row row;
    while (next_row(&at, &row)) {
        if (!strcmp(row.kind, "root")) plant++;
        n += plant == 0 && !strcmp(row.kind, "internode") && row.y < height;
    }
    return n;
}

#define VIGOR                                                                                    \
    "grow T {\n  years 9\n  internode 0.3\n  light shadow a 0.2 b 3 depth 5\n  shoot vigor max 3\n" \
    "  allocate bh alpha 1.6\n  direction jitter 0\n}\n"

static void lsystem_plants_cast_shadow(void **state) {
    (void)state;
    char path[128];
    snprintf(path, sizeof path, "%s/roof.syl", tmpdir);
    char text[4096];
    snprintf(text, sizeof text,
             "%s"
             "lsystem Roof {\n  derive 8\n  axiom &(90) X\n  R -> FFFFFFFFFFFFFFFF\n  step 0.25\n"
             "  X -> R +(90) F +(90) R -(90) F -(90) X\n}\n"
             "scene {\n  plant T at (0, 0, 0)\n  plant Roof at (2, 2, 2)\n}\n",
             VIGOR);
    char *diag = NULL;
    char *csv = grow_text(path, text, true, 1, &diag);
    if (!csv) fail_msg("%s", diag);
    free(diag);
    size_t shaded = below(csv, 100);
    free(csv);
    csv = grow_text("alone.syl", VIGOR, false, 1, NULL);
    assert_non_null(csv);
    size_t alone = below(csv, 100);
    free(csv);
    if (!(shaded < alone * 2 / 3)) fail_msg("under the roof %zu metamers, alone %zu", shaded, alone);
}

/* ---- determinism ---- */

static void reruns_and_threads_agree(void **state) {
    (void)state;
    const char *models[] = {
        TREE("  shed threshold 0.2\n  organ leaf size 0.1 count 2\n"),
        TREE("  space bud markers 6 occupancy 2 perception 4 cone 90\n"),
        TREE("  space global density 3 occupancy 2 perception 4 cone 90\n"),
        "grow S {\n  years 5\n  light sky rays 8\n  shoot vigor max 3\n  allocate priority kappa 0.4\n}\n",
    };
    for (size_t m = 0; m < sizeof models / sizeof *models; m++) {
        char *a = grow_text("t.syl", models[m], false, 1, NULL);
        char *b = grow_text("t.syl", models[m], false, 1, NULL);
        char *c = grow_text("t.syl", models[m], false, 2, NULL);
        assert_non_null(a);
        assert_true(strlen(a) > 1000);
        assert_string_equal(a, b);
        assert_string_equal(a, c);
        free(a), free(b), free(c);
    }
}

/* ---- directives ---- */

static void directive_errors(void **state) {
    (void)state;
    static const struct {
        const char *line, *message;
    } cases[] = {
        {"  lite shadow\n", "test.syl:2:3: error: unknown directive 'lite' in a grow block"},
        {"  allocate bh lamda 0.5\n", "test.syl:2:15: error: unknown key 'lamda' of 'allocate' (did you mean 'lambda'?)"},
        {"  allocate bh lambda 1.5\n", "test.syl:2:22: error: lambda must be in [0, 1], not 1.5"},
        {"  light sky voxel 2\n", "test.syl:2:13: error: 'voxel' is not a key of 'light sky'"},
        {"  buds whorled\n", "test.syl:2:8: error: 'whorled' expects a whole number of buds from 1 to 32 after it"},
        {"  years 2.5\n", "test.syl:2:9: error: years takes a whole number in [0, 10000], not 2.5"},
        {"  direction trunk_tropism maybe\n", "test.syl:2:27: error: 'trunk_tropism' expects on or off"},
        {"  organ petal\n", "test.syl:2:9: error: 'organ' expects leaf, flower or needle first, not 'petal'"},
        {"  space occupancy 3 perception 2\n", "test.syl:2:3: error: 'space': perception (2) must reach beyond occupancy (3)"},
        {"  years 3\n  years 4\n", "test.syl:3:3: error: 'years' is given twice (first at line 2)"},
        {"  light sun (0, -1, 0)\n", "the sun must be above the horizon"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char text[512], *diag = NULL;
        snprintf(text, sizeof text, "grow G {\n%s}\n", cases[i].line);
        int st;
        SylProgram *p = unit_compile(text, &diag, &st);
        assert_null(p);
        assert_int_equal(st, SYL_EMODEL);
        assert_contains(diag, cases[i].message);
        free(diag);
    }
    /* the design brief's example, and values from parameters */
    const char *ok = "param lam = 0.52\ngrow Birch {\n  years 18\n  seed 7\n  internode 0.3\n"
                     "  buds alternate divergence 137.5 angle 45\n  light shadow voxel 0.3 a 1.0 b 1.5 depth 6\n"
                     "  space markers 20 occupancy 2 perception 5 cone 90\n  allocate bh lambda (lam) alpha 2\n"
                     "  sensitivity 1.2\n  shoot max 4\n  direction bud 1 space 0.4 tropism 0.2 at 70 trunk 0.5\n"
                     "  shed threshold 0.3 bare_trunk 1.5\n  pipe exponent 2.5 tip 0.004\n"
                     "  organ leaf ~leaf(0.06) on young\n}\n";
    char *diag = NULL;
    SylProgram *p = unit_compile(ok, &diag, NULL);
    if (!p) fail_msg("%s", diag);
    free(diag);
    GrowParams P;
    assert_int_equal(grow_params_read(p, &P, NULL), 0);
    assert_near(P.lambda, 0.52, 1e-6);
    assert_int_equal(P.space, SPACEM_BUD);
    assert_int_equal(P.markers, 20);
    assert_int_equal(P.shoot, SHOOT_RELATIVE);
    assert_int_equal(P.shoot_max, 4);
    assert_int_equal(P.norgans, 1);
    assert_near(P.organs[0].size, 0.06, 1e-6);
    syl_program_free(p);
    /* every key lands in its own field */
    P = params_of("grow G {\n  seed 12345678901\n  organ needle size 0.08 count 8 angle 55 age 5 chance 0.5 on tips\n}\n");
    assert_true(P.seed == 12345678901ull);
    assert_int_equal(P.organs[0].kind, SYL_KIND_NEEDLE);
    assert_near(P.organs[0].size, 0.08, 1e-6);
    assert_int_equal(P.organs[0].count, 8);
    assert_near(P.organs[0].angle, 55, 1e-6);
    assert_int_equal(P.organs[0].age, 5);
    assert_near(P.organs[0].chance, 0.5, 1e-6);
    assert_int_equal(P.organs[0].place, ORGAN_TIPS);
    /* --set reaches a directive through a param */
    SylOverride set = {"lam", 0.47};
    SylCompileOptions co = {.overrides = &set, .noverrides = 1, .validate = syl_validate};
    int st;
    p = syl_compile("test.syl", ok, strlen(ok), &co, &st);
    assert_non_null(p);
    assert_int_equal(grow_params_read(p, &P, NULL), 0);
    assert_near(P.lambda, 0.47, 1e-6);
    syl_program_free(p);
}

static void scene_errors(void **state) {
    (void)state;
    const char *text = "grow G {\n  years 2\n}\nscene {\n  plant Nope at (0, 0, 0)\n  plant G at (1, 2)\n"
                       "  sun direction (0, -1, 0)\n  fog on\n}\n";
    char *diag = NULL;
    SylProgram *p = unit_compile(text, &diag, NULL);
    assert_null(p);
    assert_contains(diag, "test.syl:5:9: error: no plant model 'Nope' in this file (an lsystem, grow, weber or strands block)");
    assert_contains(diag, "test.syl:6:14: error: 'at' expects a point (x, y, z)");
    assert_contains(diag, "test.syl:7:17: error: the sun must be above the horizon (y > 0)");
    assert_contains(diag, "test.syl:8:3: error: unknown directive 'fog' in a scene");
    free(diag);
}

/* ---- phyllotaxis and gravimorphism ---- */

/* syl_compile checks the language only; a grow block's directives and the scene are the
 * hook's (SylCompileOptions.validate): without it a wrong directive compiles, with
 * syl_validate it is an error, and the scene is checked with the file's first model. */
static SylProgram *compile_hooked(const char *text, const char *model, bool hook, char **diag, int *st) {
    size_t len = 0;
    FILE *mem = open_memstream(diag, &len);
    SylCompileOptions co = {.model = model, .diag = mem, .validate = hook ? syl_validate : NULL};
    SylProgram *p = syl_compile("test.syl", text, strlen(text), &co, st);
    fclose(mem);
    return p;
}

static int count_calls(void *user, const SylProgram *p, FILE *diag) {
    (void)p, (void)diag;
    ++*(int *)user;
    return 0;
}

static void directives_checked_by_the_hook(void **state) {
    (void)state;
    const char *grow = "grow G {\n  years 2\n  fog on\n}\n";
    char *diag = NULL;
    int st = -1;
    SylProgram *p = compile_hooked(grow, NULL, false, &diag, &st);
    assert_non_null(p); /* the check is the caller's */
    assert_int_equal(st, SYL_OK);
    assert_string_equal(diag, "");
    free(diag);
    diag = NULL;
    SylGrowOptions go = {.years = -1, .threads = 1, .diag = open_memstream(&diag, &(size_t){0})};
    SylSkeleton *sk = NULL;
    assert_int_equal(syl_grow_build(p, &go, &sk), SYL_EMODEL); /* growing reads the same directives */
    fclose(go.diag);
    assert_contains(diag, "test.syl:3:3: error: unknown directive 'fog' in a grow block");
    free(diag);
    syl_program_free(p);

    diag = NULL;
    assert_null(compile_hooked(grow, NULL, true, &diag, &st));
    assert_int_equal(st, SYL_EMODEL);
    assert_contains(diag, "test.syl:3:3: error: unknown directive 'fog' in a grow block");
    free(diag);

    const char *scene = "lsystem A {\n  axiom X\n}\nlsystem B {\n  axiom Y\n}\nscene {\n  fog on\n}\n";
    diag = NULL;
    assert_null(compile_hooked(scene, "A", true, &diag, &st));
    assert_contains(diag, "test.syl:8:3: error: unknown directive 'fog' in a scene");
    free(diag);
    diag = NULL;
    p = compile_hooked(scene, "B", true, &diag, &st); /* not the first: the scene was A's */
    assert_non_null(p);
    assert_string_equal(diag, "");
    free(diag);
    syl_program_free(p);

    /* the hook runs once, with its user pointer, and only on a program without errors */
    int calls = 0;
    SylCompileOptions co = {.validate = count_calls, .validate_user = &calls};
    p = syl_compile("test.syl", scene, strlen(scene), &co, &st);
    assert_non_null(p);
    assert_int_equal(calls, 1);
    syl_program_free(p);
    const char *wrong = "lsystem A {\n  axiom X(\n}\n";
    assert_null(syl_compile("test.syl", wrong, strlen(wrong), &co, &st));
    assert_int_equal(calls, 1);
}

static void phyllotaxis_directions(void **state) {
    (void)state;
    GrowParams P = params_of("grow G {\n  buds opposite angle 90\n}\n");
    assert_int_equal(P.laterals, 2);
    assert_near(P.divergence, 90, 1e-6);
    Node nd = {.h = {0, 1, 0}, .l = {1, 0, 0}, .rank = 0};
    float a[3], b[3];
    phyl_lateral_dir(&P, &nd, 0, a);
    phyl_lateral_dir(&P, &nd, 1, b);
    assert_near(a[0], 1, 1e-6);
    assert_near(b[0], -1, 1e-6); /* opposite */
    nd.rank = 1;                 /* decussate: the next pair turned by 90 degrees */
    phyl_lateral_dir(&P, &nd, 0, a);
    assert_near(fabs(a[2]), 1, 1e-6);
    P = params_of("grow G {\n  buds whorled 3 angle 30\n}\n");
    nd.rank = 0;
    float d[3][3];
    for (int k = 0; k < 3; k++) phyl_lateral_dir(&P, &nd, k, d[k]);
    for (int k = 0; k < 3; k++) {
        assert_near(d[k][1], cos(30 * M_PI / 180), 1e-6);
        double dot = d[k][0] * d[(k + 1) % 3][0] + d[k][2] * d[(k + 1) % 3][2];
        assert_near(dot, 0.25 * cos(120 * M_PI / 180), 1e-5); /* 120 degrees apart, radius sin 30 */
    }
}

static void gravimorphism_prefers(void **state) {
    (void)state;
    GrowParams P = params_of("grow G {\n  gravimorphism horizontal 2 vertical 0.5 up 0\n}\n");
    const float up[3] = {0, 1, 0}, flat[3] = {1, 0, 0};
    const float side[3] = {0, 0, 1}, upward[3] = {0, 1, 0}, tilted[3] = {0.7071f, 0.7071f, 0};
    assert_near(phyl_gravimorphism(&P, up, side), 1, 1e-6);       /* a vertical branch: no effect */
    assert_near(phyl_gravimorphism(&P, flat, side), 2, 1e-5);     /* horizontal bud on a flat branch */
    assert_near(phyl_gravimorphism(&P, flat, upward), 0.5, 1e-5); /* upward bud on a flat branch */
    float mid = phyl_gravimorphism(&P, tilted, side);              /* half the effect at 45 degrees */
    assert_near(mid, 0.5 + 0.5 * 2, 1e-4);
    P = params_of("grow G {\n  gravimorphism up 0.5\n}\n");
    const float down[3] = {0, -1, 0};
    assert_true(phyl_gravimorphism(&P, flat, upward) > phyl_gravimorphism(&P, flat, down));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(bh_conserves_at_every_fork),
        cmocka_unit_test(lambda_raises_apical_dominance),
        cmocka_unit_test(no_segment_enters_an_obstacle),
        cmocka_unit_test(malformed_obstacle_is_reported),
        cmocka_unit_test(shedding_by_light_ratio),
        cmocka_unit_test(bare_trunk_clears_low_branches),
        cmocka_unit_test(pipe_model_at_every_fork),
        cmocka_unit_test(neighbours_grow_apart),
        cmocka_unit_test(lsystem_plants_cast_shadow),
        cmocka_unit_test(reruns_and_threads_agree),
        cmocka_unit_test(directive_errors),
        cmocka_unit_test(scene_errors),
        cmocka_unit_test(directives_checked_by_the_hook),
        cmocka_unit_test(phyllotaxis_directions),
        cmocka_unit_test(gravimorphism_prefers),
    };
    return cmocka_run_group_tests(tests, setup_dir, teardown_dir);
}
