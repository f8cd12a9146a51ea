/* libFuzzer harness: the plant table reader (plants-YEAR.csv, sylva render --plants) on
 * arbitrary bytes, for a model of two species (one whose name CSV quotes) on a 12 x 12 terrain of 2 m cells at (-6, 4).
 * A table that reads must hold what the reader promises (ids increasing, species known,
 * positions on the terrain, cells in the grid), and written back by the one writer it must
 * read again as the same plants and write the same text (x, z and height round-trip). */
#include <math.h>

#include "fuzz.h"
#include "sylva/ecosystem.h"

enum { N = 12 };

static char *write_table(const SylEcoModel *m, const SylTerrain *t, const SylEcoPlant *p, size_t n, size_t *len) {
    char *text = NULL;
    FILE *f = open_memstream(&text, len);
    if (!f) abort();
    fprintf(f, "%s\n", syl_ecosystem_table_header);
    for (size_t j = 0; j < n; j++) syl_ecosystem_table_write_row(f, m, t, &p[j]);
    fclose(f);
    return text;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    static SylEcoModel m;
    static float h[N * N];
    static uint8_t valid[N * N];
    SylTerrain t = {.nx = N, .nz = N, .cell = 2, .x0 = -6, .z0 = 4, .height = h, .valid = valid};
    if (!m.nspecies) {
        m.nspecies = 2;
        strcpy(m.species[0].name, "tall"), m.species[0].radius_ratio = 0.3;
        strcpy(m.species[1].name, "short, \"x\""), m.species[1].radius_ratio = 0.4; /* written quoted */
        for (int c = 0; c < N * N; c++) h[c] = (float)(c % N) * 0.5f + (float)(c / N), valid[c] = 1;
    }
    t.factor[SYL_TERRAIN_ALTITUDE] = h;
    SylEcoPlant *p = NULL, *q = NULL;
    size_t n = 0, nq = 0;
    if (syl_ecosystem_table_parse((const char *)data, size, "fuzz.csv", &m, &t, &p, &n, fuzz_sink()) != SYL_OK) {
        if (p || n) abort(); /* a failed read leaves nothing */
        return 0;
    }
    for (size_t j = 0; j < n; j++)
        if ((j && p[j].id <= p[j - 1].id) || p[j].species >= m.nspecies || p[j].state > SYL_ECO_DOMINATED ||
            !(p[j].x >= t.x0 && p[j].x <= t.x0 + N * t.cell) || !(p[j].z >= t.z0 && p[j].z <= t.z0 + N * t.cell) ||
            p[j].cell >= N * N || !isfinite(p[j].height) || p[j].height < 0)
            abort();
    size_t len1, len2;
    char *one = write_table(&m, &t, p, n, &len1);
    if (syl_ecosystem_table_parse(one, len1, "again.csv", &m, &t, &q, &nq, fuzz_sink()) != SYL_OK || nq != n) abort();
    for (size_t j = 0; j < n; j++)
        if (q[j].id != p[j].id || q[j].species != p[j].species || q[j].x != p[j].x || q[j].z != p[j].z ||
            q[j].height != p[j].height || q[j].age != p[j].age || q[j].state != p[j].state || q[j].cell != p[j].cell)
            abort();
    char *two = write_table(&m, &t, q, nq, &len2);
    if (len1 != len2 || memcmp(one, two, len1)) abort(); /* vigour's 4 decimals are stable too */
    free(one), free(two), free(p), free(q);
    return 0;
}
