/* What each frame of `sylva animate` is framed to: a box that moves from the frame's own
 * plant (the first frame fills the picture: a seedling is readable, not a speck) to the last
 * frame's (which the last frame fills), so the camera pulls back steadily as the plant grows. */
#include <math.h>
#include <stdbool.h>

#include "cli/animate.h"

static void bounds(const SylMesh *m, float lo[3], float hi[3]) {
    for (int k = 0; k < 3; k++) lo[k] = INFINITY, hi[k] = -INFINITY;
    for (size_t i = 0; m && i < m->nverts; i++)
        for (int k = 0; k < 3; k++) {
            float v = m->pos[3 * i + k];
            if (!isfinite(v)) continue;
            lo[k] = fminf(lo[k], v), hi[k] = fmaxf(hi[k], v);
        }
}

void cli_frame_box(const SylMesh *own, const SylMesh *last, double t, CliFrameBox *box) {
    float lo[3], hi[3], llo[3], lhi[3];
    bounds(own, lo, hi);
    bounds(last, llo, lhi);
    /* the box's size moves geometrically, own^(1-t) last^t: a plant that grows a hundredfold
     * grows tenfold by the middle frame, never shrinking to a speck early on */
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    float so = 0, sl = 0;
    for (int k = 0; k < 3; k++) {
        if (lo[k] <= hi[k]) so = fmaxf(so, hi[k] - lo[k]);
        if (llo[k] <= lhi[k]) sl = fmaxf(sl, lhi[k] - llo[k]);
    }
    float w = (float)t;
    if (so > 0 && sl > so) w = (float)((pow(so, 1 - t) * pow(sl, t) - so) / (sl - so));
    for (int k = 0; k < 3; k++) {
        if (!(lo[k] <= hi[k])) lo[k] = llo[k], hi[k] = lhi[k]; /* nothing drawn yet */
        if (!(llo[k] <= lhi[k])) continue;                     /* nor at the end: the renderer's own */
        float a = lo[k] + w * (llo[k] - lo[k]), b = hi[k] + w * (lhi[k] - hi[k]);
        lo[k] = fminf(lo[k], a), hi[k] = fmaxf(hi[k], b); /* the frame's own plant always fits */
    }
    /* the view `auto` picks from the box (front for a plant in a plane) is the last frame's in
     * every frame: a one-shoot seedling is not drawn from the front and its tree from eye level */
    float size = fmaxf(hi[0] - lo[0], fmaxf(hi[1] - lo[1], hi[2] - lo[2])), mid = 0.5f * (lo[2] + hi[2]);
    bool flat = sl > 0 && lhi[2] - llo[2] < 0.05f * sl;
    float depth = flat ? (lhi[2] - llo[2]) / sl * size : fmaxf(hi[2] - lo[2], 0.06f * size);
    if (isfinite(size) && size > 0) lo[2] = mid - 0.5f * depth, hi[2] = mid + 0.5f * depth;
    for (int i = 0; i < 8; i++)
        for (int k = 0; k < 3; k++) box->corners[i][k] = i >> k & 1 ? hi[k] : lo[k];
    box->mesh = (SylMesh){.pos = &box->corners[0][0], .nverts = isfinite(lo[0]) && isfinite(lo[1]) ? 8 : 0};
}
