/*
 * The plant FMU follows the master's clock: long runs (20 s at 1 ms and 0.1 ms, from t0 = 0 and
 * 100 s, FMI 2 and FMI 3) with the communication point counted (t0 + n h, as fmpy and Maestro
 * compute it) or summed (t += h) are accepted at every step, and the motion is the closed form of
 * uniform motion; a gap beyond the rounding of a clock is still an Error.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "plant_fmu_unit.h"
#include "stewart/stewart.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

/* A free platform (no gravity, no forces, massless legs) translating at constant velocity from
 * t0 for `seconds` at steps of h, the master's clock counted (t = t0 + n h, as fmpy and Maestro
 * compute it) or summed (t += h): every step OK, lastSuccessfulTime the master's t + h, and the
 * pose the closed form of uniform motion. The unit follows the master's clock within rounding,
 * so neither clock's rounding adds up over a run. */
static void free_run(int v3, double t0, double h, double seconds, int counted) {
    const double zero[6] = {0}, velocity[3] = {1e-3, -5e-4, 2e-4};
    const unsigned vr[6] = {VR_gravity_1, VR_gravity_2, VR_gravity_3,
                            VR_x_dot0,    VR_y_dot0,    VR_z_dot0};
    const double value[6] = {0, 0, 0, velocity[0], velocity[1], velocity[2]};
    unit u;
    TEST_ASSERT_TRUE_MESSAGE(unit_open_at(&u, v3, STEWART_MASSLESS, zero, t0, 6, vr, value),
                             u.log.last);
    const long n = lround(seconds / h);
    double t = t0, last = -1;
    for (long i = 0; i < n; ++i) {
        if (counted) t = t0 + (double)i * h;
        const int s = do_step(&u, t, h, &last);
        if (s != fmi2OK) {
            printf("FMI %d, t0 = %g, h = %g, %s clock: step %ld at t = %.17g returned %d\n",
                   v3 ? 3 : 2, t0, h, counted ? "counted" : "summed", i, t, s);
            TEST_FAIL_MESSAGE(u.log.last);
        }
        TEST_ASSERT_EQUAL_DOUBLE(t + h, last);
        if (!counted) t += h;
    }
    const snapshot s = outputs(&u);
    stewart_params params;
    stewart_params_default(&params);
    const double elapsed = (double)n * h;
    const double expected[3] = {velocity[0] * elapsed, velocity[1] * elapsed,
                                params.home_height + velocity[2] * elapsed};
    double error = 0;
    for (int c = 0; c < 3; ++c) error = fmax(error, fabs(s.real[c] - expected[c]));
    printf("FMI %d, t0 = %g s, h = %g s, %s clock: %ld steps OK, position %.3g m off uniform "
           "motion\n",
           v3 ? 3 : 2, t0, h, counted ? "t0 + n h" : "t += h", n, error);
    TEST_ASSERT_TRUE(error <= 1e-9);
    unit_free(&u);
}

/* Every combination: FMI 2 and 3, t0 = 0 and 100 s, 1 ms and 0.1 ms, both clocks, 20 s each. */
static void test_long_runs_follow_the_masters_clock(void) {
    const double starts[2] = {0.0, 100.0}, steps[2] = {1e-3, 1e-4};
    for (int v3 = 0; v3 < 2; ++v3)
        for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b)
                for (int counted = 1; counted >= 0; --counted)
                    free_run(v3, starts[a], steps[b], 20.0, counted);
}

/* A real gap, however small beyond the rounding of a clock, is still an Error: 1e-12 s after
 * 100 s (45 units in the last place of t). */
static void test_a_gap_beyond_rounding_is_an_error(void) {
    for (int v3 = 0; v3 < 2; ++v3) {
        double statics[6], last;
        static_forces(STEWART_FULL, statics);
        unit u;
        TEST_ASSERT_TRUE_MESSAGE(unit_open_at(&u, v3, STEWART_FULL, statics, 100.0, 0, NULL, NULL),
                                 u.log.last);
        TEST_ASSERT_EQUAL_MESSAGE(fmi2OK, do_step(&u, 100.0, STEP, &last), u.log.last);
        TEST_ASSERT_EQUAL(fmi2Error, do_step(&u, 100.0 + STEP + 1e-12, STEP, &last));
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(u.log.last, "cannot skip time"), u.log.last);
        unit_free(&u);
    }
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_long_runs_follow_the_masters_clock);
    RUN_TEST(test_a_gap_beyond_rounding_is_an_error);
    return UNITY_END();
}
