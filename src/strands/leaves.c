/* The leaves of a terminal branch (Zamuda 3.3.2, after Bryce 5): evenly spaced along it,
 * pointing out across it, in one of five arrangements; an odd leaf of a pair sits at the tip. */
#include <math.h>

#include "strands/strands.h"

#define PI 3.14159265358979323846
#define GOLDEN (137.50776405003785 * PI / 180) /* spiral: the golden angle between leaves */
#define BUNCH_TILT (PI / 4)                    /* bunched: out from the tip, 45 degrees forward */
#define NEEDLE_TILT (PI / 4)                   /* coniferous: 45 degrees between needle and twig */

/* One leaf at distance t (0..1) along the branch, pointing to side phi, tilted forward by tilt
 * (0: across the branch). */
static int32_t leaf(const StrandsParams *P, const StrandsFrame *f, double len, double t, double phi, double tilt,
                    int32_t node, SylSkeleton *sk) {
    SylOrgan o = {.size = (float)P->leaf_size, .node = node, .material = SYL_MATERIAL_LEAF,
                  .kind = P->leaf_type == LEAVES_CONIFEROUS ? SYL_KIND_NEEDLE : SYL_KIND_LEAF,
                  .module = (uint32_t)node};
    double c = cos(phi), s = sin(phi), ct = cos(tilt), st = sin(tilt);
    for (int i = 0; i < 3; i++) {
        double side = c * f->x[i] + s * f->z[i];
        double h = ct * side + st * f->y[i];
        double l = -st * side + ct * f->y[i]; /* the blade's width lies along the twig */
        o.pos[i] = (float)(f->pos[i] + t * len * f->y[i]);
        o.h[i] = (float)h;
        o.l[i] = (float)l;
    }
    o.u[0] = o.h[1] * o.l[2] - o.h[2] * o.l[1];
    o.u[1] = o.h[2] * o.l[0] - o.h[0] * o.l[2];
    o.u[2] = o.h[0] * o.l[1] - o.h[1] * o.l[0];
    return syl_skeleton_add_organ(sk, &o);
}

int strands_leaves(const StrandsParams *P, const StrandsFrame *f, double len, int32_t node, SylSkeleton *sk) {
    int n = strands_leaf_count(P);
    for (int i = 0; i < n; i++) {
        double t, phi = 0, tilt = 0;
        switch (P->leaf_type) {
        case LEAVES_STACKED: { /* pairs, one each side; the odd one at the tip */
            int pairs = n / 2, slots = pairs + (n & 1);
            t = (double)(i / 2 + 1) / slots;
            phi = (i & 1) * PI;
            if (i == n - 1 && (n & 1)) tilt = PI / 2; /* the odd one carries the twig on */
            break;
        }
        case LEAVES_STAGGERED: t = (double)(i + 1) / n, phi = (i & 1) * PI; break;
        case LEAVES_SPIRAL: t = (double)(i + 1) / n, phi = i * GOLDEN; break;
        case LEAVES_BUNCHED: t = 1, phi = 2 * PI * i / n, tilt = BUNCH_TILT; break;
        case LEAVES_CONIFEROUS: t = (double)(i + 1) / n, phi = (i & 1) * PI, tilt = PI / 2 - NEEDLE_TILT; break;
        default: return 0;
        }
        if (leaf(P, f, len, t, phi, tilt, node, sk) < 0) return -1;
    }
    return n;
}
