/* An embedding program in C, built against an installed Sylva with pkg-config by
 * tests/run-embed. It has a bison parser of its own: its yyparse and yylex must not replace
 * Sylva's (before the syl_yy prefix, syl_compile then said "this file holds no lsystem").
 *   plant MODEL.syl   prints "modules N", "F N", "nodes N", "internodes N", "triangles N"
 * and checks what it can know by itself; exit 1 on any failed check. */
#include <stdio.h>
#include <stdlib.h>

#include <sylva/mesh.h>
#include <sylva/plant.h>
#include <sylva/skeleton.h>
#include <sylva/sylva.h>

int yylex(void) { return 0; }
int yyparse(void) { return 42 + yylex(); } /* the program's own parser */

static int failures;
#define CHECK(cond)                                                                      \
    do {                                                                                 \
        if (!(cond)) {                                                                   \
            fprintf(stderr, "plant.c:%d: check failed: %s\n", __LINE__, #cond);          \
            failures++;                                                                  \
        }                                                                                \
    } while (0)

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s MODEL.syl\n", argv[0]);
        return 2;
    }
    CHECK(yyparse() == 42); /* ours, not Sylva's */
    int st;
    SylProgram *p = syl_compile(argv[1], NULL, 0, &(SylCompileOptions){.diag = stderr}, &st);
    if (!p) return st;
    SylPlant pl;
    st = syl_plant_build(p, &(SylPlantOptions){.diag = stderr}, &pl);
    if (st) return st;
    CHECK(pl.kind == SYL_MODEL_LSYSTEM);
    CHECK(pl.string && pl.skeleton && pl.mesh);
    CHECK(pl.modules == syl_string_length(pl.string));
    /* every F draws one segment: one internode node each */
    int F = syl_program_symbol_find(p, "F");
    size_t nF = 0, internodes = 0;
    for (size_t i = 0; i < pl.modules; i++) nF += syl_string_module(pl.string, i, NULL, NULL) == F;
    CHECK(syl_string_module(pl.string, pl.modules, NULL, NULL) == -1); /* past the end */
    for (size_t i = 0; i < pl.skeleton->nnodes; i++) internodes += pl.skeleton->nodes[i].kind == SYL_KIND_INTERNODE;
    CHECK(internodes == nF);
    /* a mesh of triangles whose indices name real vertices */
    const SylMesh *m = pl.mesh;
    CHECK(m->nidx > 0 && m->nidx % 3 == 0);
    size_t bad = 0;
    for (size_t i = 0; i < m->nidx; i++) bad += m->idx[i] >= m->nverts;
    CHECK(bad == 0);
    printf("modules %zu\nF %zu\nnodes %zu\ninternodes %zu\ntriangles %zu\n", pl.modules, nF,
           pl.skeleton->nnodes, internodes, m->nidx / 3);
    syl_plant_free(&pl);
    CHECK(!pl.mesh && !pl.skeleton && !pl.string);
    syl_plant_free(&pl); /* twice is harmless: it zeroed the struct */
    syl_program_free(p);
    return failures ? 1 : 0;
}
