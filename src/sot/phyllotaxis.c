/* Phyllotaxis and gravimorphism: see phyllotaxis.h. */
#include "sot/phyllotaxis.h"

#include "sot/geometry.h"

void phyl_lateral_dir(const GrowParams *P, const Node *nd, int k, float out[3]) {
    float az = ((float)nd->rank * P->divergence + (float)k * 360.0f / (float)P->laterals) * SOT_DEG;
    vec3 h, l, u;
    glm_vec3_copy((float *)nd->h, h);
    glm_vec3_copy((float *)nd->l, l);
    glm_vec3_cross(h, l, u);
    float ca = cosf(az), sa = sinf(az), cp = P->branch_cos, sp = P->branch_sin;
    for (int j = 0; j < 3; j++) out[j] = cp * h[j] + sp * (ca * l[j] + sa * u[j]);
    sot_normalize(out);
}

float phyl_gravimorphism(const GrowParams *P, const float branch[3], const float bud[3]) {
    if (P->grav_h == 1 && P->grav_v == 1 && P->grav_up == 0) return 1;
    vec3 h, b, v = {0, 1, 0}, p;
    glm_vec3_copy((float *)branch, h);
    glm_vec3_copy((float *)bud, b);
    float ct = fabsf(h[1]);
    /* V: up, across the branch; P: horizontal, across the branch */
    glm_vec3_muladds(h, -h[1], v);
    if (!sot_normalize(v)) return 1; /* a vertical branch: no effect */
    glm_vec3_cross(h, v, p);
    float x = glm_vec3_dot(b, p), y = glm_vec3_dot(b, v), len = sqrtf(x * x + y * y);
    float d = 1;
    if (len > 1e-6f) {
        x /= len, y /= len;
        /* t^2 (x^2/Sp^2 + y^2/Sv^2) - 2 t y e/Sv^2 + e^2/Sv^2 - 1 = 0, the positive root */
        float sp2 = P->grav_h * P->grav_h, sv2 = P->grav_v * P->grav_v, e = P->grav_up;
        float A = x * x / sp2 + y * y / sv2, B = -2 * y * e / sv2, C = e * e / sv2 - 1;
        float disc = B * B - 4 * A * C;
        d = disc > 0 ? (-B + sqrtf(disc)) / (2 * A) : 0;
        if (d < 0) d = 0;
    }
    float st2 = 1 - ct * ct;
    return ct * ct + d * st2;
}
