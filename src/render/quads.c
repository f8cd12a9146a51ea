/* The mesh's triangles paired into Embree quads, and a quad hit turned back into a hit of
 * the triangle it fell on. A plant is mostly quads (tube segments, leaf blades) written as
 * two triangles: half the primitives build a smaller hierarchy faster, and a ray tests both
 * halves at once. Embree splits quad (v0, v1, v2, v3) into triangles (v0, v1, v3) and
 * (v2, v3, v1), exactly the two triangles paired, so a hit is the same surface point. */
#include <stdlib.h>

#include "render/scene.h"

/* How far ahead a triangle's partner is looked for: meshoptimizer's vertex-cache order keeps
 * a quad's two halves near each other (most within a few triangles). */
enum { WINDOW = 8 };

/* A triangle's code: its index times 4 plus the rotation r that puts its first corner at
 * the quad corner the code's triangle starts with (corner k of the rotated triangle is
 * corner (k + r) % 3 of the triangle). */
static inline uint32_t code(size_t tri, int r) { return (uint32_t)tri << 2 | (uint32_t)r; }

/* Rotations ra of A and rb of B with A's edge 1 -> 2 the reverse of B's edge 1 -> 2, which is
 * Embree's diagonal v1 -> v3 seen from each half: the quad (A0, A1, B0, A2). */
static bool pair(const uint32_t *A, const uint32_t *B, int *ra, int *rb) {
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (A[(i + 2) % 3] == B[(j + 1) % 3] && A[(i + 1) % 3] == B[(j + 2) % 3] && A[i] != B[j]) {
                *ra = i, *rb = j;
                return true;
            }
    return false;
}

int render_quads(const SylMesh *m, const uint8_t *tri_mat, uint32_t (**index)[4], uint32_t (**halves)[2],
                 size_t *nquads) {
    size_t ntri = m->nidx / 3, nq = 0;
    uint32_t (*qi)[4] = malloc((ntri + 1) * sizeof *qi);
    uint32_t (*h)[2] = malloc((ntri + 1) * sizeof *h);
    uint8_t *used = calloc(ntri + 1, 1);
    if (!qi || !h || !used) {
        free(qi), free(h), free(used);
        return SYL_ELIMIT;
    }
    for (size_t i = 0; i < ntri; i++) {
        if (used[i]) continue;
        const uint32_t *A = m->idx + 3 * i;
        int ra = 0, rb = 0;
        size_t j = i + 1;
        for (; j < ntri && j <= i + WINDOW; j++)
            if (!used[j] && tri_mat[j] == tri_mat[i] && pair(A, m->idx + 3 * j, &ra, &rb)) break;
        if (j < ntri && j <= i + WINDOW) {
            const uint32_t *B = m->idx + 3 * j;
            used[j] = 1;
            qi[nq][0] = A[ra], qi[nq][1] = A[(ra + 1) % 3], qi[nq][2] = B[rb], qi[nq][3] = A[(ra + 2) % 3];
            h[nq][0] = code(i, ra), h[nq][1] = code(j, rb);
        } else { /* alone: a quad whose last corner repeats its third, as Embree allows */
            qi[nq][0] = A[0], qi[nq][1] = A[1], qi[nq][2] = A[2], qi[nq][3] = A[2];
            h[nq][0] = code(i, 0), h[nq][1] = UINT32_MAX;
        }
        nq++;
    }
    free(used);
    *index = qi, *halves = h, *nquads = nq;
    return SYL_OK;
}

void render_quad_hit(const uint32_t (*halves)[2], unsigned *prim, float *u, float *v) {
    const uint32_t *q = halves[*prim];
    float a = *u, b = *v;
    uint32_t c = q[0];
    if (q[1] != UINT32_MAX && a + b > 1) c = q[1], a = 1 - a, b = 1 - b; /* the second half */
    /* weights of the rotated triangle's corners 0, 1, 2; the triangle's corner k is the
     * rotated corner (k - r) mod 3 */
    float wt[3] = {1 - a - b, a, b};
    int r = (int)(c & 3);
    *prim = c >> 2;
    *u = wt[(4 - r) % 3], *v = wt[(5 - r) % 3];
}
