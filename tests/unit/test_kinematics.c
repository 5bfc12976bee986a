/* Kinematic level: lengths against hand-worked values and symmetry, rates and accelerations
 * against finite differences of the lengths. */
#include <math.h>

#include "platform_fixture.h"
#include "test_support.h"
#include "unity.h"

/* At home every leg spans a 30 degree chord of the 0.5 m circles and rises 0.5 m:
 * L^2 = (2 r sin 15deg)^2 + h^2. */
static void test_home_lengths_by_hand(void) {
    stewart_pose home = {{0, 0, 0.5, 0, 0, 0}, {0}, {0}};
    stewart_inverse_output out = solve_ok(data, STEWART_KINEMATIC, &home);
    const double chord = 2 * 0.5 * sin(15 * M_PI / 180);
    const double expected = sqrt(chord * chord + 0.25);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 0.563016250, expected); /* worked by hand */
    for (int k = 0; k < 6; ++k) {
        TEST_ASSERT_DOUBLE_WITHIN(1e-15, expected, out.lengths.length[k]);
        TEST_ASSERT_EQUAL_DOUBLE(0.0, out.lengths.length_rate[k]);
        TEST_ASSERT_EQUAL_DOUBLE(0.0, out.lengths.length_accel[k]);
    }
}

/* A translation along x alone: L_k^2 = (x + b_kx - a_kx)^2 + (b_ky - a_ky)^2 + z^2, by hand. */
static void test_translated_lengths_by_hand(void) {
    stewart_pose pose = {{0.07, 0, 0.45, 0, 0, 0}, {0}, {0}};
    stewart_inverse_output out = solve_ok(data, STEWART_KINEMATIC, &pose);
    for (int k = 0; k < 6; ++k) {
        const double dx =
            0.07 + 0.5 * cos(params.platform_angle[k]) - 0.5 * cos(params.base_angle[k]);
        const double dy = 0.5 * sin(params.platform_angle[k]) - 0.5 * sin(params.base_angle[k]);
        TEST_ASSERT_DOUBLE_WITHIN(1e-15, sqrt(dx * dx + dy * dy + 0.45 * 0.45),
                                  out.lengths.length[k]);
    }
}

/* Yaw keeps the threefold symmetry: legs 1, 3, 5 alike and legs 2, 4, 6 alike, in every output. */
static void test_yaw_manoeuvre_symmetry(void) {
    for (int i = 0; i <= 120; ++i) {
        stewart_pose pose = thesis_pose(5, 0.1 * i);
        stewart_inverse_output out = solve_ok(data, STEWART_MASSLESS, &pose);
        for (int k = 2; k < 6; ++k) {
            const int first = k % 2;
            TEST_ASSERT_DOUBLE_WITHIN(1e-14, out.lengths.length[first], out.lengths.length[k]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-13, out.lengths.length_rate[first],
                                      out.lengths.length_rate[k]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-12, out.lengths.length_accel[first],
                                      out.lengths.length_accel[k]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-9, out.force[first], out.force[k]);
        }
        /* and legs 1 and 2 mirror each other: yaw psi on one is -psi on the other. */
        stewart_pose mirrored = pose;
        mirrored.q[5] = -pose.q[5];
        stewart_inverse_output m = solve_ok(data, STEWART_KINEMATIC, &mirrored);
        TEST_ASSERT_DOUBLE_WITHIN(1e-14, out.lengths.length[0], m.lengths.length[1]);
    }
}

/* L_dot and L_ddot along the combined manoeuvre against central differences of L and L_dot. */
static void test_rates_match_finite_differences(void) {
    const double h = 1e-5;
    for (int i = 0; i < 50; ++i) {
        const double t = 0.173 * i;
        stewart_pose p0 = combined_pose(t), pm = combined_pose(t - h), pp = combined_pose(t + h);
        stewart_inverse_output o0 = solve_ok(data, STEWART_KINEMATIC, &p0);
        stewart_inverse_output om = solve_ok(data, STEWART_KINEMATIC, &pm);
        stewart_inverse_output op = solve_ok(data, STEWART_KINEMATIC, &pp);
        for (int k = 0; k < 6; ++k) {
            const double rate_fd = (op.lengths.length[k] - om.lengths.length[k]) / (2 * h);
            const double accel_fd =
                (op.lengths.length_rate[k] - om.lengths.length_rate[k]) / (2 * h);
            TEST_ASSERT_DOUBLE_WITHIN(1e-9, rate_fd, o0.lengths.length_rate[k]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-8, accel_fd, o0.lengths.length_accel[k]);
        }
    }
}

/* Stroke limits flag a warning without failing the solve. */
static void test_stroke_warning(void) {
    stewart_pose high = {{0, 0, 0.69, 0, 0, 0}, {0}, {0}};
    stewart_inverse_output out = solve_ok(data, STEWART_KINEMATIC, &high);
    TEST_ASSERT_TRUE(out.lengths.length[0] > params.stroke_max[0]);
    TEST_ASSERT_TRUE(out.warnings & STEWART_WARN_STROKE);
    stewart_pose home = {{0, 0, 0.5, 0, 0, 0}, {0}, {0}};
    out = solve_ok(data, STEWART_KINEMATIC, &home);
    TEST_ASSERT_EQUAL_INT(0, out.warnings);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_home_lengths_by_hand);
    RUN_TEST(test_translated_lengths_by_hand);
    RUN_TEST(test_yaw_manoeuvre_symmetry);
    RUN_TEST(test_rates_match_finite_differences);
    RUN_TEST(test_stroke_warning);
    return UNITY_END();
}
