/* The 3D turtle: ABOP curves that must come out exact, skeleton structure (nodes, axes,
 * orders, roots), frames, tropism, cuts, polygons, organs, materials, and odd input. */
#include <math.h>

#include "lsys/modstr.h"
#include "sylva/skeleton.h"
#include "turtle/turtle.h"
#include "unit.h"

typedef struct Drawn {
    SylProgram *p;
    SylString *s; /* the string the turtle read */
    SylSkeleton *sk;
    char *diag;
} Drawn;

/* Compile, derive n steps (n < 0: the model's), interpret and draw. */
static Drawn draw_model(const char *text, int n) {
    Drawn d = {0};
    UnitRun r = unit_run(text, (SylDeriveOptions){.steps = n, .threads = 1});
    if (r.status != SYL_OK) fail_msg("status %d:\n%s", r.status, r.diag);
    SylDeriveOptions opt = {.steps = -1};
    if (syl_interpret(r.p, r.s, &opt, &d.s) != SYL_OK) fail_msg("interpret failed");
    size_t len = 0;
    FILE *mem = open_memstream(&d.diag, &len);
    SylTurtleOptions topt = {.diag = mem};
    int st = syl_turtle_draw(r.p, d.s, &topt, &d.sk);
    fclose(mem);
    if (st != SYL_OK || !d.sk) fail_msg("turtle status %d:\n%s", st, d.diag);
    d.p = r.p;
    r.p = NULL;
    unit_run_free(&r);
    return d;
}

/* Draw an axiom (no rules) with settings. */
static Drawn draw_axiom(const char *settings, const char *axiom) {
    char text[4096];
    snprintf(text, sizeof text, "lsystem T {\n%s\n  axiom %s\n}\n", settings, axiom);
    return draw_model(text, 0);
}

static void drawn_free(Drawn *d) {
    syl_skeleton_free(d->sk);
    syl_string_free(d->s);
    syl_program_free(d->p);
    free(d->diag);
}

static size_t count_symbol(const Drawn *d, const char *name) {
    int sym = syl_program_symbol_find(d->p, name);
    size_t n = 0;
    for (size_t i = 0; sym >= 0 && i < syl_string_length(d->s); i++)
        n += syl_string_module(d->s, i, NULL, NULL) == sym;
    return n;
}

static size_t count_kind(const SylSkeleton *sk, int kind) {
    size_t n = 0;
    for (size_t i = 0; i < sk->nnodes; i++) n += sk->nodes[i].kind == kind;
    return n;
}

#define assert_vec(v, x, y, z, eps)      \
    do {                                 \
        assert_near((v)[0], (x), (eps)); \
        assert_near((v)[1], (y), (eps)); \
        assert_near((v)[2], (z), (eps)); \
    } while (0)

static char *read_example(const char *name) {
    char path[256];
    snprintf(path, sizeof path, "examples/abop/%s", name);
    size_t len;
    char *raw = syl_read_file(path, &len);
    if (!raw) fail_msg("cannot read %s (run the tests from the top directory)", path);
    char *text = malloc(len + 1); /* the reader does not end it with a 0 */
    memcpy(text, raw, len);
    text[len] = 0;
    free(raw);
    return text;
}

