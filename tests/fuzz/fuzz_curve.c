/* libFuzzer harness: the curvetree's trunk curve reader (an OBJ of `v` and `l` lines, as Blender
 * exports a curve: src/curvetree/curve.c) on arbitrary bytes; a curve it accepts must be one
 * open chain of finite points with increasing arc length from its lower end, and the tree is
 * grown along it inside a sphere around it (the generator on curves no example has: loops
 * back, zero-length pieces, huge or tiny scales). */
#include <math.h>

#include "curvetree/curvetree.h"
#include "fuzz.h"

typedef struct Ball {
    double c[3], r2;
} Ball;

static bool in_ball(void *user, const double p[3]) {
    const Ball *b = user;
    double d[3] = {p[0] - b->c[0], p[1] - b->c[1], p[2] - b->c[2]};
    return d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < b->r2;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    FILE *diag = fuzz_diag();
    CtCurve c;
    if (ct_curve_obj("fuzz.obj", (const char *)data, size, &c, diag) != SYL_OK) return 0;
    if (c.n < 2 || c.nctrl != c.n || !(c.length > 0) || c.s[0] != 0 || c.s[c.n - 1] != c.length) abort();
    for (int i = 0; i < c.n; i++) {
        if (i && !(c.s[i] >= c.s[i - 1])) abort();
        for (int j = 0; j < 3; j++)
            if (!isfinite(c.p[i][j])) abort();
    }
    if (c.p[0][1] > c.p[c.n - 1][1]) abort(); /* from the lower end */
    Ball b = {{0, 0, 0}, 0};
    for (int i = 0; i < c.n; i++)
        for (int j = 0; j < 3; j++) b.c[j] += c.p[i][j] / c.n;
    b.r2 = c.length * c.length;
    for (int k = 0; k <= 8; k++) { /* points along it lie on it */
        double pos[3], dir[3];
        int piece = ct_curve_at(&c, c.length * k / 8, pos, dir);
        if (piece < 0 || piece >= c.n - 1 || !isfinite(pos[0] + pos[1] + pos[2])) abort();
    }
    /* the defaults, then a denser tree, grown along it */
    CtParams P = {.trunkWidth = 0.5, .trunkRes = 2, .branch1Density = size % 3, .branch2Density = 1,
                  .branch1Width = 0.6, .branch2Width = 0.6, .branchRes = 1, .branch2Len = 1, .branchAngle = 0.3,
                  .branchCurvature = 0.2, .leavesDensity = 1, .leavesSize = 1, .leafAspect = 2, .seed = 1};
    if (c.n <= 4096) {
        SylSkeleton *sk = syl_skeleton_new("fuzz");
        if (!sk) abort();
        if (ct_build(&P, &c, in_ball, &b, 2, 1, sk, NULL) != SYL_OK) abort();
        uint64_t nodes, leaves;
        ct_bounds(&P, &c, &nodes, &leaves);
        if (sk->nnodes > nodes || sk->norgans > leaves) abort(); /* the budget's count is an upper bound */
        syl_skeleton_free(sk);
    }
    ct_curve_free(&c);
    return 0;
}
