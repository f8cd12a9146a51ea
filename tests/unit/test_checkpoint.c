/* Ecosystem checkpoints (src/eco/checkpoint.c) and the tiles' cut over ranks (balance.c):
 * a state written and read back is the same state; every truncation and every changed byte
 * of a checkpoint is refused; the cut gives each rank a contiguous run of tiles whose plants
 * differ from an equal share by less than one tile's. */
#include <unistd.h>

#include "unit.h"
#include "eco/eco.h"
#include "sylva/ecosystem.h"

static SylEcoCheckpoint sample(void) {
    static SylEcoYear years[3];
    static SylEcoPlant plants[4];
    for (int y = 0; y < 3; y++) {
        years[y] = (SylEcoYear){.year = y + 1};
        years[y].count[0] = (uint32_t)(10 * y + 1);
        years[y].cover[1] = 0.25 * y;
        years[y].mean_height[0] = 1.5 + y;
    }
    for (int j = 0; j < 4; j++)
        plants[j] = (SylEcoPlant){.id = 100 + 7 * (uint64_t)j, .x = 3.5f * j, .z = 1.25f, .height = 2 + j, .vigour = 0.5f,
                                  .age = (uint16_t)j, .species = (uint8_t)(j % 2), .state = (uint8_t)(j == 3)};
    return (SylEcoCheckpoint){.model_hash = 0x1234abcdull, .year = 3, .years = years, .plants = plants, .nplants = 4};
}

static uint8_t *write_sample(size_t *len) {
    char path[] = "/tmp/test_checkpoint.XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    SylEcoCheckpoint c = sample();
    assert_int_equal(syl_ecosystem_checkpoint_write(path, &c, &(SylSink){syl_diagnostic_print, stderr}), SYL_OK);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    static uint8_t buf[8192];
    *len = fread(buf, 1, sizeof buf, f);
    fclose(f);
    unlink(path);
    return buf;
}

static void round_trip(void **state) {
    (void)state;
    size_t len;
    uint8_t *b = write_sample(&len);
    SylEcoCheckpoint in = sample(), out;
    /* 64-byte header, 3 years of 644 bytes, 4 plants, 8 bytes of checksum */
    assert_int_equal(len, 64 + 3 * 644 + 4 * sizeof(SylEcoPlant) + 8);
    assert_int_equal(syl_ecosystem_checkpoint_parse(b, len, "t", &out, NULL), SYL_OK);
    assert_int_equal(out.year, 3);
    assert_true(out.model_hash == in.model_hash);
    assert_int_equal(out.nplants, 4);
    assert_memory_equal(out.plants, in.plants, 4 * sizeof *in.plants);
    for (int y = 0; y < 3; y++) {
        assert_int_equal(out.years[y].year, y + 1);
        assert_int_equal(out.years[y].count[0], in.years[y].count[0]);
        assert_true(out.years[y].cover[1] == in.years[y].cover[1]);
        assert_true(out.years[y].mean_height[0] == in.years[y].mean_height[0]);
    }
    syl_ecosystem_checkpoint_free(&out);
}

static void damage_is_refused(void **state) {
    (void)state;
    size_t len;
    uint8_t *b = write_sample(&len);
    SylEcoCheckpoint out;
    for (size_t n = 0; n < len; n++) { /* every truncation */
        assert_int_equal(syl_ecosystem_checkpoint_parse(b, n, "t", &out, NULL), SYL_EMODEL);
        assert_null(out.plants);
    }
    for (size_t i = 0; i < len; i++) { /* every byte changed */
        b[i] ^= 0x10;
        assert_int_equal(syl_ecosystem_checkpoint_parse(b, len, "t", &out, NULL), SYL_EMODEL);
        b[i] ^= 0x10;
    }
    assert_int_equal(syl_ecosystem_checkpoint_parse(b, len, "t", &out, NULL), SYL_OK);
    syl_ecosystem_checkpoint_free(&out);
}

static void cut_is_balanced(void **state) {
    (void)state;
    enum { T = 40 };
    int64_t plants[T];
    int owner[T];
    for (int seed = 1; seed <= 50; seed++)
        for (int ranks = 1; ranks <= 7; ranks++) {
            uint64_t x = (uint64_t)seed * 0x9e3779b97f4a7c15ull;
            int64_t total = 0, biggest = 0;
            for (int t = 0; t < T; t++) {
                x ^= x >> 12, x ^= x << 25, x ^= x >> 27;
                plants[t] = (int64_t)((x * 2685821657736338717ull) >> 54) * (t % 5 == 0); /* lumpy */
                total += plants[t] + 1;
                if (plants[t] + 1 > biggest) biggest = plants[t] + 1;
            }
            eco_balance_cut(plants, T, ranks, owner);
            int64_t share[8] = {0};
            for (int t = 0; t < T; t++) {
                assert_in_range(owner[t], 0, ranks - 1);
                if (t) assert_true(owner[t] >= owner[t - 1]); /* contiguous runs */
                share[owner[t]] += plants[t] + 1;
            }
            for (int r = 0; r < ranks; r++) { /* within one tile (and a half) of an equal share */
                double d = (double)share[r] - (double)total / ranks;
                assert_true(d <= 1.5 * biggest && d >= -1.5 * biggest);
            }
        }
    eco_balance_cut(NULL, 8, 4, owner); /* bare ground: two tiles each */
    for (int t = 0; t < 8; t++) assert_int_equal(owner[t], t / 2);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(round_trip),
        cmocka_unit_test(damage_is_refused),
        cmocka_unit_test(cut_is_balanced),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
