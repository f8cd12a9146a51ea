/* Turtle internals the derivation engine may use. */
#ifndef SYL_TURTLE_H
#define SYL_TURTLE_H
#include "sylva/sylva.h"

/* Fill the query modules ?P(x,y,z), ?H, ?L and ?U of s with the turtle's position and frame
 * where each one stands (LANGUAGE.md §5), in place. Nothing else is changed; strings without
 * query modules are left alone at the cost of one look-up per symbol. Returns SYL_OK, or
 * SYL_ELIMIT when out of memory. */
/* With env, also collect segment ends and ?E modules into it (emptied first); without, ?E
 * modules are not looked at. */
int syl_turtle_query(const SylProgram *p, SylString *s, SylEnvFill *env);

#endif
