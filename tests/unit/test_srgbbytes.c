/* srgb_byte, the table syl_texture_draw converts texels with, is the formula it stands for
 * (lrintf(255 * linear_to_srgb(v))) byte for byte: every 61st float of [0, 1], every float
 * within 4096 of each of the 255 steps, the edges (0, -0, 1, past 1, negative, NaN,
 * infinities, denormals); and the steps themselves are where the formula's byte changes. */
#include <math.h>

#include "unit.h"

#include "texture/srgbbytes.h"

static float of_bits(uint32_t u) {
    float v;
    memcpy(&v, &u, sizeof v);
    return v;
}

static void check(const SrgbBytes *t, uint32_t u) {
    float v = of_bits(u);
    uint8_t want = srgb_byte_exact(v), got = srgb_byte(t, v);
    if (want != got) fail_msg("%a (bits %08x): the formula says %d, the table %d", (double)v, u, want, got);
}

static void table_is_the_formula(void **state) {
    (void)state;
    SrgbBytes *t = malloc(sizeof *t);
    assert_non_null(t);
    srgb_bytes_init(t);
    for (uint32_t u = 0; u <= 0x3f800000u; u += 61) check(t, u);
    for (int b = 1; b < 256; b++) {
        assert_true(t->at[b] > t->at[b - 1]); /* increasing */
        assert_true(srgb_byte_exact(of_bits(t->at[b])) >= b);
        assert_true(srgb_byte_exact(of_bits(t->at[b] - 1)) < b);
        for (uint32_t u = t->at[b] - 4096; u <= t->at[b] + 4096; u++) check(t, u);
    }
    static const float edges[] = {0.0f, -0.0f, 1.0f, 1.5f, -0.25f, NAN, INFINITY, -INFINITY, 1e-45f, 1e-38f, 0.0031308f,
                                  0.99999994f, 0.5f};
    for (size_t i = 0; i < sizeof edges / sizeof *edges; i++) {
        uint32_t u;
        memcpy(&u, &edges[i], sizeof u);
        check(t, u);
    }
    free(t);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(table_is_the_formula),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
