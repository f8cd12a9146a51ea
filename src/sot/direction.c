/* Growth direction: see direction.h. */
#include "sot/direction.h"

#include "sot/geometry.h"

void sot_tropism(const GrowParams *P, const float O[3], Rng *r, float out[3]) {
    vec3 side = {O[0], 0, O[2]};
    if (!sot_normalize(side)) { /* a vertical bud: a plane at random */
        float a = 6.2831853f * (float)rng_unit(r);
        side[0] = cosf(a), side[1] = 0, side[2] = sinf(a);
    }
    out[0] = P->tropism_sin * side[0];
    out[1] = P->tropism_cos;
    out[2] = P->tropism_sin * side[2];
}

void sot_direction(const GrowParams *P, const float O[3], const float space[3], const float light[3], bool trunk,
                   Rng *r, float out[3]) {
    vec3 s, t;
    glm_vec3_scale((float *)O, P->w_bud, s);
    glm_vec3_muladds((float *)space, P->w_space, s);
    glm_vec3_muladds((float *)light, P->w_light, s);
    if (P->w_tropism != 0 && (!trunk || P->trunk_tropism)) {
        sot_tropism(P, O, r, t);
        glm_vec3_muladds(t, P->w_tropism, s);
    }
    if (trunk) s[1] += P->w_trunk;
    if (!sot_normalize(s)) glm_vec3_copy((float *)O, s);
    sot_jitter(s, P->jitter_cos, r);
    glm_vec3_copy(s, out);
}
