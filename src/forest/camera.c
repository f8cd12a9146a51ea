/* The two cameras of a forest picture: the bird's eye framing the whole terrain, and the
 * walker standing inside it, on its valley floor, looking across the stand. */
#include <math.h>
#include <stdbool.h>

#include "forest/forest_internal.h"

static float height_at(const SylTerrain *t, double x, double z) {
    return (float)syl_terrain_factor_at(t, SYL_TERRAIN_ALTITUDE, x, z);
}

static void cross(const double a[3], const double b[3], double out[3]) {
    out[0] = a[1] * b[2] - a[2] * b[1], out[1] = a[2] * b[0] - a[0] * b[2], out[2] = a[0] * b[1] - a[1] * b[0];
    double n = sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
    for (int k = 0; k < 3; k++) out[k] /= n;
}

/* The least distance back from the point (cx, cy) across the view at which every point lies
 * within `fit` of the frame (camera.c's rule for a plant). */
static double fit_distance(const double (*v)[3], size_t n, double cx, double cy, double kx, double ky) {
    double need = 0;
    for (size_t i = 0; i < n; i++)
        need = fmax(need, fmax(fabs(v[i][0] - cx) * kx, fabs(v[i][1] - cy) * ky) - v[i][2]);
    return need;
}

/* From the south (the terrain square to the frame), 40 degrees up: centred and pulled back until every sampled
 * point of the terrain (a grid over it with its edges, at their heights) lies within `fit` of
 * the frame, so the terrain fills the picture (its bounding sphere left half of it empty). */
static void bird(const SylTerrain *t, double aspect, SylRenderCamera *cam) {
    enum { GRID = 48 };
    double v[(GRID + 1) * (GRID + 1)][3]; /* 58 kB: the grid's points in the view's axes */
    const double fit = 0.98, fov = 30, az = 0, el = 50 * M_PI / 180;
    double w = t->nx * t->cell, d = t->nz * t->cell, c[3] = {t->x0 + w / 2, 0, t->z0 + d / 2};
    double back[3] = {sin(az) * cos(el), sin(el), cos(az) * cos(el)}, fwd[3] = {-back[0], -back[1], -back[2]};
    double right[3], up[3], world_up[3] = {0, 1, 0};
    cross(fwd, world_up, right);
    cross(right, fwd, up);
    double tany = tan(fov * 0.5 * M_PI / 180), tanx = tany * aspect, kx = 1 / (fit * tanx), ky = 1 / (fit * tany);
    size_t n = 0;
    for (int k = 0; k <= GRID; k++)
        for (int i = 0; i <= GRID; i++) {
            double x = t->x0 + t->cell * (0.5 + (t->nx - 1) * (double)i / GRID);
            double z = t->z0 + t->cell * (0.5 + (t->nz - 1) * (double)k / GRID);
            double p[3] = {x - c[0], height_at(t, x, z) - c[1], z - c[2]};
            v[n][0] = p[0] * right[0] + p[1] * right[1] + p[2] * right[2];
            v[n][1] = p[0] * up[0] + p[1] * up[1] + p[2] * up[2];
            v[n][2] = p[0] * fwd[0] + p[1] * fwd[1] + p[2] * fwd[2];
            n++;
        }
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++)
        for (int j = 0; j < 2; j++) lo[j] = fmin(lo[j], v[i][j]), hi[j] = fmax(hi[j], v[i][j]);
    double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]); /* flat: the middle */
    double dist = fit_distance(v, n, cx, cy, kx, ky);
    for (int round = 0; round < 4; round++) { /* a few rounds settle the perspective's asymmetry */
        lo[0] = lo[1] = INFINITY, hi[0] = hi[1] = -INFINITY;
        for (size_t i = 0; i < n; i++)
            for (int j = 0; j < 2; j++) {
                double q = (v[i][j] - (j ? cy : cx)) / (dist + v[i][2]);
                lo[j] = fmin(lo[j], q), hi[j] = fmax(hi[j], q);
            }
        cx += 0.5 * (lo[0] + hi[0]) * dist, cy += 0.5 * (lo[1] + hi[1]) * dist;
        dist = fit_distance(v, n, cx, cy, kx, ky);
    }
    for (int k = 0; k < 3; k++) {
        double e = c[k] + right[k] * cx + up[k] * cy - fwd[k] * dist;
        cam->eye[k] = (float)e, cam->target[k] = (float)(e + fwd[k] * dist);
    }
    cam->fov = (float)fov;
}

void syl_forest_camera(const SylForest *f, SylForestView v, int width, int height, SylRenderCamera *cam) {
    const SylTerrain *t = f->t;
    *cam = (SylRenderCamera){0};
    if (v == SYL_FOREST_BIRD) {
        bird(t, height > 0 ? (double)width / height : 1, cam);
        return;
    }
    double w = t->nx * t->cell, d = t->nz * t->cell, cx = t->x0 + w / 2, cz = t->z0 + d / 2, gx = 0, gz = 0;
    size_t nx = (size_t)t->nx, nz = (size_t)t->nz;
    for (size_t k = 0; k < nz; k++)
        for (size_t i = 0; i < nx; i++) {
            double h = t->height[k * nx + i];
            if (i + 1 < nx) gx += fabs(t->height[k * nx + i + 1] - h);
            if (k + 1 < nz) gz += fabs(t->height[(k + 1) * nx + i] - h);
        }
    /* along z when the ground rises less that way per cell (the valley runs along z) */
    bool along_z = gz / (double)(nx * (nz > 1 ? nz - 1 : 1)) < gx / (double)(nz * (nx > 1 ? nx - 1 : 1));
    /* the floor across the terrain's middle, in its middle half: on a hill the lowest point
     * across is its edge, where the walker would look into the void */
    int n = along_z ? t->nx : t->nz;
    double ex = cx, ez = cz, best = INFINITY;
    for (int j = n / 4; j < n - n / 4; j++) {
        double x = along_z ? t->x0 + (j + 0.5) * t->cell : cx, z = along_z ? cz : t->z0 + (j + 0.5) * t->cell;
        double h = height_at(t, x, z);
        if (h < best) best = h, ex = x, ez = z;
    }
    double a = along_z ? height_at(t, ex, t->z0) : height_at(t, t->x0, ez);
    double b = along_z ? height_at(t, ex, t->z0 + d) : height_at(t, t->x0 + w, ez);
    double dir = b <= a ? 1 : -1; /* downhill, across the stand from the middle */
    float ey = height_at(t, ex, ez) + 1.7f;
    /* the eye's target 100 m on, 4 m lower: the ground ahead and the crowns both in view */
    *cam = (SylRenderCamera){.eye = {(float)ex, ey, (float)ez},
                             .target = {(float)(ex + (along_z ? 0 : 100 * dir)), ey - 4,
                                        (float)(ez + (along_z ? 100 * dir : 0))},
                             .fov = 55};
}
