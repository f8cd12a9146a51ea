/* The renderer's camera: each view framed so the mesh fills about 80% of the picture. */
#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "render/render_internal.h"

static const float fit = 0.8f;            /* the plant fills this share of the frame */
static const float half_fov_y = 17.5f;    /* degrees: a 35 degree vertical field of view */
static const float eye_level = 6;         /* degrees above the horizontal of the auto view */

/* The points to frame in view coordinates (x right, y up, z depth from the centre): the
 * mesh's vertices, or the corners of its box when there are none or memory is short. */
typedef struct FitPoints {
    float (*v)[3];
    size_t n;
    float corners[8][3];
} FitPoints;

static void fit_points(FitPoints *f, const SylMesh *m, const float lo[3], const float hi[3], const float c[3],
                       const float right[3], const float up[3], const float fwd[3]) {
    const float *axes[3] = {right, up, fwd};
    for (int i = 0; i < 8; i++) {
        float q[3] = {(i & 1 ? hi[0] : lo[0]) - c[0], (i & 2 ? hi[1] : lo[1]) - c[1], (i & 4 ? hi[2] : lo[2]) - c[2]};
        for (int k = 0; k < 3; k++) f->corners[i][k] = q[0] * axes[k][0] + q[1] * axes[k][1] + q[2] * axes[k][2];
    }
    f->v = f->corners;
    f->n = 8;
    float (*v)[3] = m && m->nverts ? malloc(m->nverts * sizeof *v) : NULL;
    if (!v) return;
    size_t n = 0;
    for (size_t i = 0; i < m->nverts; i++) {
        const float *p = m->pos + 3 * i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) continue;
        float q[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
        for (int k = 0; k < 3; k++) v[n][k] = q[0] * axes[k][0] + q[1] * axes[k][1] + q[2] * axes[k][2];
        n++;
    }
    if (!n) {
        free(v);
        return;
    }
    f->v = v;
    f->n = n;
}

/* Extent of the points across the view, shifted by (cx, cy): divided by the depth when
 * dist >= 0 (tangents), plain (orthographic) when dist < 0. ext: xmin xmax ymin ymax. */
static void fit_extent(const FitPoints *f, float cx, float cy, float dist, float ext[4]) {
    ext[0] = ext[2] = INFINITY;
    ext[1] = ext[3] = -INFINITY;
    for (size_t i = 0; i < f->n; i++) {
        float x = f->v[i][0] - cx, y = f->v[i][1] - cy, z = f->v[i][2];
        if (dist >= 0) {
            if (!(dist + z > 0)) continue;
            x /= dist + z, y /= dist + z;
        }
        ext[0] = x < ext[0] ? x : ext[0], ext[1] = x > ext[1] ? x : ext[1];
        ext[2] = y < ext[2] ? y : ext[2], ext[3] = y > ext[3] ? y : ext[3];
    }
    if (!(ext[0] <= ext[1])) ext[0] = ext[1] = 0;
    if (!(ext[2] <= ext[3])) ext[2] = ext[3] = 0;
}

/* The least distance back from the centre at which all points fit. */
static float fit_distance(const FitPoints *f, float cx, float cy, float tanx, float tany, float size) {
    float need = 0, zmin = INFINITY, kx = 1 / (fit * tanx), ky = 1 / (fit * tany);
    for (size_t i = 0; i < f->n; i++) {
        float x = f->v[i][0] - cx, y = f->v[i][1] - cy, z = f->v[i][2];
        float ax = fabsf(x) * kx, ay = fabsf(y) * ky, a = (ax > ay ? ax : ay) - z;
        need = a > need ? a : need;
        zmin = z < zmin ? z : zmin;
    }
    if (!isfinite(zmin)) zmin = 0;
    return fmaxf(need, fmaxf(-zmin + 0.05f * size, 0.1f * size));
}

void render_mesh_bounds(const SylMesh *m, float lo[3], float hi[3]) {
    glm_vec3_copy((vec3){INFINITY, INFINITY, INFINITY}, lo);
    glm_vec3_copy((vec3){-INFINITY, -INFINITY, -INFINITY}, hi);
    for (size_t i = 0; m && i < m->nverts; i++)
        for (int k = 0; k < 3; k++) {
            float v = m->pos[3 * i + k];
            if (!isfinite(v)) continue;
            if (v < lo[k]) lo[k] = v;
            if (v > hi[k]) hi[k] = v;
        }
    if (!(lo[0] <= hi[0] && lo[1] <= hi[1] && lo[2] <= hi[2])) { /* nothing to frame */
        glm_vec3_copy((vec3){-0.5f, 0, -0.5f}, lo);
        glm_vec3_copy((vec3){0.5f, 1, 0.5f}, hi);
    }
}

void render_camera_toward(const SylMesh *m, const float toward[3], int width, int height, RenderCamera *cam) {
    vec3 lo, hi;
    render_mesh_bounds(m, lo, hi);
    render_camera_toward_box(lo, hi, toward, width, height, cam);
}