/* ABOP Fig. 1.15: the 3D Hilbert curve visits all 8^n points of a lattice cube, one unit apart. */
static void hilbert3d_visits_the_lattice(void **state) {
    char *text = read_example("fig1_15_hilbert3d.syl");
    for (int n = 1; n <= 3; n++) {
        Drawn d = draw_model(text, n);
        size_t want = (size_t)1 << (3 * n), side = (size_t)1 << n;
        assert_int_equal(d.sk->nnodes, want);
        assert_int_equal(count_kind(d.sk, SYL_KIND_ROOT), 1);
        int lo[3] = {1 << 20, 1 << 20, 1 << 20}, hi[3] = {-(1 << 20), -(1 << 20), -(1 << 20)};
        int(*pts)[3] = calloc(want, sizeof *pts);
        for (size_t i = 0; i < want; i++) {
            const SylNode *nd = &d.sk->nodes[i];
            for (int k = 0; k < 3; k++) {
                pts[i][k] = (int)lround(nd->pos[k]);
                assert_near(nd->pos[k], pts[i][k], 1e-5);
                if (pts[i][k] < lo[k]) lo[k] = pts[i][k];
                if (pts[i][k] > hi[k]) hi[k] = pts[i][k];
            }
            if (i) {
                assert_int_equal(nd->parent, (int)i - 1);
                int dist = abs(pts[i][0] - pts[i - 1][0]) + abs(pts[i][1] - pts[i - 1][1]) +
                           abs(pts[i][2] - pts[i - 1][2]);
                assert_int_equal(dist, 1);
            }
        }
        for (int k = 0; k < 3; k++) assert_int_equal(hi[k] - lo[k] + 1, side);
        /* distinct: mark each lattice cell */
        unsigned char *seen = calloc(want, 1);
        for (size_t i = 0; i < want; i++) {
            size_t cell = ((size_t)(pts[i][0] - lo[0]) * side + (size_t)(pts[i][1] - lo[1])) * side +
                          (size_t)(pts[i][2] - lo[2]);
            if (seen[cell]) fail_msg("n=%d: point %zu visited twice", n, i);
            seen[cell] = 1;
        }
        free(seen);
        free(pts);
        drawn_free(&d);
    }
    free(text);
}

static double drawn_length(const SylSkeleton *sk) {
    double len = 0;
    for (size_t i = 0; i < sk->nnodes; i++) {
        const SylNode *n = &sk->nodes[i];
        if (n->parent < 0) continue;
        const float *a = sk->nodes[n->parent].pos;
        len += sqrt(pow(n->pos[0] - a[0], 2) + pow(n->pos[1] - a[1], 2) + pow(n->pos[2] - a[2], 2));
    }
    return len;
}

/* The quadratic Koch curve F -> F+F-F-F+F: 25 unit segments for n = 2, ending 9 ahead, and
 * reaching 4 to the left (+ turns toward L = -X). */
static void koch_quadratic_length_and_end(void **state) {
    Drawn d = draw_model("lsystem K {\n  angle 90\n  axiom F\n  F -> F+F-F-F+F\n}\n", 2);
    assert_int_equal(d.sk->nnodes, 26);
    assert_near(drawn_length(d.sk), 25, 0);
    assert_vec(d.sk->nodes[25].pos, 0, 9, 0, 0);
    float lo[3], hi[3];
    syl_skeleton_bounds(d.sk, lo, hi);
    assert_near(lo[0], -4 - 0.05, 1e-6); /* bounds include the radius */
    assert_near(hi[0], 0.05, 1e-6);
    drawn_free(&d);
}

/* ABOP Fig. 1.9a: a closed Koch island, 4 * 8^2 segments, back at the start. */
static void koch_island_is_closed(void **state) {
    char *text = read_example("fig1_09a_koch.syl");
    Drawn d = draw_model(text, 2);
    assert_int_equal(d.sk->nnodes, 4 * 64 + 1);
    assert_near(drawn_length(d.sk), 256, 0);
    assert_vec(d.sk->nodes[256].pos, 0, 0, 0, 0);
    drawn_free(&d);
    free(text);
}

/* The classic Koch curve at 60 degrees: 16 segments, end point 9 ahead. */
static void koch_60_degrees(void **state) {
    Drawn d = draw_model("lsystem K {\n  angle 60\n  axiom F\n  F -> F+F--F+F\n}\n", 2);
    assert_int_equal(d.sk->nnodes, 17);
    assert_near(drawn_length(d.sk), 16, 1e-4);
    assert_vec(d.sk->nodes[16].pos, 0, 9, 0, 1e-5);
    drawn_free(&d);
}

/* ABOP Fig. 1.24a, n = 3: one node per F plus the root, every frame orthonormal. */
static void bracketed_plant_node_count(void **state) {
    char *text = read_example("fig1_24a_plant.syl");
    Drawn d = draw_model(text, 3);
    size_t nf = count_symbol(&d, "F");
    assert_int_equal(nf, 125);
    assert_int_equal(d.sk->nnodes, nf + 1);
    assert_int_equal(count_kind(d.sk, SYL_KIND_ROOT), 1);
    assert_int_equal(d.sk->nodes[0].kind, SYL_KIND_ROOT);
    assert_int_equal(d.sk->nodes[0].parent, -1);
    for (size_t i = 1; i < d.sk->nnodes; i++) {
        const SylNode *n = &d.sk->nodes[i];
        assert_true(n->parent >= 0 && (size_t)n->parent < i);
        assert_int_equal(n->kind, SYL_KIND_INTERNODE);
        /* a segment is one step long, along its heading */
        const float *a = d.sk->nodes[n->parent].pos;
        for (int k = 0; k < 3; k++) assert_near(n->pos[k] - a[k], n->h[k], 1e-5);
        assert_near(n->radius, 0.6, 1e-6); /* half the model's `width 1.2` */
    }
    drawn_free(&d);
    free(text);
}

