/* The turtle's query pass for the scene layer's environments (scene/open.c); syl_turtle_query is
 * public (sylva/skeleton.h). */
#ifndef SYL_TURTLE_H
#define SYL_TURTLE_H
#include "sylva/sylva.h"

#include "sylva/skeleton.h"

/* A light probe (?E(0, q)) as scene/open.c keeps it: 16 bytes, not a SylEnvProbe's 40. */
typedef struct SylLightProbe {
    float pos[3];
    uint32_t par; /* offset of the module's parameters (below 2^31); top bit: at a segment's end */
} SylLightProbe;
#define SYL_LIGHT_TIP ((uint32_t)1 << 31)

/* What scene/open.c reads of the ?E modules, collected by syl_turtle_fill (emptied first). */
typedef struct SylOpenFill {
    SylLightProbe *light; /* ?E(0, q, ...) */
    size_t nlight, light_cap;
    unsigned kinds; /* bit k: a module asks kind k = 0..3 (its first parameter; 0 without) */
} SylOpenFill;

/* syl_turtle_query for scene/open.c's answers: light probes go to open, the ?E modules of
 * kinds 1 to 3 (with two parameters or more) to env, with their heading; modules it would
 * not answer are only counted in open->kinds. Ends are collected in env as always. */
int syl_turtle_fill(const SylProgram *p, SylString *s, SylEnvFill *env, SylOpenFill *open);

#endif
