/* Terrains for the unit tests: an empty grid of nx x nz cells, and a cell's height or value. */
#ifndef SYL_TEST_TERRAIN_FIXTURES_H
#define SYL_TEST_TERRAIN_FIXTURES_H
#include "unit.h"
#include "terrain/terrain.h"

static Terrain *grid(int nx, int nz, double cell) {
    Terrain *t;
    assert_int_equal(terrain_new(nx, nz, NULL, 0, "test", diag_sink(&(SylSink){0}, stderr, NULL), &t), SYL_OK);
    t->cell = cell;
    return t;
}

#define H(t, i, k) (t)->height[(size_t)(k) * (size_t)(t)->nx + (size_t)(i)]
#define AT(g, t, i, k) (g)[(size_t)(k) * (size_t)(t)->nx + (size_t)(i)]

#endif
