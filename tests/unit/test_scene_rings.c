/* A scene draws each plant with its own ring rule (issue 28: per-plant surface properties travel
 * with each plant): a Pafčo tree at DETAIL 1 (Table T.1 of the thesis: 6 points around the
 * trunk, 5, 3, 3 around generations 1 to 3) and a curve tree (4 x trunkRes around its trunk,
 * 4 x branchRes around its branches, as the Blender plug-in draws them), planted in one scene
 * and meshed once without --sides: every tube's ring, counted from the mesh's vertices by the
 * node each names, is its own plant's rule for its branch order. */
#include <sys/stat.h>
#include <unistd.h>

#include "unit.h"

#include "sylva/grow.h"
#include "sylva/mesh.h"

static char dir[64];

static void write_file(const char *name, const char *text) { unit_write_file(dir, name, text); }

static const char *const files[] = {"box.obj", "tree.cfg", "scene.syl"};

static int setup(void **state) {
    (void)state;
    snprintf(dir, sizeof dir, "/tmp/sylva-rings-XXXXXX");
    assert_non_null(mkdtemp(dir));
    write_file("box.obj", "v -3 2 -3\nv 3 2 -3\nv 3 2 3\nv -3 2 3\nv -3 9 -3\nv 3 9 -3\nv 3 9 3\nv -3 9 3\n"
                          "f 1 2 3\nf 1 3 4\nf 5 7 6\nf 5 8 7\nf 1 5 6\nf 1 6 2\nf 2 6 7\nf 2 7 3\nf 3 7 8\nf 3 8 4\n"
                          "f 4 8 5\nf 4 5 1\n");
    write_file("tree.cfg", "VYSKA_STROMU=9\nV2GENER=true\nV3GENER=true\nV2G_MAX=1.6\nV3G_MAX=0.6\nSEG_VET=5\n"
                           "SPH_LISTY=false\nDETAIL=1\n");
    write_file("scene.syl", "curvetree T {\n  trunk polyline (0,0,0) (0,8,0)\n  envelope \"box.obj\"\n"
                            "  trunkRes 3\n  branchRes 2\n}\n"
                            "scene {\n  plant \"tree.cfg\" at (0, 0, 0)\n  plant T at (20, 0, 0)\n}\n");
    return 0;
}

static int teardown(void **state) {
    (void)state;
    unit_remove_files(dir, files, sizeof files / sizeof *files);
    return 0;
}

/* Points around a ring: part 0 the Pafčo tree (Table T.1, DETAIL 1), part 1 the curve tree. */
static int rule(int part, int order) {
    static const int t1[4] = {6, 5, 3, 3};
    if (part == 0) return t1[order < 3 ? order : 3];
    return order == 0 ? 4 * 3 : 4 * 2;
}

static void each_plant_its_own_rings(void **state) {
    (void)state;
    char path[128];
    snprintf(path, sizeof path, "%s/scene.syl", dir);
    int st;
    char *said = NULL; /* tree.cfg leaves parameters out: a warning, shown only on failure */
    size_t len = 0;
    FILE *diag = open_memstream(&said, &len);
    SylProgram *p = syl_compile(path, NULL, 0, &(SylCompileOptions){.diag = diag, .validate = syl_validate}, &st);
    SylSkeleton *sk = NULL;
    SylGrowOptions go = {.years = -1, .threads = 1, .diag = diag};
    st = p ? syl_grow_build_scene(p, &go, &sk, NULL) : st;
    fclose(diag);
    if (st) fail_msg("%s", said);
    free(said);
    assert_int_equal(sk->nparts, 2);
    /* leaves left out (instanced), no caps: a tube's vertices are its rings, all naming its last node */
    SylMeshOptions mo = {.vertex_nodes = 1, .caps = -1, .threads = 1, .leaves = SYL_LEAVES_INSTANCED};
    SylMesh *m = NULL;
    assert_int_equal(syl_mesh_build(sk, &mo, &m), SYL_OK);
    size_t n = sk->nnodes, *per = calloc(n + 1, sizeof *per), *points = calloc(n + 1, sizeof *points);
    int32_t *tail = malloc((n + 1) * sizeof *tail); /* a node's tube, by its last node so far */
    assert_true(per && points && tail);
    for (size_t v = 0; v < m->nverts; v++)
        if (m->node[v] >= 0) per[m->node[v]]++;
    /* the tubes as the mesher splits them (sylva/mesh.h: an axis from its parent's point):
     * points[last] counts a tube's points */
    for (size_t i = 0; i < n; i++) {
        int32_t q = sk->nodes[i].parent;
        bool cont = q >= 0 && sk->nodes[q].axis == sk->nodes[i].axis && tail[q] == q;
        tail[i] = (int32_t)i;
        if (cont) {
            points[i] = points[q] + 1, points[q] = 0, tail[q] = -1;
        } else {
            points[i] = 1 + (q >= 0);
        }
    }
    int seen[2][2] = {{0}}; /* [part][trunk, branch] */
    for (size_t i = 0; i < n; i++) {
        if (points[i] < 2 || !per[i]) continue; /* not a tube's last node, or nothing drawn */
        int part = sk->parts[1].first_node <= i;
        int order = sk->nodes[i].order;
        assert_int_equal(per[i] % points[i], 0);
        int ring = (int)(per[i] / points[i]) - 1; /* a ring's points and the seam's copy */
        if (ring != rule(part, order))
            fail_msg("node %zu of plant %d, order %d: %d points a ring, not %d", i, part, order, ring,
                     rule(part, order));
        seen[part][order > 0]++;
    }
    for (int k = 0; k < 2; k++) assert_true(seen[k][0] > 0 && seen[k][1] > 0); /* trunks and branches of both */
    free(per), free(points), free(tail);
    syl_mesh_free(m);
    syl_skeleton_free(sk);
    syl_program_free(p);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(each_plant_its_own_rings),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