static void frame_is_orthonormal(const SylNode *n) {
    const float *v[3] = {n->h, n->l, n->u};
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            double dot = v[a][0] * v[b][0] + v[a][1] * v[b][1] + v[a][2] * v[b][2];
            assert_near(dot, a == b ? 1 : 0, 1e-5);
        }
    /* H x L = U */
    assert_near(n->h[1] * n->l[2] - n->h[2] * n->l[1], n->u[0], 1e-5);
    assert_near(n->h[2] * n->l[0] - n->h[0] * n->l[2], n->u[1], 1e-5);
    assert_near(n->h[0] * n->l[1] - n->h[1] * n->l[0], n->u[2], 1e-5);
}

/* Odd angles, every rotation, $, tropism and @R: the frame stays orthonormal and right-handed. */
static void frames_orthonormal_everywhere(void **state) {
    Drawn d = draw_model("lsystem B {\n  angle 22.5\n  tropism 0.3, -1, 0.2, 0.15\n  axiom A\n"
                         "  A -> [&FL!A]/////'[&FL!A]///////'[&FL!A]\n"
                         "  F -> S/////F\n  S -> F L\n  L -> ['''^^{-f+f+f-|-f+f+f}]\n"
                         "  interpret {\n    L -> \\(13.7)+(33.3)&(71)$F@R(1, 2, 3)F@R(0, 0, 1, 1, 0, 0)F|F~leaf\n  }\n}\n",
                         5);
    assert_true(d.sk->nnodes > 1000);
    for (size_t i = 0; i < d.sk->nnodes; i++) frame_is_orthonormal(&d.sk->nodes[i]);
    for (size_t i = 0; i < d.sk->norgans; i++) {
        const SylOrgan *o = &d.sk->organs[i];
        SylNode n = {0};
        memcpy(n.h, o->h, sizeof n.h);
        memcpy(n.l, o->l, sizeof n.l);
        memcpy(n.u, o->u, sizeof n.u);
        frame_is_orthonormal(&n);
    }
    drawn_free(&d);
}

/* The turning symbols, each checked on the start frame H = +Y, L = -X, U = +Z. */
static void rotations_follow_the_conventions(void **state) {
    static const struct {
        const char *axiom;
        float x, y, z;
    } cases[] = {
        {"+(90)F", -1, 0, 0},  /* left: toward L */
        {"-(90)F", 1, 0, 0},   /* right */
        {"&(90)F", 0, 0, -1},  /* pitch down: toward -U */
        {"^(90)F", 0, 0, 1},   /* pitch up */
        {"&(90)\\(90)+(90)F", 0, -1, 0}, /* after &: L = -X, U = +Y; roll left: L = -Y */
        {"&(90)/(90)+(90)F", 0, 1, 0},
        {"|F", 0, -1, 0},
        {"@R(0, 0, 2)F", 0, 0, 1},
        {"@R(0, -1, 0)F", 0, -1, 0},
        {"@R(0, 0, 0)F", 0, 1, 0},  /* no direction: ignored */
        {"@M(1, 2, 3)F", 1, 3, 3},
        {"F(2)@D(3)F(2)", 0, 8, 0},
    };
    for (size_t c = 0; c < sizeof cases / sizeof *cases; c++) {
        Drawn d = draw_axiom("", cases[c].axiom);
        const SylNode *n = &d.sk->nodes[d.sk->nnodes - 1];
        if (fabsf(n->pos[0] - cases[c].x) > 1e-6f || fabsf(n->pos[1] - cases[c].y) > 1e-6f ||
            fabsf(n->pos[2] - cases[c].z) > 1e-6f)
            fail_msg("%s ends at %g %g %g, not %g %g %g", cases[c].axiom, n->pos[0], n->pos[1], n->pos[2],
                     cases[c].x, cases[c].y, cases[c].z);
        frame_is_orthonormal(n);
        drawn_free(&d);
    }
    /* after &(90): H = -Z, L = -X, U = +Y; \ turns L toward -U, / toward U */
    Drawn d = draw_axiom("", "&(90)\\(90)F");
    assert_vec(d.sk->nodes[1].l, 0, -1, 0, 1e-6);
    assert_vec(d.sk->nodes[1].u, -1, 0, 0, 1e-6);
    drawn_free(&d);
    d = draw_axiom("", "&(90)/(90)F");
    assert_vec(d.sk->nodes[1].l, 0, 1, 0, 1e-6);
    drawn_free(&d);
}

