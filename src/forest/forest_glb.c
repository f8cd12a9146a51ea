/* syl_forest_write_glb: a snapshot as a .glb — the terrain, and each look's instances split
 * into square cells, one node per cell and look, so a viewer can cull a cell at a time. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "forest/forest_internal.h"
#include "io/glb.h"

enum { MAX_SETS = 4096 };

int syl_forest_write_glb(const SylForest *f, const SylEcoPlant *plants, size_t n, double cell, const char *path,
                         const SylSink *sink) {
    const SylTerrain *t = f->t;
    double w = t->nx * t->cell, d = t->nz * t->cell;
    if (!(cell > 0)) cell = 250;
    int cx = (int)fmax(1, ceil(w / cell)), cz = (int)fmax(1, ceil(d / cell));
    while (f->nprotos * cx * cz > MAX_SETS) cell *= 2, cx = (int)fmax(1, ceil(w / cell)), cz = (int)fmax(1, ceil(d / cell));
    size_t nb = (size_t)(f->nprotos ? f->nprotos : 1) * (size_t)cx * (size_t)cz;
    SylRenderInstance *inst = malloc((n ? n : 1) * sizeof *inst);
    size_t *count = calloc(nb, sizeof *count), *start = calloc(nb + 1, sizeof *start);
    int *bucket = malloc((n ? n : 1) * sizeof *bucket);
    int st = inst && count && start && bucket ? SYL_OK : SYL_ELIMIT;
    SylInstances *sets = NULL;
    char **extras = NULL;
    float *t3 = NULL, *r4 = NULL, *s3 = NULL;
    int nsets = 0;
    if (!st) {
        syl_forest_instances(f, plants, n, inst);
        for (size_t i = 0; i < n; i++) { /* the cell of a plant on the edge is the last one */
            bucket[i] = -1;
            if (!(inst[i].scale > 0)) continue;
            const SylMesh *look = f->looks[inst[i].proto].mesh;
            if (!look || !look->nidx) continue; /* a look of nothing (a seedling's bare axiom) draws nothing */
            int i0 = (int)floor((inst[i].t[0] - t->x0) / cell), k0 = (int)floor((inst[i].t[2] - t->z0) / cell);
            i0 = i0 < 0 ? 0 : i0 >= cx ? cx - 1 : i0, k0 = k0 < 0 ? 0 : k0 >= cz ? cz - 1 : k0;
            bucket[i] = ((int)inst[i].proto * cz + k0) * cx + i0;
            count[bucket[i]]++;
        }
        for (size_t b = 0; b < nb; b++) start[b + 1] = start[b] + count[b], nsets += count[b] > 0;
        size_t total = start[nb];
        sets = calloc((size_t)nsets + 1, sizeof *sets);
        extras = calloc((size_t)nsets + 1, sizeof *extras);
        t3 = malloc((total + 1) * 3 * sizeof *t3), r4 = malloc((total + 1) * 4 * sizeof *r4);
        s3 = malloc((total + 1) * 3 * sizeof *s3);
        if (!sets || !extras || !t3 || !r4 || !s3) st = SYL_ELIMIT;
    }
    if (!st) {
        memset(count, 0, nb * sizeof *count);
        for (size_t i = 0; i < n; i++) { /* in the plants' order (by id) within each cell */
            if (bucket[i] < 0) continue;
            size_t j = start[bucket[i]] + count[bucket[i]]++;
            const SylRenderInstance *a = &inst[i];
            memcpy(t3 + 3 * j, a->t, 3 * sizeof *t3);
            float q[4] = {0, sinf(0.5f * a->yaw), 0, cosf(0.5f * a->yaw)}; /* about +y, as the renderer turns */
            memcpy(r4 + 4 * j, q, sizeof q);
            s3[3 * j] = s3[3 * j + 1] = s3[3 * j + 2] = a->scale;
        }
        int k = 0;
        for (size_t b = 0; b < nb && !st; b++) {
            if (!count[b]) continue;
            int p = (int)(b / ((size_t)cx * cz)), kz = (int)(b / cx % cz), ix = (int)(b % cx);
            const SylEcoSpecies *sp = &f->m->species[f->proto_species[p]];
            SylInstances *s = &sets[k];
            s->proto = f->looks[p].mesh;
            s->count = count[b];
            s->t = t3 + 3 * start[b], s->r = r4 + 4 * start[b], s->s = s3 + 3 * start[b];
            snprintf(s->name, sizeof s->name, "%.24s_class%d_v%d_cell%d_%d", sp->name, f->proto_class[p] % 10,
                     f->proto_variant[p] % 10, ix % 10000, kz % 10000);
            double x0 = t->x0 + ix * cell, z0 = t->z0 + kz * cell;
            double x1 = ix == cx - 1 ? t->x0 + w : x0 + cell, z1 = kz == cz - 1 ? t->z0 + d : z0 + cell;
            extras[k] = malloc(256);
            if (!extras[k]) {
                st = SYL_ELIMIT;
                break;
            }
            snprintf(extras[k], 256,
                     "{\"species\":\"%s\",\"class\":%d,\"variant\":%d,\"cell\":[%d,%d],\"bounds\":[%.3f,%.3f,%.3f,%.3f]}",
                     sp->name, f->proto_class[p], f->proto_variant[p], ix, kz, x0, z0, x1, z1);
            k++;
        }
    }
    if (!st) st = glb_write_forest(f->ground, sets, (const char *const *)extras, nsets, f->textures, path, sink);
    for (int i = 0; extras && i < nsets; i++) free(extras[i]);
    free(extras), free(sets), free(t3), free(r4), free(s3), free(inst), free(count), free(start), free(bucket);
    return st;
}
