/* libFuzzer harness: the ecosystem checkpoint reader (sylva ecosystem --resume) on arbitrary
 * bytes. A read that succeeds must give what the format promises: ids strictly increasing,
 * species and states in range, a year's counts for every year; and what the check of its
 * plants against a model and terrain (two species on 6 x 5 cells of 2 m, one without data)
 * takes must stand where the simulation puts plants. */
#include "fuzz.h"
#include "sylva/ecosystem.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    SylEcoCheckpoint c;
    if (syl_ecosystem_checkpoint_parse(data, size, "fuzz.ckpt", &c, fuzz_sink()) != SYL_OK) {
        if (c.plants || c.years) abort(); /* a failed read leaves nothing */
        return 0;
    }
    for (size_t j = 0; j < c.nplants; j++)
        if ((j && c.plants[j].id <= c.plants[j - 1].id) || c.plants[j].species >= SYL_ECO_MAX_SPECIES ||
            c.plants[j].state > SYL_ECO_DOMINATED)
            abort();
    for (int y = 0; y < c.year; y++)
        if (c.years[y].year != y + 1) abort();
    static SylEcoModel m;
    static float h[30];
    static uint8_t valid[30];
    SylTerrain t = {.nx = 6, .nz = 5, .cell = 2, .x0 = -3, .z0 = 1, .height = h, .valid = valid};
    if (!m.nspecies) {
        m.nspecies = 2;
        m.species[0].height_max = 30, m.species[0].max_age = 200;
        m.species[1].height_max = 1, m.species[1].max_age = 5;
        for (int k = 0; k < 30; k++) valid[k] = k != 7;
    }
    if (syl_ecosystem_checkpoint_check(&c, &m, &t, "fuzz.ckpt", fuzz_sink()) == SYL_OK)
        for (size_t j = 0; j < c.nplants; j++) {
            const SylEcoPlant *q = &c.plants[j];
            if (q->species >= m.nspecies || q->cell >= 30 || !valid[q->cell] ||
                q->height > m.species[q->species].height_max * (1 + 1e-6) || q->age > c.year)
                abort();
        }
    syl_ecosystem_checkpoint_free(&c);
    return 0;
}