/* $ and @v roll so that L is horizontal, U on the upper side. */
static void level_makes_l_horizontal(void **state) {
    const char *axioms[] = {"&(30)/(40)+(10)$F", "&(30)/(40)+(10)@vF", "+(80)\\(170)$F"};
    for (int i = 0; i < 3; i++) {
        Drawn d = draw_axiom("", axioms[i]);
        const SylNode *n = &d.sk->nodes[1];
        assert_near(n->l[1], 0, 1e-6);
        assert_true(n->u[1] > 0);
        frame_is_orthonormal(n);
        drawn_free(&d);
    }
}

/* Axes and orders on a small string, checked by hand. */
static void axes_and_orders(void **state) {
    Drawn d = draw_axiom("", "F[+F]F[-F[+F]F]F");
    static const struct {
        int parent, axis, order;
    } want[] = {{-1, 0, 0}, {0, 0, 0}, {1, 1, 1}, {1, 0, 0}, {3, 2, 1}, {4, 3, 2}, {4, 2, 1}, {3, 0, 0}};
    assert_int_equal(d.sk->nnodes, 8);
    for (int i = 0; i < 8; i++) {
        const SylNode *n = &d.sk->nodes[i];
        if (n->parent != want[i].parent || n->axis != want[i].axis || n->order != want[i].order)
            fail_msg("node %d: parent %d axis %d order %u, expected %d %d %d", i, n->parent, n->axis, n->order,
                     want[i].parent, want[i].axis, want[i].order);
        static const uint32_t module[] = {0, 0, 3, 5, 8, 11, 13, 15}; /* the root: the first F */
        assert_int_equal(n->module, module[i]);
    }
    drawn_free(&d);
}

/* f moves without drawing: the next segment starts from a new root, shared by the branches
 * that start there. */
static void moves_start_new_roots(void **state) {
    Drawn d = draw_axiom("", "FfF");
    assert_int_equal(d.sk->nnodes, 4);
    assert_int_equal(d.sk->nodes[2].kind, SYL_KIND_ROOT);
    assert_int_equal(d.sk->nodes[2].parent, -1);
    assert_vec(d.sk->nodes[2].pos, 0, 2, 0, 0);
    assert_int_equal(d.sk->nodes[3].parent, 2);
    assert_vec(d.sk->nodes[3].pos, 0, 3, 0, 0);
    drawn_free(&d);

    d = draw_axiom("", "f[+F][-F]F[f[F]F]");
    /* root at (0,1); three segments from it; then a root at (0,3) with two segments */
    assert_int_equal(d.sk->nnodes, 7);
    assert_int_equal(count_kind(d.sk, SYL_KIND_ROOT), 2);
    assert_int_equal(d.sk->nodes[1].parent, 0);
    assert_int_equal(d.sk->nodes[2].parent, 0);
    assert_int_equal(d.sk->nodes[3].parent, 0);
    assert_int_equal(d.sk->nodes[3].axis, d.sk->nodes[0].axis); /* the main axis goes on */
    assert_int_equal(d.sk->nodes[5].parent, 4);
    assert_int_equal(d.sk->nodes[6].parent, 4);
    drawn_free(&d);

    /* no segment: no node */
    d = draw_axiom("", "f+g");
    assert_int_equal(d.sk->nnodes, 0);
    drawn_free(&d);
}

