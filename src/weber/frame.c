/* Frames turned about axes: the rotations of Weber & Penn's stem model. A local rotation
 * (about one of the frame's own axes) equals a rotation about that axis in tree coordinates,
 * so every rotation is done one way: Rodrigues' formula applied to the three axes. */
#include "weber/internal.h"

void frame_identity(Frame *f) {
    *f = (Frame){.x = {1, 0, 0}, .y = {0, 1, 0}, .z = {0, 0, 1}, .t = {0, 0, 0}};
}

static void rot_vec(double v[3], const double k[3], double c, double s) {
    double kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    double cx = k[1] * v[2] - k[2] * v[1], cy = k[2] * v[0] - k[0] * v[2], cz = k[0] * v[1] - k[1] * v[0];
    for (int i = 0; i < 3; i++) v[i] = v[i] * c + (i == 0 ? cx : i == 1 ? cy : cz) * s + k[i] * kv * (1 - c);
}

void frame_rot_global(Frame *f, const double axis[3], double deg) {
    if (axis[0] == 0 && axis[1] == 0 && axis[2] > 0) { /* about the vertical */
        double a = deg * (M_PI / 180);
        frame_turn_vertical(f, cos(a), sin(a));
        return;
    }
    double n = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    if (!(n > 1e-12) || deg == 0) return;
    double k[3] = {axis[0] / n, axis[1] / n, axis[2] / n}, a = deg * (M_PI / 180);
    double c = cos(a), s = sin(a);
    rot_vec(f->x, k, c, s);
    rot_vec(f->y, k, c, s);
    rot_vec(f->z, k, c, s);
}

void frame_rot_local(Frame *f, double ax, double ay, double az, double deg) {
    if (deg == 0) return; /* (as frame_rot_global: a straight stem's segments turn by nothing) */
    /* the frame's own axes, the common case, by a plane turn */
    if (ay == 0 && az == 0 && ax == 1) {
        double a = deg * (M_PI / 180);
        frame_turn_x(f, cos(a), sin(a));
        return;
    }
    if (ax == 0 && ay == 0 && az == 1) {
        double a = deg * (M_PI / 180);
        frame_turn_z(f, cos(a), sin(a));
        return;
    }
    double k[3];
    for (int i = 0; i < 3; i++) k[i] = ax * f->x[i] + ay * f->y[i] + az * f->z[i];
    frame_rot_global(f, k, deg);
}

void frame_rotxz(Frame *f, double down, double rot) {
    frame_rot_local(f, 0, 0, 1, rot);
    frame_rot_local(f, 1, 0, 0, down);
}

void frame_move(Frame *f, double d) {
    for (int i = 0; i < 3; i++) f->t[i] += f->z[i] * d;
}
