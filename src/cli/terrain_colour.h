/* Coloured, hillshaded maps of a terrain's factors with a legend (terrain_colour.c). */
#ifndef SYL_CLI_TERRAIN_COLOUR_H
#define SYL_CLI_TERRAIN_COLOUR_H
#include "sylva/terrain.h"

/* DIR/NAME-colour.png for every factor (all computed), their paths printed; a Sylva status. */
int cli_terrain_colour_maps(const SylTerrain *t, const char *dir);

#endif