/* % cuts the rest of its branch; on the main axis, the rest of the string. */
static void cut_skips_the_branch(void **state) {
    Drawn d = draw_axiom("", "F[+F%F[F]+F]F[%F]F%FF");
    assert_int_equal(d.sk->nnodes, 5); /* root, F, +F, F, F */
    assert_vec(d.sk->nodes[4].pos, 0, 3, 0, 0);
    drawn_free(&d);
}

/* { . } polygons: . records, f and F add their end points, G and g do not; nested polygons. */
static void polygons(void **state) {
    Drawn d = draw_axiom("  angle 90", "F[{-f+f+f-|-f+f+f}]F");
    assert_int_equal(d.sk->npolys, 1);
    assert_int_equal(d.sk->polys[0].count, 6);
    assert_int_equal(d.sk->polys[0].node, 1);
    assert_int_equal(d.sk->nnodes, 3); /* F inside a polygon does not draw */
    assert_vec(d.sk->poly_verts[0], 1, 1, 0, 0);
    drawn_free(&d);

    d = draw_axiom("", "{.G.[{.G.G.}]G.G.}{..}");
    assert_int_equal(d.sk->nnodes, 0);
    assert_int_equal(d.sk->npolys, 2); /* the inner one closes first; two vertices are no polygon */
    assert_int_equal(d.sk->polys[0].count, 3);
    assert_int_equal(d.sk->polys[1].count, 4);
    for (int i = 0; i < 3; i++) assert_vec(d.sk->poly_verts[d.sk->polys[0].first + i], 0, 1 + i, 0, 0);
    for (int i = 0; i < 4; i++) assert_vec(d.sk->poly_verts[d.sk->polys[1].first + i], 0, i, 0, 0);
    assert_int_equal(d.sk->polys[0].node, -1);
    drawn_free(&d);

    /* unbalanced braces do no harm */
    d = draw_axiom("", "}.F{.F.F");
    assert_int_equal(d.sk->npolys, 0);
    drawn_free(&d);
}

static void organs(void **state) {
    Drawn d = draw_axiom("  step 2\n  width 0.4", "F~leaf(3)[&(90)@O(0.5)]~needle~petal@O'~leaf;(7)~flower~unknown");
    assert_int_equal(d.sk->norgans, 7);
    static const struct {
        int kind;
        float size;
        int material;
    } want[] = {{SYL_KIND_LEAF, 3, 1},   {SYL_KIND_SPHERE, 0.5, 0}, {SYL_KIND_NEEDLE, 2, 1}, {SYL_KIND_FLOWER, 2, 2},
                {SYL_KIND_SPHERE, 0.4, 0}, {SYL_KIND_LEAF, 2, 1},  {SYL_KIND_FLOWER, 2, 7}};
    for (int i = 0; i < 7; i++) {
        const SylOrgan *o = &d.sk->organs[i];
        assert_int_equal(o->kind, want[i].kind);
        assert_near(o->size, want[i].size, 1e-6);
        assert_int_equal(o->material, want[i].material);
        assert_int_equal(o->node, 1);
        assert_vec(o->pos, 0, 2, 0, 0);
    }
    assert_vec(d.sk->organs[1].h, 0, 0, -1, 1e-6); /* pitched down in its branch */
    assert_contains(d.diag, "~unknown");
    drawn_free(&d);
}

/* ' ; , set and step the material; colours become the skeleton's materials. */
static void materials(void **state) {
    Drawn d = draw_axiom("  colour 1, 1, 0, 0\n  colour 5, 0, 0, 1\n  colour 0, 0.5, 0.5, 0.5",
                         "F'F'(5)F;F,F,(0)F,F;(300)F'(-2)F");
    static const int want[] = {0, 0, 1, 5, 6, 5, 0, 0, 255, 0};
    assert_int_equal(d.sk->nnodes, 10);
    for (int i = 0; i < 10; i++) assert_int_equal(d.sk->nodes[i].material, want[i]);
    assert_vec(d.sk->materials[1].rgb, 1, 0, 0, 0);
    assert_int_equal(d.sk->materials[1].kind, SYL_MATERIAL_LEAF);
    assert_vec(d.sk->materials[5].rgb, 0, 0, 1, 0);
    assert_int_equal(d.sk->materials[5].kind, SYL_MATERIAL_PLAIN);
    assert_vec(d.sk->materials[0].rgb, 0.5, 0.5, 0.5, 1e-7);
    assert_int_equal(d.sk->materials[0].kind, SYL_MATERIAL_BARK);
    assert_int_equal(d.sk->materials[2].kind, SYL_MATERIAL_FLOWER); /* the default palette */
    assert_int_equal(d.sk->nmaterials, 256);
    drawn_free(&d);
}

