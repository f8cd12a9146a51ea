/* The direction of a new metamer (Tázlar 2018 §3.4.6–7, Palubicki 2009):
 *
 *   S = w_bud O + w_space P + w_light G + w_tropism T  (+ w_trunk Y on the trunk's apex)
 *
 * O the bud's orientation, P the space-colonization direction (sum of unit vectors to the
 * bud's markers), G the direction of least shadow, T the tropism — "up" turned by the
 * tropism angle (0 up, 90 horizontal, 180 down) in the vertical plane of O — and Y straight
 * up, keeping the trunk straight. The trunk's apex gets T only with trunk_tropism on. The
 * result is turned at random by up to `jitter` degrees. All vectors are unit; a missing one
 * (no markers, uniform light) is zero. */
#ifndef SYL_SOT_DIRECTION_H
#define SYL_SOT_DIRECTION_H
#include <stdbool.h>

#include "sot/params.h"
#include "util/rng.h"

void sot_tropism(const GrowParams *P, const float O[3], Rng *r, float out[3]);
void sot_direction(const GrowParams *P, const float O[3], const float space[3], const float light[3], bool trunk,
                   Rng *r, float out[3]);

#endif
