/* Plants side by side for `sylva compare --image`. */
#ifndef SYL_CLI_LINEUP_H
#define SYL_CLI_LINEUP_H
#include "sylva/mesh.h"

/* One mesh of the n meshes, each moved so that its ground (ground[i], a y) is at y = 0,
 * its middle in z at z = 0, the plants in a row along +x with gaps between their bounds, and
 * a height ruler left of the first: a pole from 0 to the next tick above the tallest plant,
 * ticks at round heights (1, 2 or 5 times a power of ten) and their values written with
 * seven-segment digits, all as boxes of a material of its own (the last one). Materials that
 * are the same (colour and kind) are shared. names: NULL, or each plant's name, written in
 * the ruler's material with the 5 x 7 letters of font.c, upright on the ground in front of
 * its plant. NULL when out of memory. */
SylMesh *lineup_build(const SylMesh *const *meshes, const double *ground, const char *const *names, int n);

#endif