/* ! sets or scales the diameter; radius is half of it; @D scales lengths and widths. */
static void widths_and_scale(void **state) {
    Drawn d = draw_axiom("  width 1\n  widthfactor 0.5", "F!F!(3)F!(-1)F[!F]F@D(2)!(1)F");
    static const float r[] = {0.5, 0.5, 0.25, 1.5, 0, 0, 0, 1};
    assert_int_equal(d.sk->nnodes, 8);
    for (int i = 0; i < 8; i++) assert_near(d.sk->nodes[i].radius, r[i], 1e-7);
    assert_vec(d.sk->nodes[7].pos, 0, 7, 0, 0);
    drawn_free(&d);
}

/* Tropism bends the heading toward T at every F: with T down, the end is lower. */
static void tropism_bends_toward_t(void **state) {
    Drawn straight = draw_axiom("", "+(60)FFFFFF");
    Drawn bent = draw_axiom("  tropism 0, -1, 0, 0.2", "+(60)FFFFFF");
    Drawn module = draw_axiom("", "@Tp(0, -3, 0, 0.2)+(60)FFFFFF");
    Drawn up = draw_axiom("", "@Tp(0, 1, 0, 0.2)+(60)FFFFFF");
    const float *a = straight.sk->nodes[6].pos, *b = bent.sk->nodes[6].pos, *c = module.sk->nodes[6].pos,
                *u = up.sk->nodes[6].pos;
    assert_near(a[1], 3, 1e-5);
    assert_true(b[1] < a[1] - 0.5);
    assert_vec(c, b[0], b[1], b[2], 1e-6); /* @Tp normalises T like the setting */
    assert_true(u[1] > a[1] + 0.5);
    assert_near(b[2], 0, 1e-6); /* stays in the plane of H and T */
    /* the first segment is straight: bending follows each F */
    const float *s1 = straight.sk->nodes[1].pos;
    assert_vec(bent.sk->nodes[1].pos, s1[0], s1[1], s1[2], 1e-6);
    /* each bend: alpha = e |H x T| */
    double h0 = atan2(-straight.sk->nodes[1].h[0], straight.sk->nodes[1].h[1]); /* from +Y toward -X */
    double h1 = atan2(-bent.sk->nodes[2].h[0], bent.sk->nodes[2].h[1]);
    assert_near(h1 - h0, 0.2 * sin(60 * M_PI / 180), 1e-5);
    /* straight down, T straight down: nothing to bend */
    Drawn down = draw_axiom("  tropism 0, -1, 0, 0.5", "|FF");
    assert_vec(down.sk->nodes[2].pos, 0, -2, 0, 1e-6);
    /* @Ts changes only the elasticity; @Tp with elasticity 0 turns it off */
    Drawn off = draw_axiom("  tropism 0, -1, 0, 0.2", "@Ts(0)+(60)FFFFFF");
    assert_vec(off.sk->nodes[6].pos, a[0], a[1], a[2], 1e-5);
    drawn_free(&straight);
    drawn_free(&bent);
    drawn_free(&module);
    drawn_free(&up);
    drawn_free(&down);
    drawn_free(&off);
}

/* @Gc ... @Ge mark the nodes drawn between them as smooth. */
static void generalized_cylinders(void **state) {
    Drawn d = draw_axiom("", "F@GcF[F@Ge]F@GeF");
    static const int want[] = {0, 0, 1, 1, 1, 0};
    assert_int_equal(d.sk->nnodes, 6);
    for (int i = 0; i < 6; i++) assert_int_equal(d.sk->nodes[i].flags & SYL_NODE_SMOOTH ? 1 : 0, want[i]);
    drawn_free(&d);
}

