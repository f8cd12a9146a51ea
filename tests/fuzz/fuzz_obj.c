/* libFuzzer harness: the OBJ reader (obstacles, and terrain: `ground "hill.obj"`) on
 * arbitrary bytes, then what growth asks of a terrain — the obstacles' Embree scene, the
 * height under points across it, blocked segments and distances — and the OBJ DEM reader
 * (`sylva terrain hill.obj`: the mesh rasterized into a grid, src/terrain/read_obj.c), which
 * reads a path: the input goes through a memfd. */
#include <math.h>
#include <sys/mman.h>
#include <unistd.h>

#include "env/objread.h"
#include "env/obstacles.h"
#include "util/diag.h"
#include "fuzz.h"
#include "sylva/sylva.h"
#include "terrain/terrain.h"

/* Embree refuses coordinates much beyond this (issue 9 item 2b: a model far from the origin
 * aborts inside Embree; coordinate checks are being added). Until then the harness keeps
 * terrains within it, so the reader and the queries are what it tests. */
#define FAR 1e6f

/* The OBJ DEM of the input, in a grid of at most ~1 MB: every height must lie within the
 * heights of the mesh's vertices (a cell's is a ray's hit or a neighbour's, filled in). */
static void dem(const uint8_t *data, size_t size, const ObjMesh *m, FILE *diag) {
    static int fd = -1;
    static char path[64];
    if (fd < 0) {
        if ((fd = memfd_create("fuzz.obj", 0)) < 0) abort();
        snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
    }
    if (ftruncate(fd, 0) || pwrite(fd, data, size, 0) != (ssize_t)size) abort();
    float lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < m->nv; i++) lo = fminf(lo, m->v[3 * i + 1]), hi = fmaxf(hi, m->v[3 * i + 1]);
    SylTerrainOptions o = {.threads = 1, .max_memory = 1u << 20, .diag = diag};
    Terrain *t = NULL;
    if (terrain_read_obj(path, &o, &t) != SYL_OK) {
        if (t) abort(); /* a failed read leaves nothing */
        return;
    }
    float tol = 1e-3f * (1 + fmaxf(fabsf(lo), fabsf(hi)));
    for (size_t c = 0; c < (size_t)t->nx * (size_t)t->nz; c++)
        if (!(t->height[c] >= lo - tol && t->height[c] <= hi + tol)) abort();
    syl_terrain_free(t);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    static RTCDevice dev;
    if (!dev && !(dev = rtcNewDevice("threads=1,verbose=0"))) abort();
    FILE *diag = fuzz_diag();
    ObjMesh m;
    if (obj_parse("fuzz.obj", (const char *)data, size, &m, diag_sink(&(SylSink){0}, diag, NULL)) != SYL_OK) return 0;
    for (size_t i = 0; i < 3 * m.nv; i++)
        if (!(fabsf(m.v[i]) <= FAR)) {
            obj_free(&m);
            return 0;
        }
    Obstacles o = {0};
    if (obstacles_add(&o, m.v, m.nv, m.tri, m.nt) && obstacles_commit(&o, dev, diag_sink(&(SylSink){0}, diag, NULL)) == SYL_OK &&
        obstacles_any(&o)) {
        for (int i = 0; i <= 4; i++)
            for (int j = 0; j <= 4; j++) {
                float x = o.lo[0] + (o.hi[0] - o.lo[0]) * (float)i / 4;
                float z = o.lo[2] + (o.hi[2] - o.lo[2]) * (float)j / 4, h;
                if (obstacles_height(&o, x, z, o.hi[1] + 1, &h) && !(h >= o.lo[1] - 1e-3f * (1 + fabsf(o.lo[1]))))
                    abort(); /* a height below the terrain's lowest point */
                float a[3] = {x, o.hi[1] + 1, z}, b[3] = {x, o.lo[1] - 1, z}, down[3] = {0, -1, 0};
                (void)obstacles_blocked(&o, a, b, 0.1f);
                (void)obstacles_distance(&o, a, down, 1e3f);
            }
    }
    obstacles_free(&o);
    dem(data, size, &m, diag);
    obj_free(&m);
    return 0;
}
