/* The turtle's frame operations, for every reader of turtle commands (the drawing turtle, its
 * query pass, sot's shoot-plan reader): exact turns, and re-orthonormalising the frame. */
#ifndef SYL_TURTLE_FRAME_H
#define SYL_TURTLE_FRAME_H
#include <cglm/cglm.h>

#include "lang/turtle_commands.h"

/* The frame is re-orthonormalised after this many turns, and before it is read after one:
 * float rounding builds up over many turns. */
enum { TURTLE_TIDY_TURNS = 32 };

/* sin and cos of an angle in degrees, exact at multiples of 90. */
void turtle_sincos(double deg, float *s, float *c);

/* Rotate the pair (a, b) in its plane: a' = a cos + b sin, b' = b cos - a sin. */
static inline __attribute__((always_inline)) void turtle_rotate_pair(vec3 a, vec3 b, float s, float c) {
    vec3 a2, b2;
    glm_vec3_scale(a, c, a2);
    glm_vec3_muladds(b, s, a2);
    glm_vec3_scale(b, c, b2);
    glm_vec3_muladds(a, -s, b2);
    glm_vec3_copy(a2, a);
    glm_vec3_copy(b2, b);
}

/* A turn command (TC_LEFT to TC_ROLL_RIGHT) by an angle of sine s and cosine c, or `|`
 * (TC_TURN_AROUND): + turns H toward L, & H toward -U, \ L toward -U. */
static inline __attribute__((always_inline)) void turtle_turn(TurtleCommand cmd, float s, float c, vec3 h, vec3 l,
                                                              vec3 u) {
    switch (cmd) {
    case TC_LEFT: turtle_rotate_pair(h, l, s, c); break;
    case TC_RIGHT: turtle_rotate_pair(h, l, -s, c); break;
    case TC_DOWN: turtle_rotate_pair(u, h, s, c); break;
    case TC_UP: turtle_rotate_pair(u, h, -s, c); break;
    case TC_ROLL_LEFT: turtle_rotate_pair(u, l, s, c); break;
    case TC_ROLL_RIGHT: turtle_rotate_pair(u, l, -s, c); break;
    case TC_TURN_AROUND:
        glm_vec3_negate(h);
        glm_vec3_negate(l);
        break;
    default: break;
    }
}

/* Make H, L, U orthonormal again, keeping H's direction and L's plane. */
static inline void turtle_orthonormalise(vec3 h, vec3 l, vec3 u) {
    glm_vec3_normalize(h);
    glm_vec3_muladds(h, -glm_vec3_dot(l, h), l);
    glm_vec3_normalize(l);
    glm_vec3_cross(h, l, u);
}

/* Its second half, L and U from a unit H (the query pass makes H alone first). */
static inline void turtle_orthonormalise_lu(vec3 h, vec3 l, vec3 u) {
    glm_vec3_muladds(h, -glm_vec3_dot(l, h), l);
    glm_vec3_normalize(l);
    glm_vec3_cross(h, l, u);
}

#endif
