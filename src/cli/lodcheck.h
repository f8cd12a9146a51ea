/* The silhouette error of a level of detail (sylva mesh --lod N --stats). */
#ifndef SYL_CLI_LODCHECK_H
#define SYL_CLI_LODCHECK_H
#include <stddef.h>

#include "sylva/lod.h"

typedef struct LodSilhouette {
    int pixels;            /* the square pictures' side */
    size_t covered, differ; /* pixels inside LOD0's silhouette; pixels inside one only */
    double percent;        /* differ / covered, in percent */
    double soft;           /* the sum of coverage differences over LOD0's coverage, percent */
} LodSilhouette;

/* Render LOD0 and LODk (k >= 1) as seen where LODk switches on and compare silhouettes
 * (coverage >= 1/2). SYL_OK or the renderer's status. */
int lod_silhouette(const SylLodChain *c, int k, int threads, LodSilhouette *out);

/* Every level rendered size x size by one camera (LOD0's), side by side, into a PNG. */
int lod_picture(const SylLodChain *c, const char *path, int size, int threads);

#endif
