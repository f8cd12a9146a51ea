/* libFuzzer harness: the ecosystem checkpoint reader (sylva ecosystem --resume) on arbitrary
 * bytes. A read that succeeds must give what the format promises: ids strictly increasing,
 * species and states in range, a year's counts for every year. */
#include "fuzz.h"
#include "sylva/ecosystem.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    SylEcoCheckpoint c;
    if (syl_ecosystem_checkpoint_parse(data, size, "fuzz.ckpt", &c, fuzz_diag()) != SYL_OK) {
        if (c.plants || c.years) abort(); /* a failed read leaves nothing */
        return 0;
    }
    for (size_t j = 0; j < c.nplants; j++)
        if ((j && c.plants[j].id <= c.plants[j - 1].id) || c.plants[j].species >= SYL_ECO_MAX_SPECIES ||
            c.plants[j].state > SYL_ECO_DOMINATED)
            abort();
    for (int y = 0; y < c.year; y++)
        if (c.years[y].year != y + 1) abort();
    syl_ecosystem_checkpoint_free(&c);
    return 0;
}
