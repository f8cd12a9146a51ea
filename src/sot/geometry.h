/* Small vector helpers of the growth engine, on cglm's vec3. */
#ifndef SYL_SOT_GEOMETRY_H
#define SYL_SOT_GEOMETRY_H
#include <math.h>

#include <cglm/cglm.h>

#include "util/rng.h"

#define SOT_DEG (3.14159265358979f / 180.0f)

/* Normalise v; false (and v untouched) when it is too short. */
static inline bool sot_normalize(vec3 v) {
    float n = glm_vec3_norm(v);
    if (!(n > 1e-12f) || !isfinite(n)) return false;
    glm_vec3_scale(v, 1.0f / n, v);
    return true;
}

/* Carry the reference l along from heading h0 to h1 with the smallest rotation, so an axis
 * does not twist; l1 comes out unit and perpendicular to h1. */
static inline void sot_transport(const vec3 h0, const vec3 l0, const vec3 h1, vec3 l1) {
    /* the rotation taking h0 to h1, without trigonometry: with k = h0 x h1 and c = h0 . h1,
     * R v = c v + k x v + k (k . v) / (1 + c) */
    vec3 k, kv, out;
    glm_vec3_cross((float *)h0, (float *)h1, k);
    float c = glm_vec3_dot((float *)h0, (float *)h1);
    glm_vec3_copy((float *)l0, out);
    if (c > -0.999f) {
        glm_vec3_cross(k, (float *)l0, kv);
        float f = glm_vec3_dot(k, (float *)l0) / (1 + c);
        for (int i = 0; i < 3; i++) out[i] = c * l0[i] + kv[i] + k[i] * f;
    }
    glm_vec3_muladds((float *)h1, -glm_vec3_dot(out, (float *)h1), out);
    if (!sot_normalize(out)) { /* any perpendicular */
        vec3 a = {1, 0, 0};
        if (fabsf(h1[0]) > 0.9f) a[0] = 0, a[1] = 1;
        glm_vec3_cross((float *)h1, a, out);
        sot_normalize(out);
    }
    glm_vec3_copy(out, l1);
}

/* Any unit vector perpendicular to unit n. */
static inline void sot_perpendicular(const vec3 n, vec3 out) {
    vec3 a = {1, 0, 0};
    if (fabsf(n[0]) > 0.9f) a[0] = 0, a[1] = 1;
    glm_vec3_cross((float *)n, a, out);
    sot_normalize(out);
}

/* Turn unit d at random by up to the angle whose cosine is cmax (area-uniform in the cap). */
static inline void sot_jitter(vec3 d, float cmax, Rng *r) { /* cmax: the cosine of the largest turn */
    if (!(cmax < 1)) return;
    float cz = 1 - (float)rng_unit(r) * (1 - cmax), sz = sqrtf(fmaxf(0, 1 - cz * cz));
    float a = 6.2831853f * (float)rng_unit(r);
    vec3 t, b, out;
    sot_perpendicular(d, t);
    glm_vec3_cross(d, t, b);
    for (int k = 0; k < 3; k++) out[k] = d[k] * cz + (t[k] * cosf(a) + b[k] * sinf(a)) * sz;
    if (sot_normalize(out)) glm_vec3_copy(out, d);
}

#endif
