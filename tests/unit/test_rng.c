/* Random streams: keyed, reproducible, uniform. */
#include "unit.h"
#include "util/rng.h"

static void same_key_same_draws(void **state) {
    (void)state;
    Rng a = rng_stream(42, 3, 0, 17), b = rng_stream(42, 3, 0, 17);
    for (int i = 0; i < 100; i++) assert_int_equal(rng_next(&a), rng_next(&b));
}

static void keys_differ(void **state) {
    (void)state;
    uint64_t first[4] = {
        rng_next(&(Rng){rng_stream(1, 1, 0, 1).key, 0}), rng_next(&(Rng){rng_stream(2, 1, 0, 1).key, 0}),
        rng_next(&(Rng){rng_stream(1, 2, 0, 1).key, 0}), rng_next(&(Rng){rng_stream(1, 1, 0, 2).key, 0})};
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < i; j++) assert_true(first[i] != first[j]);
}

static void unit_interval_is_uniform(void **state) {
    (void)state;
    int bins[10] = {0};
    const int n = 100000;
    for (int pos = 0; pos < n; pos++) {
        Rng r = rng_stream(7, 1, 0, (uint64_t)pos);
        double u = rng_unit(&r);
        assert_true(u >= 0 && u < 1);
        bins[(int)(u * 10)]++;
    }
    /* each bin expects 10000 with sd ~95: 5 sd is a failure */
    for (int i = 0; i < 10; i++) assert_in_range(bins[i], 10000 - 475, 10000 + 475);
}

static void normal_has_unit_variance(void **state) {
    (void)state;
    double sum = 0, sq = 0;
    const int n = 200000;
    Rng r = rng_stream(9, 0, 0, 0);
    for (int i = 0; i < n; i++) {
        double x = rng_normal(&r);
        sum += x;
        sq += x * x;
    }
    double mean = sum / n, var = sq / n - mean * mean;
    assert_true(mean > -0.01 && mean < 0.01);
    assert_true(var > 0.98 && var < 1.02);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(same_key_same_draws),
        cmocka_unit_test(keys_differ),
        cmocka_unit_test(unit_interval_is_uniform),
        cmocka_unit_test(normal_has_unit_variance),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
