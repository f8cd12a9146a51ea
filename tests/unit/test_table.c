/* The plant table plants-YEAR.csv (src/eco/table.c): what its one writer writes its reader
 * reads back as the same plants, x, z and height the same floats bit for bit (the same
 * picture from a saved snapshot); the writer's decimals are the fewest (at least 3) that
 * read back so, checked against strtof; a plant at the terrain's very edge is on it. */
#include <math.h>

#include "unit.h"
#include "sylva/ecosystem.h"

enum { N = 8 };
static float heights[N * N];

static SylTerrain terrain(void) {
    for (int c = 0; c < N * N; c++) heights[c] = (float)c / 8;
    SylTerrain t = {.nx = N, .nz = N, .cell = 12.5, .x0 = -40, .z0 = 1000, .height = heights};
    t.factor[SYL_TERRAIN_ALTITUDE] = heights;
    return t;
}

static const SylEcoModel *model(void) {
    static SylEcoModel m;
    m.nspecies = 2;
    strcpy(m.species[0].name, "oak"), m.species[0].radius_ratio = 0.3;
    strcpy(m.species[1].name, "hazel"), m.species[1].radius_ratio = 0.5;
    return &m;
}

/* xorshift: a fixed sequence of plants, no dependence on Sylva's generators */
static uint64_t next(uint64_t *s) {
    *s ^= *s << 13, *s ^= *s >> 7, *s ^= *s << 17;
    return *s;
}

static char *write_table(const SylEcoModel *m, const SylTerrain *t, const SylEcoPlant *p, size_t n, size_t *len) {
    char *text = NULL;
    FILE *f = open_memstream(&text, len);
    assert_non_null(f);
    fprintf(f, "%s\n", syl_ecosystem_table_header);
    for (size_t j = 0; j < n; j++) syl_ecosystem_table_write_row(f, m, t, &p[j]);
    fclose(f);
    return text;
}

static void floats_round_trip(void **state) {
    (void)state;
    SylTerrain t = terrain();
    const SylEcoModel *m = model();
    enum { COUNT = 20000 };
    static SylEcoPlant in[COUNT];
    uint64_t s = 0x9e3779b97f4a7c15ull;
    double x1 = t.x0 + N * t.cell, z1 = t.z0 + N * t.cell;
    for (size_t j = 0; j < COUNT; j++) {
        /* uniform in the terrain, and every 7th plant at an edge or a float's neighbour of one */
        float x = (float)(t.x0 + (x1 - t.x0) * (double)(next(&s) >> 11) / 9007199254740992.0);
        float z = (float)(t.z0 + (z1 - t.z0) * (double)(next(&s) >> 11) / 9007199254740992.0);
        if (j % 7 == 3) x = (float)t.x0, z = nextafterf((float)z1, 0);
        if (j % 7 == 5) x = (float)x1, z = nextafterf((float)t.z0, 2000);
        /* heights over 14 orders of magnitude: seedlings of a micrometre to 100 m trees */
        float h = (float)ldexp((double)(next(&s) >> 40) / 16777216.0, (int)(next(&s) % 48) - 40);
        in[j] = (SylEcoPlant){.id = 1 + 3 * (uint64_t)j + (next(&s) & 1), .x = x, .z = z, .height = h,
                              .vigour = (float)(next(&s) % 10001) / 10000, .age = (uint16_t)(next(&s) % 500),
                              .species = (uint8_t)(j % 2), .state = (uint8_t)(next(&s) & 1)};
    }
    size_t len;
    char *text = write_table(m, &t, in, COUNT, &len);
    SylEcoPlant *out = NULL;
    size_t n = 0;
    assert_int_equal(syl_ecosystem_table_parse(text, len, "t.csv", m, &t, &out, &n, &(SylSink){syl_diagnostic_print, stderr}), SYL_OK);
    assert_int_equal(n, COUNT);
    for (size_t j = 0; j < COUNT; j++) {
        assert_true(out[j].id == in[j].id);
        assert_memory_equal(&out[j].x, &in[j].x, sizeof(float)); /* bit for bit */
        assert_memory_equal(&out[j].z, &in[j].z, sizeof(float));
        assert_memory_equal(&out[j].height, &in[j].height, sizeof(float));
        assert_int_equal(out[j].age, in[j].age);
        assert_int_equal(out[j].species, in[j].species);
        assert_int_equal(out[j].state, in[j].state);
        assert_true(fabsf(out[j].vigour - in[j].vigour) <= 0.00005f); /* 4 decimals */
        assert_true(out[j].cell < N * N);
    }
    free(out);
    free(text);
}

/* The fields as written: fewest decimals from 3 that strtof reads back as the float. */
static void fewest_decimals(void **state) {
    (void)state;
    SylTerrain t = terrain();
    const SylEcoModel *m = model();
    /* 0.1f: 3 decimals; 1000 + 1/3: as many as its spacing (2^-14) takes, checked below
     * against one fewer; 1e-7f: 7 (0.0000001), where %.3f would write 0.000 */
    SylEcoPlant p = {.id = 0xabc, .x = 0.1f, .z = 1000 + 1.0f / 3, .height = 1e-7f, .vigour = 0.25f, .age = 7,
                     .species = 1, .state = SYL_ECO_DOMINATED};
    char *text = NULL;
    size_t len;
    FILE *f = open_memstream(&text, &len);
    syl_ecosystem_table_write_row(f, m, &t, &p);
    fclose(f);
    char x[32], z[32], h[32];
    assert_int_equal(sscanf(text, "0000000000000abc,hazel,%31[^,],%*[^,],%31[^,],7,%31[^,],", x, z, h), 3);
    assert_string_equal(x, "0.100");
    assert_true(strtof(z, NULL) == p.z);
    char fewer[32];
    const char *dot = strchr(z, '.');
    assert_non_null(dot);
    int decimals = (int)strlen(dot + 1);
    assert_true(decimals >= 3);
    if (decimals > 3) { /* one decimal fewer does not read back */
        snprintf(fewer, sizeof fewer, "%.*f", decimals - 1, (double)p.z);
        assert_true(strtof(fewer, NULL) != p.z);
    }
    assert_string_equal(h, "0.0000001");
    assert_true(strstr(text, ",0.2500,dominated\n") != NULL);
    free(text);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(floats_round_trip),
        cmocka_unit_test(fewest_decimals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