/* The CSV and JSON writers on a turtle skeleton. */
static void export_csv(void **state) {
    Drawn d = draw_axiom("  angle 90", "F[+F~leaf]");
    char *out = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&out, &len);
    assert_int_equal(syl_skeleton_write_csv(d.sk, mem), SYL_OK);
    fclose(mem);
    assert_string_equal(out, "id,parent,x,y,z,radius,order,kind\n"
                             "0,-1,0,0,0,0.05,0,root\n"
                             "1,0,0,1,0,0.05,0,internode\n"
                             "2,1,-1,1,0,0.05,1,internode\n"
                             "3,2,-1,1,0,0.5,1,leaf\n");
    free(out);
    drawn_free(&d);
}

/* A string made by hand: parameters no model would produce, brackets that do not balance. */
static SylString *raw_string(SylProgram *p, const char *const *names, const int *arity, const double *par, int n) {
    SylString *s = calloc(1, sizeof *s);
    size_t np = 0;
    for (int i = 0; i < n; i++) np += (size_t)arity[i];
    s->code = calloc((size_t)n + 1, sizeof *s->code);
    s->par = calloc(np + 1, sizeof *s->par);
    s->n = s->cap = (size_t)n;
    s->np = s->pcap = np;
    for (int i = 0; i < n; i++) {
        int sym = syl_program_symbol_find(p, names[i]);
        if (sym < 0) fail_msg("no symbol %s", names[i]);
        s->code[i] = CODE(sym, arity[i]);
    }
    memcpy(s->par, par, np * sizeof *par);
    return s;
}

static void odd_input_is_harmless(void **state) {
    SylProgram *p = unit_compile("lsystem T {\n  axiom F [ ] ! ' @R @M @D @O @Tp ~leaf + % { . } $ ?P @Ts f g G & ^ "
                                 "\\ / | @v ; , @Gc @Ge ~petal ~needle ~x\n}\n",
                                 NULL, NULL);
    assert_non_null(p);
    const char *names[] = {"]", "]", "F", "!", "F", "+", "F", "F", "@R", "F", "@R", "@M", "F", "@D", "F", "@O",
                           "@Tp", "F", "~leaf", "'", "[", "%", "F", "@Tp", "F", "$", "F", "?P", "!", "F", "@Ts", "F"};
    const int arity[] = {0, 0, 1, 1, 1, 1, 1, 1, 3, 1, 6, 3, 1, 1, 1, 1, 4, 1, 1, 1, 0, 0, 1, 4, 1, 0, 1, 3, 1, 1, 1, 1};
    static const double odd[] = {NAN, -5, INFINITY, 1e300, 1, -1e300, 0, 0, 0, 1e40, -3, -INFINITY, 1e-300, 90};
    double par[64];
    for (int i = 0; i < 64; i++) par[i] = odd[i % (int)(sizeof odd / sizeof *odd)];
    int n = (int)(sizeof names / sizeof *names);
    SylString *s = raw_string(p, names, arity, par, n);
    char *diag = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&diag, &len);
    SylSkeleton *sk = NULL;
    assert_int_equal(syl_turtle_draw(p, s, &(SylTurtleOptions){.diag = mem}, &sk), SYL_OK);
    fclose(mem);
    assert_non_null(sk);
    assert_contains(diag, "not a finite number");
    for (size_t i = 0; i < sk->nnodes; i++) {
        assert_true(sk->nodes[i].radius >= 0);
        assert_false(isnan(sk->nodes[i].pos[0]) || isnan(sk->nodes[i].h[0]));
    }
    syl_skeleton_free(sk);
    free(diag);
    /* random strings of turtle symbols with random parameters */
    static const char *const all[] = {"F", "[", "]", "!", "'", "@R", "@M", "@D", "@O", "@Tp", "~leaf", "+", "%",
                                      "{", ".", "}", "$", "?P", "@Ts", "f", "g", "G", "&", "^", "\\", "/", "|",
                                      "@v", ";", ",", "@Gc", "@Ge", "~petal", "~needle", "~x"};
    const int nall = (int)(sizeof all / sizeof *all);
    uint64_t x = 12345;
    for (int round = 0; round < 300; round++) {
        int m = 1 + round % 60;
        const char **nm = malloc(sizeof *nm * (size_t)m);
        int *ar = malloc(sizeof *ar * (size_t)m);
        double *pr = malloc(sizeof *pr * (size_t)m * 6);
        int np = 0;
        for (int i = 0; i < m; i++) {
            x = x * 6364136223846793005ULL + 1442695040888963407ULL;
            nm[i] = all[(x >> 33) % (uint64_t)nall];
            ar[i] = (nm[i][0] == '[' || nm[i][0] == ']' || nm[i][0] == '%' || nm[i][0] == '$' || nm[i][0] == '{' ||
                     nm[i][0] == '.' || nm[i][0] == '}')
                        ? 0
                        : (int)((x >> 20) % 7);
            for (int k = 0; k < ar[i]; k++) {
                x = x * 6364136223846793005ULL + 1442695040888963407ULL;
                static const double pick[] = {0, 1, -1, 0.5, 90, -1e300, 1e300, 1e-300, 1e9, 3};
                pr[np++] = pick[(x >> 40) % 10];
            }
        }
        SylString *r = raw_string(p, nm, ar, pr, m);
        sk = NULL;
        assert_int_equal(syl_turtle_draw(p, r, NULL, &sk), SYL_OK);
        syl_skeleton_free(sk);
        syl_string_free(r);
        free(nm);
        free(ar);
        free(pr);
    }
    syl_string_free(s);
    syl_program_free(p);
}

