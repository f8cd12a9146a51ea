/* Impostors: the plant baked by the renderer into texture atlases for the far distance
 * (docs/mesh.md, "Impostors and billboards"). An octahedral impostor holds grid x grid
 * views over the upper hemisphere; crossed billboards are 2 to 4 vertical quads, each face
 * textured with the side view it faces (Pafčo 2007). */
#ifndef SYLVA_IMPOSTOR_H
#define SYLVA_IMPOSTOR_H
#include <stdint.h>
#include <stdio.h>

#include "lod.h"
#include "mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct SylImpostorOptions {
    int grid;        /* views across the octahedral atlas; 0: 8; -1: no octahedral atlas */
    int view;        /* pixels per view; 0: 256 */
    int billboards;  /* quads of the crossed billboard, 2 to 4; 0: none */
    int threads;
    FILE *diag;
    const SylSink *sink; /* or as records to this sink instead (sylva.h); NULL: diag */
    SylBudget *budget; /* the bake's pictures and atlases are counted against it (NULL: none);
                          beyond it the bake stops with SYL_ELIMIT before it allocates */
} SylImpostorOptions;

typedef struct SylImpostor {
    int grid, view, size;      /* size = grid * view: the atlas's side */
    uint8_t *color;            /* size x size RGBA: the lit plant, alpha its coverage */
    uint8_t *normal;           /* size x size RGBA: world normal * 0.5 + 0.5, depth in A */
    float centre[3], radius;   /* the bounding sphere every view frames exactly */
    int billboards, bb_width;  /* the billboard atlas: 2 * billboards views in a row */
    uint8_t *bb_color;         /* bb_width x view RGBA */
    SylMesh *bb_mesh;          /* the quads (material 0 of m's table is replaced by none:
                                  one group of the material SYL_IMPOSTOR_MATERIAL) */
    struct SylImpostorStore *store; /* the library's own: the memory budget the atlases count
                                       against until syl_impostor_free (NULL: none) */
} SylImpostor;

enum { SYL_IMPOSTOR_MATERIAL = 255 };

/* The view direction (unit, from the plant toward the eye) of cell (col, row) of a grid x
 * grid hemi-octahedral atlas: e = 2 (cell + 0.5) / grid - 1, t = ((ex + ey) / 2,
 * (ex - ey) / 2), d = normalize(tx, 1 - |tx| - |ty|, ty) with Y up. */
void syl_impostor_direction(int grid, int col, int row, float d[3]);

int syl_impostor_bake(const SylMesh *m, const SylImpostorOptions *o, SylImpostor *out);
void syl_impostor_free(SylImpostor *imp);

/* Bake the impostor of c's LOD0 as it is drawn (instanced leaves meshed into it, as blades or
 * cards; sk and mo are what LOD0 was meshed from) with io, and make its crossed billboards
 * the chain's last level (which imp then owns; the chain's atlas is imp's). SYL_OK,
 * SYL_EMODEL (nothing drawn), SYL_ELIMIT, SYL_EUSAGE; reported to io's sink (else its diag). */
int syl_impostor_add_level(SylLodChain *c, const SylSkeleton *sk, const SylMeshOptions *mo, const SylImpostorOptions *io,
                           SylImpostor *imp);

#ifdef __cplusplus
}
#endif

#endif
