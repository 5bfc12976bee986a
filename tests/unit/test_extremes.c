/* The closed-form levels at the edges: near the yaw singularity of the thesis geometry, at the
 * stroke limits, and with parameters scaled far from the thesis platform. */
#include <math.h>
#include <string.h>

#include "platform_fixture.h"
#include "test_support.h"
#include "unity.h"

static stewart_pose yawed(double yaw) {
    stewart_pose p = {{0, 0, 0.5, 0, 0, yaw}, {0}, {0}};
    return p;
}

/* Toward yaw = 90 deg the leg Jacobian loses rank linearly in the distance e to the singular pose,
 * so the static forces grow as 1/e: F(e) e tends to a constant. The condition number grows
 * monotonically, the warning comes on, and the singular pose itself is an error, not Inf. */
static void test_yaw_singularity_sweep(void) {
    double previous_condition = 0, scaled[4];
    const double distance[4] = {1e-1, 1e-2, 1e-3, 1e-4}; /* rad from 90 deg */
    for (int i = 0; i < 4; ++i) {
        stewart_pose p = yawed(M_PI / 2 - distance[i]);
        stewart_inverse_output out = solve_ok(data, STEWART_MASSLESS, &p);
        TEST_ASSERT_TRUE(out.condition > previous_condition);
        previous_condition = out.condition;
        double largest = 0;
        for (int k = 0; k < 6; ++k) largest = fmax(largest, fabs(out.force[k]));
        scaled[i] = largest * distance[i];
        if (out.condition > 1e3) TEST_ASSERT_TRUE(out.warnings & STEWART_WARN_NEAR_SINGULAR);
    }
    TEST_ASSERT_DOUBLE_WITHIN(0.01 * scaled[3], scaled[3], scaled[2]);
    TEST_ASSERT_DOUBLE_WITHIN(0.1 * scaled[3], scaled[3], scaled[1]);
    TEST_ASSERT_TRUE(previous_condition > 1e4);

    stewart_pose singular = yawed(M_PI / 2);
    stewart_inverse_options o = test_options(STEWART_MASSLESS);
    stewart_inverse_output out;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_SINGULAR, solve_as(data, &o, &singular, &out));
    /* and the next pose is solved as if nothing happened */
    stewart_pose home = yawed(0);
    stewart_inverse_output good = solve_ok(data, STEWART_MASSLESS, &home);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, params.platform_mass * 9.81 * good.lengths.length[0] / 3.0,
                              good.force[0]);
}

/* Geometry scaled by s with the same mass: lengths scale by s, static forces do not change
 * (F = m g L / (6 h) depends on L / h only). From a 1 mm to a 100 m platform. */
static void test_scaled_platform_is_similar(void) {
    stewart_pose home = {{0.01, -0.02, 0.5, 0.05, -0.03, 0.2}, {0}, {0}};
    stewart_inverse_output reference = solve_ok(data, STEWART_MASSLESS, &home);
    const double scales[2] = {2e-3, 200.0};
    for (int i = 0; i < 2; ++i) {
        const double s = scales[i];
        stewart_params_default(&params);
        params.base_radius *= s;
        params.platform_radius *= s;
        params.home_height *= s;
        params.leg_diameter *= s; /* legs thicker than the joints are apart are refused */
        for (int k = 0; k < 6; ++k) params.stroke_min[k] *= s, params.stroke_max[k] *= s;
        /* the inertia of the disc scales as s^2 (it plays no part at rest) */
        for (int j = 0; j < 3; ++j) params.platform_inertia[j] *= s * s;
        rebuild_platform();
        stewart_pose p = home;
        for (int j = 0; j < 3; ++j) p.q[j] *= s;
        stewart_inverse_output out = solve_ok(data, STEWART_MASSLESS, &p);
        for (int k = 0; k < 6; ++k) {
            TEST_ASSERT_DOUBLE_WITHIN(1e-13 * s, s * reference.lengths.length[k],
                                      out.lengths.length[k]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-9 * fabs(reference.force[k]), reference.force[k],
                                      out.force[k]);
        }
        TEST_ASSERT_EQUAL_INT(0, out.warnings);
    }
}