/* Query modules take the turtle's position and frame where they stand. */
static void query_modules_are_filled(void **state) {
    UnitRun r = unit_run("lsystem Q {\n  angle 90\n  axiom F?P(0, 0, 0)+F(2)?H(0, 0, 0)?L(9, 9, 9)?U(0, 0, 0)[?P(7)]\n}\n",
                         (SylDeriveOptions){.steps = 0});
    assert_int_equal(r.status, SYL_OK);
    assert_int_equal(syl_turtle_query(r.p, r.s, NULL), SYL_OK);
    char *got = unit_string(&r);
    assert_string_equal(got, "F?P(0,1,0)+F(2)?H(-1,0,0)?L(0,-1,0)?U(0,0,1)[?P(-2)]");
    free(got);
    unit_run_free(&r);
}

/* A string without any parameter has no parameter array (NULL): the turtle and its query
 * pass read it without offsetting that pointer (clang's -fsanitize=pointer-overflow, part
 * of -fsanitize=undefined, stops on "applying zero offset to null pointer"). The skeleton
 * is still the one the string draws: F+F at 90 degrees, a root and two segments. */
static void string_without_parameters(void **state) {
    Drawn d = draw_axiom("  angle 90", "F+F[-F]?P?H!");
    assert_null(d.s->par);
    assert_int_equal(d.sk->nnodes, 4);
    const SylNode *last = &d.sk->nodes[d.sk->nnodes - 1];
    assert_float_equal(last->pos[0], -1, 1e-6);
    assert_float_equal(last->pos[1], 2, 1e-6);
    drawn_free(&d);
    /* the query pass, over queries that have nowhere to write */
    d = draw_axiom("", "F?P?E[?P]+F");
    assert_null(d.s->par);
    assert_int_equal(syl_turtle_query(d.p, d.s, NULL), SYL_OK);
    assert_int_equal(syl_string_length(d.s), 8);
    drawn_free(&d);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(hilbert3d_visits_the_lattice),
        cmocka_unit_test(koch_quadratic_length_and_end),
        cmocka_unit_test(koch_island_is_closed),
        cmocka_unit_test(koch_60_degrees),
        cmocka_unit_test(bracketed_plant_node_count),
        cmocka_unit_test(frames_orthonormal_everywhere),
        cmocka_unit_test(rotations_follow_the_conventions),
        cmocka_unit_test(level_makes_l_horizontal),
        cmocka_unit_test(axes_and_orders),
        cmocka_unit_test(moves_start_new_roots),
        cmocka_unit_test(cut_skips_the_branch),
        cmocka_unit_test(polygons),
        cmocka_unit_test(organs),
        cmocka_unit_test(materials),
        cmocka_unit_test(widths_and_scale),
        cmocka_unit_test(tropism_bends_toward_t),
        cmocka_unit_test(generalized_cylinders),
        cmocka_unit_test(export_csv),
        cmocka_unit_test(odd_input_is_harmless),
        cmocka_unit_test(query_modules_are_filled),
        cmocka_unit_test(string_without_parameters),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
