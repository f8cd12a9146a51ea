/* Is a point inside a closed triangle mesh: the crossings of one ray counted by parity, as
 * obstacles_inside asks Embree, answered from a grid of the triangles projected along the
 * ray's fixed direction. A ray of one direction is all the test needs: its triangles are
 * those whose shadow on the plane across the ray holds the point, so a 2D grid of those
 * shadows finds them without a BVH, and without loading Embree (its start-up is most of a
 * small tree's time: docs/curvetree.md). */
#ifndef SYL_ENV_PARITY_H
#define SYL_ENV_PARITY_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct ParityGrid {
    double (*p)[2];     /* each vertex projected on the plane across the ray */
    double (*v)[3];     /* each vertex */
    const uint32_t *tri;/* the caller's, 3 per triangle */
    struct ParityTri {  /* per triangle, computed once: its normal, n . dir, and its shadow's turn */
        double n[3], den;
        int8_t turn;    /* 1 or -1; 0: seen edge-on, never crossed */
    } *t;
    uint32_t *start;    /* cell c's triangles: idx[start[c] .. start[c + 1]) */
    uint32_t *idx;
    int g;              /* cells per side */
    double lo[2], inv;  /* the grid's corner and cells per unit */
    double u[3], w[3];  /* the plane across the ray */
} ParityGrid;

/* Build the grid over v (3 floats a vertex) and tri (kept, not copied). false: out of memory. */
bool parity_build(ParityGrid *pg, const float *v, size_t nv, const uint32_t *tri, size_t nt);
/* Odd crossings of the ray from p along obstacles_inside's direction. */
bool parity_inside(const ParityGrid *pg, const float p[3]);
void parity_free(ParityGrid *pg);

#endif
