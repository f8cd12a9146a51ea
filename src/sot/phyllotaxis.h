/* Where lateral buds point, and which of them the tree prefers.
 *
 * Phyllotaxis: a node of rank r (its place along the axis) carries N lateral buds (1
 * alternate, 2 opposite, N whorled) at azimuths r * divergence + k * 360 / N about the
 * heading, measured from the node's transported reference L, each at the branching angle
 * from the heading.
 *
 * Gravimorphism (Tázlar 2018 §3.4.2, after Barthélémy & Caraglio 2007): the bud's direction
 * is projected on the plane across its branch, whose axes are P (horizontal) and V (up the
 * slope); d is the distance from the centre to an ellipse with semi-axes S_p, S_v whose
 * centre is moved up by e_v, measured along the projection; with tau the angle between
 * branch and vertical, the bud's resource is scaled by p = cos^2 tau + d sin^2 tau — full
 * effect on horizontal branches, none on vertical ones. */
#ifndef SYL_SOT_PHYLLOTAXIS_H
#define SYL_SOT_PHYLLOTAXIS_H
#include "sot/tree.h"

/* The direction of lateral bud k of node nd. */
void phyl_lateral_dir(const GrowParams *P, const Node *nd, int k, float out[3]);
float phyl_gravimorphism(const GrowParams *P, const float branch[3], const float bud[3]);

#endif
