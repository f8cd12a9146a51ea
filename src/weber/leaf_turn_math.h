/* The leaves' turns for one width (leaf_turn.h includes this once per width): LANES_F the
 * float vector of LANES_N lanes, LANES(name) the names (the lanes' functions and this one).
 * The 8 / LANES_N sets of lanes are turned side by side: independent chains of sines and
 * arctangents keep the processor busier than one. No guard. */
static inline void LANES(leaf_turn)(Leaves8 *q8, bool turned, float b) {
    enum { NJ = 8 / LANES_N };
    LANES_F c[NJ], s[NJ], a[NJ];
    /* set j of the lanes of field v (component i): Leaves8's vectors are 8 lanes, NJ sets */
#define AX(j, v, i) (((LANES_F *)q8)[(offsetof(Leaves8, v) / sizeof(v8f) + (i)) * NJ + (j)])
    if (!turned) { /* each one's segment frame by rot about its z, then by down about the new x */
        LANES_F cr[NJ], sr[NJ], cd[NJ], sd[NJ];
        for (int j = 0; j < NJ; j++)
            LANES(sincos)(AX(j, rot, 0), &cr[j], &sr[j]), LANES(sincos)(AX(j, down, 0), &cd[j], &sd[j]);
        for (int j = 0; j < NJ; j++)
            for (int i = 0; i < 3; i++) {
                LANES_F fx = AX(j, x, i), fy = AX(j, y, i), fz = AX(j, z, i);
                LANES_F y = cr[j] * fy - sr[j] * fx;
                AX(j, x, i) = cr[j] * fx + sr[j] * fy;
                AX(j, y, i) = cd[j] * y + sd[j] * fz;
                AX(j, z, i) = cd[j] * fz - sd[j] * y;
            }
    }
    if (b == 0) return;
    /* bent outward (about the vertical) and up (about their x) toward the light */
    for (int j = 0; j < NJ; j++) a[j] = b * (LANES(atan2)(AX(j, ty, 0), AX(j, tx, 0)) - LANES(atan2)(AX(j, y, 1), AX(j, y, 0)));
    for (int j = 0; j < NJ; j++) LANES(sincos)(a[j], &c[j], &s[j]);
    for (int j = 0; j < NJ; j++)
        for (int i = 0; i < 3; i++) {
            LANES_F *v = i == 0 ? &AX(j, x, 0) : i == 1 ? &AX(j, y, 0) : &AX(j, z, 0);
            LANES_F x = v[0], y = v[NJ];
            v[0] = c[j] * x - s[j] * y;
            v[NJ] = s[j] * x + c[j] * y;
        }
    for (int j = 0; j < NJ; j++) {
        LANES_F y0 = AX(j, y, 0), y1 = AX(j, y, 1);
        a[j] = b * LANES(atan2)(LANES(sqrt)(y0 * y0 + y1 * y1), AX(j, y, 2));
    }
    for (int j = 0; j < NJ; j++) LANES(sincos)(a[j], &c[j], &s[j]);
    for (int j = 0; j < NJ; j++)
        for (int i = 0; i < 3; i++) {
            LANES_F p = AX(j, y, i), r = AX(j, z, i);
            AX(j, y, i) = c[j] * p + s[j] * r;
            AX(j, z, i) = c[j] * r - s[j] * p;
        }
#undef AX
}

#undef LANES_F
#undef LANES_N
#undef LANES
