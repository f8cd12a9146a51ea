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
/* A light probe (?E(0, q)) as env/open.c keeps it: 16 bytes, not a SylEnvProbe's 40. */
typedef struct SylLightProbe {
    float pos[3];
    uint32_t par; /* offset of the module's parameters (below 2^31); top bit: at a segment's end */
} SylLightProbe;
#define SYL_LIGHT_TIP ((uint32_t)1 << 31)

/* What env/open.c reads of the ?E modules, collected by syl_turtle_fill (emptied first). */
typedef struct SylOpenFill {
    SylLightProbe *light; /* ?E(0, q, ...) */
    size_t nlight, light_cap;
    unsigned kinds; /* bit k: a module asks kind k = 0..3 (its first parameter; 0 without) */
} SylOpenFill;

/* syl_turtle_query for env/open.c's answers: light probes go to open, the ?E modules of
 * kinds 1 to 3 (with two parameters or more) to env, with their heading; modules it would
 * not answer are only counted in open->kinds. Ends are collected in env as always. */
int syl_turtle_fill(const SylProgram *p, SylString *s, SylEnvFill *env, SylOpenFill *open);

#endif