void render_camera_toward_box(const float box_lo[3], const float box_hi[3], const float toward[3], int width,
                              int height, RenderCamera *cam) {
    memset(cam, 0, sizeof *cam);
    cam->width = width;
    cam->height = height;
    vec3 lo = {box_lo[0], box_lo[1], box_lo[2]}, hi = {box_hi[0], box_hi[1], box_hi[2]};
    vec3 c, back, fwd, right, up, upref = {0, 1, 0};
    glm_vec3_copy(lo, cam->lo);
    glm_vec3_copy(hi, cam->hi);
    glm_vec3_center(lo, hi, c);
    float r = 0.5f * glm_vec3_distance(lo, hi), dist = 100 * r;
    if (!(r > 0)) r = 1, dist = 100;
    glm_vec3_normalize_to((float *)toward, back);
    if (fabsf(back[1]) > 0.999f) glm_vec3_copy((vec3){0, 0, -1}, upref); /* from straight above */
    glm_vec3_negate_to(back, fwd);
    glm_vec3_crossn(fwd, upref, right);
    glm_vec3_cross(right, fwd, up);
    cam->tany = r / dist;
    cam->tanx = cam->tany * (float)width / (float)height;
    glm_vec3_copy(c, cam->eye);
    glm_vec3_muladds(back, dist, cam->eye);
    glm_vec3_copy(fwd, cam->fwd);
    glm_vec3_copy(right, cam->right);
    glm_vec3_copy(up, cam->up);
    cam->near = dist - r;
    cam->depth = 2 * r;
}

void render_camera(const SylMesh *m, SylView view, int width, int height, RenderCamera *cam) {
    memset(cam, 0, sizeof *cam);
    cam->width = width;
    cam->height = height;
    vec3 lo, hi;
    render_mesh_bounds(m, lo, hi);
    glm_vec3_copy(lo, cam->lo);
    glm_vec3_copy(hi, cam->hi);
    float size = fmaxf(hi[0] - lo[0], fmaxf(hi[1] - lo[1], hi[2] - lo[2]));
    if (!(size > 0)) size = 1;
    /* auto: a plant drawn in a plane from the front; any other from eye level, a little
     * above the horizontal, so the trunk stands under the crown and the horizon crosses the
     * picture above its middle (a view from 35 degrees up hides the trunk in the crown) */
    float el = glm_rad(35), az = glm_rad(45);
    if (view == SYL_VIEW_AUTO) {
        view = hi[2] - lo[2] < 0.05f * size ? SYL_VIEW_FRONT : SYL_VIEW_ISO;
        el = glm_rad(eye_level);
    }

    vec3 back, upref = {0, 1, 0};
    switch (view) {
    case SYL_VIEW_FRONT: glm_vec3_copy((vec3){0, 0, 1}, back); break;
    case SYL_VIEW_SIDE: glm_vec3_copy((vec3){1, 0, 0}, back); break;
    case SYL_VIEW_TOP:
        glm_vec3_copy((vec3){0, 1, 0}, back);
        glm_vec3_copy((vec3){0, 0, -1}, upref);
        break;
    default: glm_vec3_copy((vec3){cosf(el) * sinf(az), sinf(el), cosf(el) * cosf(az)}, back); break;
    }
    vec3 fwd, right, up;
    glm_vec3_negate_to(back, fwd);
    glm_vec3_crossn(fwd, upref, right);
    glm_vec3_cross(right, fwd, up);
    cam->tany = tanf(glm_rad(half_fov_y));
    cam->tanx = cam->tany * (float)width / (float)height;

    /* Fit: centre the projected extent and pull back until every vertex projects inside
     * `fit` of the frame; a few rounds settle the perspective's asymmetry. */
    vec3 c;
    glm_vec3_center(lo, hi, c);
    FitPoints fp;
    fit_points(&fp, m, lo, hi, c, right, up, fwd);
    float cx, cy, dist, ext[4];
    fit_extent(&fp, 0, 0, -1, ext); /* orthographic: the middle */
    cx = 0.5f * (ext[0] + ext[1]);
    cy = 0.5f * (ext[2] + ext[3]);
    dist = fit_distance(&fp, cx, cy, cam->tanx, cam->tany, size);
    for (int round = 0; round < 3; round++) {
        fit_extent(&fp, cx, cy, dist, ext);
        cx += 0.5f * (ext[0] + ext[1]) * dist;
        cy += 0.5f * (ext[2] + ext[3]) * dist;
        dist = fit_distance(&fp, cx, cy, cam->tanx, cam->tany, size);
    }
    if (fp.v != fp.corners) free(fp.v);
    vec3 eye;
    glm_vec3_copy(c, eye);
    glm_vec3_muladds(right, cx, eye);
    glm_vec3_muladds(up, cy, eye);
    glm_vec3_muladds(fwd, -dist, eye);
    glm_vec3_copy(eye, cam->eye);
    glm_vec3_copy(fwd, cam->fwd);
    glm_vec3_copy(right, cam->right);
    glm_vec3_copy(up, cam->up);
}

bool render_project(const RenderCamera *cam, const float p[3], float *x, float *y) {
    float q[3] = {p[0] - cam->eye[0], p[1] - cam->eye[1], p[2] - cam->eye[2]};
    float z = q[0] * cam->fwd[0] + q[1] * cam->fwd[1] + q[2] * cam->fwd[2];
    if (!(z > 0)) return false;
    float sx = (q[0] * cam->right[0] + q[1] * cam->right[1] + q[2] * cam->right[2]) / (z * cam->tanx);
    float sy = (q[0] * cam->up[0] + q[1] * cam->up[1] + q[2] * cam->up[2]) / (z * cam->tany);
    *x = (sx + 1) * 0.5f * (float)cam->width;
    *y = (1 - sy) * 0.5f * (float)cam->height;
    return true;
}
