/* A checkpoint is taken only as a state the simulation could have made
 * (syl_ecosystem_checkpoint_check): a whole file with a valid checksum may still hold a plant
 * taller than its species allows, off the terrain, on a cell without data or filed under
 * another cell, which the tiles would then treat differently (issue 26, item 12). */
#include "unit.h"
#include "sylva/ecosystem.h"

enum { NX = 4, NZ = 3 };

typedef struct Fixture {
    SylEcoModel m;
    SylTerrain t;
    float h[NX * NZ];
    uint8_t valid[NX * NZ];
    SylEcoPlant p[2];
    SylEcoCheckpoint c;
} Fixture;

/* two species on a 4 x 3 grid of 2 m cells from (10, -4); cell (3, 2) has no data */
static void fixture(Fixture *f) {
    memset(f, 0, sizeof *f);
    f->m.nspecies = 2;
    f->m.species[0].height_max = 20, f->m.species[0].max_age = 150;
    f->m.species[1].height_max = 2, f->m.species[1].max_age = 10;
    for (int c = 0; c < NX * NZ; c++) f->valid[c] = c != 2 * NX + 3;
    f->t = (SylTerrain){.nx = NX, .nz = NZ, .cell = 2, .x0 = 10, .z0 = -4, .height = f->h, .valid = f->valid};
    /* (11, -3): cell (0, 0); (15.5, -0.5): cell (2, 1) */
    f->p[0] = (SylEcoPlant){.id = 1, .x = 11, .z = -3, .height = 20, .age = 5, .species = 0, .cell = 0};
    f->p[1] = (SylEcoPlant){.id = 2, .x = 15.5f, .z = -0.5f, .height = 1.5f, .age = 10, .species = 1, .cell = NX + 2};
    f->c = (SylEcoCheckpoint){.year = 12, .plants = f->p, .nplants = 2};
}

static int check(Fixture *f) { return syl_ecosystem_checkpoint_check(&f->c, &f->m, &f->t, "t", NULL); }

static void as_made_is_taken(void **state) {
    (void)state;
    Fixture f;
    fixture(&f);
    assert_int_equal(check(&f), SYL_OK); /* at height_max and max_age exactly: still made so */
}

static void each_departure_is_refused(void **state) {
    (void)state;
    Fixture f;
    fixture(&f), f.p[1].height = 2.5f; /* taller than height_max 2 */
    assert_int_equal(check(&f), SYL_EMODEL);
    fixture(&f), f.p[0].x = 18.5f; /* beyond x0 + 4 cells */
    assert_int_equal(check(&f), SYL_EMODEL);
    fixture(&f), f.p[0].z = -4.5f;
    assert_int_equal(check(&f), SYL_EMODEL);
    fixture(&f), f.p[1].x = 17, f.p[1].z = 1, f.p[1].cell = 2 * NX + 3; /* the cell without data */
    assert_int_equal(check(&f), SYL_EMODEL);
    fixture(&f), f.p[1].cell = 0; /* filed under another cell than it stands on */
    assert_int_equal(check(&f), SYL_EMODEL);
    fixture(&f), f.p[0].species = 2; /* the block has two */
    assert_int_equal(check(&f), SYL_EMODEL);
    fixture(&f), f.p[1].age = 11; /* beyond max_age 10 */
    assert_int_equal(check(&f), SYL_EMODEL);
    fixture(&f), f.c.year = 4; /* a plant of 5 years in year 4 */
    assert_int_equal(check(&f), SYL_EMODEL);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(as_made_is_taken),
        cmocka_unit_test(each_departure_is_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
