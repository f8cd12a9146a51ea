/* The crossed billboards of an impostor as the last level of a chain (sylva mesh --billboards,
 * --impostor; sylva view's far level). */
#ifndef SYL_CLI_BILLBOARD_H
#define SYL_CLI_BILLBOARD_H
#include <stdio.h>

#include "sylva/impostor.h"
#include "sylva/lod.h"

/* Bake the impostor of LOD0 as it is drawn (instanced leaves meshed into it, as blades or
 * cards) with io, and make its billboards the chain's last level (which imp then owns; the
 * chain's atlas is imp's). SYL_OK, SYL_EMODEL (nothing drawn), SYL_ELIMIT, SYL_EUSAGE;
 * reported on diag. */
int billboard_level(SylLodChain *c, const SylSkeleton *sk, const SylMeshOptions *mo, const SylImpostorOptions *io,
                    SylImpostor *imp, FILE *diag);

#endif
