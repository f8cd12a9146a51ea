/* The L-system plants of a scene beside trees, deriving a step a year in lockstep (lsys.c). */
#ifndef SYL_SCENE_LSYS_H
#define SYL_SCENE_LSYS_H
#include "sot/forest.h"

/* The L-system plants of a scene with trees (lsys.c): they derive one step per year,
 * in lockstep with the trees, through the forest's year_start hook. */
typedef struct SceneLsys SceneLsys;
/* Room for max plants; hooks itself into f. NULL when out of memory. */
SceneLsys *scene_lsys_new(Forest *f, int max);
void scene_lsys_free(SceneLsys *s);
/* A plant (before forest_setup): it takes q, derives with d (its env is replaced) and takes
 * `steps` steps, standing at `at`; ground is the plane its ?E(2) distances meet. */
int scene_lsys_add(SceneLsys *s, const SylProgram *q, const SylDeriveOptions *d, const float at[3], float ground, int steps);
/* After forest_run: steps not taken yet (a forest of 0 years), and the final strings. */
int scene_lsys_finish(SceneLsys *s);
/* The i-th plant's skeleton, moved into place. */
int scene_lsys_draw(SceneLsys *s, int i, SylSkeleton **out);
/* Interpret s, draw it with the turtle and move the skeleton by at. */
int lsys_draw(const SylProgram *q, const SylString *s, const SylDeriveOptions *d, const float at[3], SylSkeleton **out);

#endif
