/* The OBJ DEM reader: a terrain mesh rasterized by casting one ray down through each cell's
 * centre (Embree, env/obstacles.h); the highest surface is the height, and a cell with none
 * under it has no data. */
#include <math.h>
#include <stdlib.h>

#include "env/obstacles.h"
#include "terrain/terrain.h"

int terrain_read_obj(const char *path, const SylTerrainOptions *o, Terrain **out) {
    *out = NULL;
    const SylSink *sink = opt_sink(o);
    Obstacles ob = {0};
    static const float zero[3] = {0, 0, 0};
    int st = obstacles_add_obj(&ob, path, zero, 1, sink);
    if (st) return st;
    double wx = (double)ob.hi[0] - ob.lo[0], wz = (double)ob.hi[2] - ob.lo[2];
    if (!(wx > 0) || !(wz > 0)) {
        diag_say(NULL, sink, DIAG_ERROR, path, "the mesh has no extent in x or z: a terrain lies in the x-z plane");
        obstacles_free(&ob);
        return SYL_EMODEL;
    }
    /* Without a cell size: about one cell per vertex, as a grid written as a mesh had. */
    double cell = o->cell > 0 ? o->cell : sqrt(wx * wz / (double)(ob.nv > 1 ? ob.nv : 1));
    cell = fmin(fmax(cell, TERRAIN_MIN_CELL), TERRAIN_MAX_CELL);
    double nxd = ceil(wx / cell - 1e-9), nzd = ceil(wz / cell - 1e-9);
    if (nxd < 1) nxd = 1;
    if (nzd < 1) nzd = 1;
    if (nxd > TERRAIN_MAX_SIDE || nzd > TERRAIN_MAX_SIDE) {
        diag_say(NULL, sink, DIAG_ERROR, path, "cells of %g make a %.0f x %.0f grid: Sylva reads 1 to %d cells a side "
                          "(--cell)", cell, nxd, nzd, TERRAIN_MAX_SIDE);
        obstacles_free(&ob);
        return SYL_ELIMIT;
    }
    Terrain *t;
    st = terrain_new((int)nxd, (int)nzd, o->budget, o->max_memory, path, sink, &t);
    if (st) {
        obstacles_free(&ob);
        return st;
    }
    t->cell = cell;
    t->x0 = ob.lo[0];
    t->z0 = ob.lo[2];
    RTCDevice dev = rtcNewDevice("threads=1,verbose=0");
    st = dev ? obstacles_commit(&ob, dev, sink) : SYL_ELIMIT;
    if (!st) {
        float top = ob.hi[1] + 1 + fabsf(ob.hi[1]) * 1e-3f;
        for (int k = 0; k < t->nz; k++)
            for (int i = 0; i < t->nx; i++) {
                size_t c = (size_t)k * (size_t)t->nx + (size_t)i;
                float h;
                if (obstacles_height(&ob, (float)(t->x0 + (i + 0.5) * cell), (float)(t->z0 + (k + 0.5) * cell), top,
                                     &h))
                    t->height[c] = h;
                else t->valid[c] = 0;
            }
        if (!terrain_fill_unknown(t)) {
            diag_say(NULL, sink, DIAG_ERROR, path, "no surface under any cell's centre");
            st = SYL_EMODEL;
        }
    } else if (sink && !dev) sink_error(sink, "cannot start Embree");
    obstacles_free(&ob);
    if (dev) rtcReleaseDevice(dev);
    if (st) syl_terrain_free(t);
    else *out = t;
    return st;
}
