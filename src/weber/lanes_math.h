/* The lanes' functions for one width (lanes.h includes this once per width): LANES_F, LANES_I
 * and LANES_U its float, int and bit vectors, LANES(name) the functions' names. No guard. */
/* a float in every lane */
static inline LANES_F LANES(set)(float a) { return (LANES_F){0} + a; }
/* m ? a : b per lane, m a comparison's mask */
static inline LANES_F LANES(sel)(LANES_I m, LANES_F a, LANES_F b) { return (LANES_F)((m & (LANES_I)a) | (~m & (LANES_I)b)); }
static inline LANES_F LANES(abs)(LANES_F a) { return (LANES_F)((LANES_U)a & 0x7fffffffu); }

/* sin and cos: x = k pi/2 + r, |r| <= pi/4, pi/2 in three parts (Cody and Waite: k times
 * the first two is exact for |k| < 2^8), Taylor polynomials to r^9 and r^10 (error under
 * 2e-9), then the quadrant. */
static inline void LANES(sincos)(LANES_F x, LANES_F *c, LANES_F *s) {
    const LANES_F round = LANES(set)(0x1.8p23f); /* adding and taking it away rounds to an integer */
    LANES_F k = (x * LANES(set)((float)(2 / M_PI)) + round) - round;
    LANES_F r = ((x - k * 1.5703125f) - k * 4.837512969970703125e-4f) - k * 7.54978995489188216e-8f, z = r * r;
    LANES_F sn = r + r * z * (-1.0f / 6 + z * (1.0f / 120 + z * (-1.0f / 5040 + z * (1.0f / 362880))));
    LANES_F cs = 1 + z * (-0.5f + z * (1.0f / 24 + z * (-1.0f / 720 + z * (1.0f / 40320 + z * (-1.0f / 3628800)))));
    LANES_I q = __builtin_convertvector(k, LANES_I), odd = (q & 1) != 0;
    LANES_F ss = LANES(sel)(odd, cs, sn), cc = LANES(sel)(odd, sn, cs);
    LANES_U uq = (LANES_U)q;
    *s = (LANES_F)((LANES_U)ss ^ ((uq & 2) << 30));       /* quadrants 2 and 3: -sin */
    *c = (LANES_F)((LANES_U)cc ^ (((uq + 1) & 2) << 30)); /* quadrants 1 and 2: -cos */
}

/* atan2(y, x): atan t / t as a polynomial in t^2 over [0, 1] (Chebyshev interpolation, degree
 * 9: within 2e-9 in doubles), t the smaller coordinate over the larger, then the octant */
static inline LANES_F LANES(atan2)(LANES_F y, LANES_F x) {
    LANES_F ax = LANES(abs)(x), ay = LANES(abs)(y);
    LANES_I xbig = ax > ay;
    LANES_F hi = LANES(sel)(xbig, ax, ay), lo = LANES(sel)(xbig, ay, ax);
    LANES_F t = LANES(sel)(hi > 0, lo / LANES(sel)(hi > 0, hi, LANES(set)(1)), LANES(set)(0)), z = t * t, z2 = z * z,
            z4 = z2 * z2;
    LANES_F p = (0.999999997160544f + -0.33333276291968977f * z) + z2 * (0.1999807528082414f + -0.14260016079705623f * z) +
                z4 * ((0.10932341485896302f + -0.083497249245010619f * z) +
                      z2 * (0.057089555186985316f + -0.030351864043404932f * z)) +
                z4 * z4 * (0.010487648853086284f + -0.0017011699732393027f * z);
    LANES_F r = t * p;
    r = LANES(sel)(ay > ax, (float)(M_PI / 2) - r, r);
    r = LANES(sel)((LANES_I)x < 0, (float)M_PI - r, r);
    return (LANES_F)(((LANES_U)r & 0x7fffffffu) | ((LANES_U)y & 0x80000000u)); /* copysign */
}

#undef LANES_F
#undef LANES_I
#undef LANES_U
#undef LANES
