/* The silhouette error of a level of detail (sylva mesh --lod N --stats). */
#ifndef SYL_CLI_LODCHECK_H
#define SYL_CLI_LODCHECK_H
#include <stddef.h>

#include "sylva/lod.h"

typedef struct LodSilhouette {
    int pixels;            /* the square pictures' side */
    size_t covered, differ; /* pixels inside LOD0's silhouette; pixels inside one only */
    double percent;        /* differ / covered, in percent */
} LodSilhouette;

/* Render LOD0 and LODk (k >= 1) as seen where LODk switches on and compare silhouettes
 * (coverage >= 1/2). SYL_OK or the renderer's status. */
int lod_silhouette(const SylLodChain *c, int k, int threads, LodSilhouette *out);

#endif