/* A payload 10 m outside the platform rim pulls some legs into tension; the legs still hold the
 * total weight and its moment about the plate centre (checked through the base wrench). */
static void test_payload_far_outside(void) {
    params.payload_mass = 50;
    params.payload_com[0] = 10.0;
    rebuild_platform();
    stewart_pose home = yawed(0);
    stewart_inverse_output out = solve_ok(data, STEWART_MASSLESS, &home);
    int tension = 0;
    for (int k = 0; k < 6; ++k) tension += out.force[k] < 0;
    TEST_ASSERT_TRUE(tension > 0);
    const double W = (params.platform_mass + 50) * 9.81;
    TEST_ASSERT_DOUBLE_WITHIN(1e-9 * W, -W, out.base_force[2]);
    /* moment of the weights about the world y axis: payload at x = 10 m */
    TEST_ASSERT_DOUBLE_WITHIN(1e-9 * W * 10, 50 * 9.81 * 10.0, out.base_torque[1]);
}

/* Just inside and just outside the stroke limits: same solve, the warning bit alone differs. */
static void test_stroke_limits_flag_without_failing(void) {
    const double chord2 = pow(sin(15 * M_PI / 180), 2);
    const double z_at_max = sqrt(params.stroke_max[0] * params.stroke_max[0] - chord2);
    const double z_at_min = sqrt(params.stroke_min[0] * params.stroke_min[0] - chord2);
    const double z[4] = {z_at_max - 1e-9, z_at_max + 1e-9, z_at_min + 1e-9, z_at_min - 1e-9};
    const int flagged[4] = {0, 1, 0, 1};
    for (int i = 0; i < 4; ++i) {
        stewart_pose p = {{0, 0, z[i], 0, 0, 0}, {0}, {0}};
        stewart_inverse_output out = solve_ok(data, STEWART_MASSLESS, &p);
        TEST_ASSERT_EQUAL_INT(flagged[i] ? STEWART_WARN_STROKE : 0,
                              out.warnings & STEWART_WARN_STROKE);
    }
}

/* The per-leg stroke bits name exactly the legs whose closed-form length is outside the stroke:
 * an x offset lengthens some legs and shortens others. */
static void test_stroke_bits_name_the_legs(void) {
    for (int f = STEWART_KINEMATIC; f <= STEWART_FULL; ++f) {
        stewart_pose p = {{0.12, -0.05, 0.50, 0.05, 0, 0.1}, {0}, {0}};
        stewart_params narrow = params;
        for (int k = 0; k < 6; ++k) narrow.stroke_min[k] = 0.55, narrow.stroke_max[k] = 0.62;
        stewart_model *m = test_model(&narrow);
        stewart_inverse *d = test_inverse(m);
        stewart_inverse_output out = solve_ok(d, (stewart_fidelity)f, &p);
        int expected = 0;
        for (int k = 0; k < STEWART_LEGS; ++k) {
            const double L = closed_form_length(&narrow, &p, k);
            if (L < narrow.stroke_min[k] || L > narrow.stroke_max[k]) expected |= 1 << k;
        }
        TEST_ASSERT_TRUE(expected != 0 && expected != 0x3f); /* the pose splits the legs */
        TEST_ASSERT_EQUAL_HEX(expected, out.stroke_legs);
        TEST_ASSERT_EQUAL_INT(STEWART_WARN_STROKE, out.warnings & STEWART_WARN_STROKE);
        stewart_inverse_free(d);
        stewart_model_free(m);
    }
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_stroke_bits_name_the_legs);
    RUN_TEST(test_yaw_singularity_sweep);
    RUN_TEST(test_scaled_platform_is_similar);
    RUN_TEST(test_payload_far_outside);
    RUN_TEST(test_stroke_limits_flag_without_failing);
    return UNITY_END();
}
