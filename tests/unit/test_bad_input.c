/* Bad input: every case returns an error code and a message naming the value, leaves the output
 * untouched, and the data block stays usable. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "platform_fixture.h"
#include "stewart/stewart_forward.h"
#include "test_support.h"
#include "unity.h"

static char msg[STEWART_MESSAGE_SIZE];

static void assert_contains(const char *haystack, const char *needle) {
    if (!strstr(haystack, needle)) {
        char text[2 * STEWART_MESSAGE_SIZE];
        snprintf(text, sizeof text, "'%s' does not mention '%s'", haystack, needle);
        TEST_FAIL_MESSAGE(text);
    }
}

/* The output keeps its sentinel after a failed solve, and a good pose right after succeeds. */
static void assert_rejected(const stewart_pose *pose, stewart_fidelity f, stewart_status expected,
                            const char *mention) {
    stewart_inverse_options o = test_options(f);
    stewart_inverse_output out;
    memset(&out, 0x5a, sizeof out);
    stewart_inverse_output sentinel = out;
    TEST_ASSERT_EQUAL_INT(expected, solve_as(data, &o, pose, &out));
    TEST_ASSERT_EQUAL_MEMORY(&sentinel, &out, sizeof out);
    assert_contains(stewart_inverse_message(data), mention);
    stewart_pose home = {{0, 0, 0.5, 0, 0, 0}, {0}, {0}};
    stewart_inverse_output good = solve_ok(data, f, &home);
    TEST_ASSERT_FALSE(isnan(good.force[0]));
    TEST_ASSERT_EQUAL_STRING("", stewart_inverse_message(data));
}

static void test_nan_and_inf_pose_components_are_named(void) {
    const char *names[6] = {"x", "y", "z", "roll", "pitch", "yaw"};
    char expected[32];
    for (int row = 0; row < 3; ++row)
        for (int i = 0; i < 6; ++i) {
            stewart_pose pose = {{0, 0, 0.5, 0, 0, 0}, {0}, {0}};
            double *v = row == 0 ? pose.q : row == 1 ? pose.q_dot : pose.q_ddot;
            v[i] = (i % 2) ? NAN : -INFINITY;
            snprintf(expected, sizeof expected, "%s%s is", names[i],
                     row == 0   ? ""
                     : row == 1 ? "_dot"
                                : "_ddot");
            assert_rejected(&pose, STEWART_MASSLESS, STEWART_ERR_ARGUMENT, expected);
        }
}

/* z = 0 and yaw = 30 degrees puts platform point 1 (at 330 deg) onto base point 1 (at 0 deg). */
static void test_leg_of_zero_length_is_unreachable(void) {
    stewart_pose pose = {{0, 0, 0, 0, 0, M_PI / 6}, {0}, {0}};
    assert_rejected(&pose, STEWART_KINEMATIC, STEWART_ERR_UNREACHABLE, "leg 1");
}

/* Finite but huge inputs overflow inside the solve: an error, never an infinite output. */
static void test_overflowing_pose_is_rejected(void) {
    stewart_pose far = {{0, 0, -2.7e154, 0, 0, 0}, {0}, {0}};
    assert_rejected(&far, STEWART_KINEMATIC, STEWART_ERR_ARGUMENT, "out of range");
    stewart_pose fast = {{0, 0, 0.5, 0, 0, 0}, {1e200, 0, 0, 0, 0, 0}, {0}};
    assert_rejected(&fast, STEWART_MASSLESS, STEWART_ERR_ARGUMENT, "out of range");
}

/* Legs all vertical (platform angles equal to base angles) cannot resist a yaw moment. */
static void test_singular_leg_jacobian(void) {
    memcpy(params.platform_angle, params.base_angle, sizeof params.base_angle);
    rebuild_platform();
    stewart_pose home = {{0, 0, 0.5, 0, 0, 0}, {0}, {0}};
    stewart_inverse_options o = test_options(STEWART_MASSLESS);
    stewart_inverse_output out;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_SINGULAR, solve_as(data, &o, &home, &out));
    assert_contains(stewart_inverse_message(data), "singular");
    /* the kinematic level needs no inverse and still answers */
    solve_ok(data, STEWART_KINEMATIC, &home);
}

static void expect_bad_params(const stewart_params *p, const char *mention) {
    TEST_ASSERT_NULL(stewart_model_create(p, msg, sizeof msg));
    assert_contains(msg, mention);
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER, stewart_params_check(p, msg, sizeof msg));
}

static void test_invalid_parameters_are_named(void) {
    stewart_params p;
    stewart_params_default(&p);
    p.base_radius = 0;
    expect_bad_params(&p, "base_radius = 0");
    stewart_params_default(&p);
    p.platform_radius = -1;
    expect_bad_params(&p, "platform_radius = -1");
    stewart_params_default(&p);
    p.platform_mass = 0;
    expect_bad_params(&p, "platform_mass = 0");
    stewart_params_default(&p);
    p.payload_mass = -5;
    expect_bad_params(&p, "payload_mass = -5");
    stewart_params_default(&p);
    p.piston_mass = -1;
    expect_bad_params(&p, "piston_mass");
    stewart_params_default(&p);
    p.gravity[2] = NAN;
    expect_bad_params(&p, "gravity[3]");
    stewart_params_default(&p);
    p.platform_angle[4] = INFINITY;
    expect_bad_params(&p, "platform_angle[5]");
    stewart_params_default(&p);
    p.platform_inertia[2] = 0;
    expect_bad_params(&p, "platform_inertia");
    /* principal moments that break the triangle inequality are no rigid body's */
    stewart_params_default(&p);
    p.payload_inertia[0] = 1;
    p.payload_inertia[1] = 1;
    p.payload_inertia[2] = 3;
    expect_bad_params(&p, "payload_inertia");
    stewart_params_default(&p);
    p.stroke_max[3] = p.stroke_min[3];
    expect_bad_params(&p, "stroke_max[4]");
    TEST_ASSERT_NULL(stewart_model_create(NULL, msg, sizeof msg));
}

static void test_invalid_options_and_null_arguments(void) {
    stewart_inverse_input in = {{{0, 0, 0.5, 0, 0, 0}, {0}, {0}}};
    stewart_inverse_output out;
    stewart_inverse_options o = test_options(STEWART_MASSLESS);
    o.fidelity = 7;
    TEST_ASSERT_NULL(stewart_inverse_create(model, &o, msg, sizeof msg));
    assert_contains(msg, "fidelity = 7");
    o = test_options(STEWART_MASSLESS);
    o.tolerance = -1;
    TEST_ASSERT_NULL(stewart_inverse_create(model, &o, msg, sizeof msg));
    assert_contains(msg, "tolerance = -1");
    o = test_options(STEWART_MASSLESS);
    TEST_ASSERT_NULL(stewart_inverse_create(NULL, &o, msg, sizeof msg));
    assert_contains(msg, "model is NULL");
    TEST_ASSERT_NULL(stewart_inverse_create(model, NULL, msg, sizeof msg));
    assert_contains(msg, "options is NULL");
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_inverse_solve(data, NULL, &out));
    assert_contains(stewart_inverse_message(data), "NULL");
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_inverse_solve(data, &in, NULL));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_inverse_solve(NULL, &in, &out));
    /* still usable */
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_inverse_solve(data, &in, &out));
    TEST_ASSERT_EQUAL_STRING("", stewart_inverse_message(data));
    stewart_model_free(NULL);
    stewart_inverse_free(NULL);
}

/* The full level's position residual (max-norm, m) cannot go below one rounding of coordinates
 * of order 1, DBL_EPSILON = 2.2e-16: a tolerance at or below it is refused by name, and 2.5e-16
 * is accepted and met along the combined manoeuvre (lengths still the closed form). */
static void test_tolerance_below_machine_precision(void) {
    const double refused[3] = {1e-16, 1e-17, DBL_EPSILON};
    const char *named[3] = {"tolerance = 1e-16", "tolerance = 1e-17",
                            "tolerance = 2.220446049250313e-16"};
    stewart_pose home = {{0, 0, 0.5, 0, 0, 0}, {0}, {0}};
    stewart_inverse_output out;
    for (int i = 0; i < 3; ++i) {
        stewart_inverse_options o = test_options(STEWART_FULL);
        o.tolerance = refused[i];
        TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                              stewart_inverse_options_check(&o, msg, sizeof msg));
        assert_contains(msg, named[i]);
        assert_contains(msg, "use at least 2.5e-16");
        TEST_ASSERT_NULL(stewart_inverse_create(model, &o, msg, sizeof msg));
        assert_contains(msg, named[i]);
    }
    stewart_inverse_options o = test_options(STEWART_FULL);
    o.tolerance = 2.5e-16;
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_inverse_options_check(&o, msg, sizeof msg),
                                  msg);
    for (int i = 0; i < 300; ++i) {
        stewart_pose pose = combined_pose(0.01 * i);
        TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, solve_as(data, &o, &pose, &out),
                                      stewart_inverse_message(data));
        TEST_ASSERT_TRUE(out.residual <= 2.5e-16);
        for (int k = 0; k < 6; ++k)
            TEST_ASSERT_DOUBLE_WITHIN(1e-12, closed_form_length(&params, &pose, k),
                                      out.lengths.length[k]);
    }
}

/* The Newton iteration cap is bounded (fuzz_fmu found inputs that set it near INT_MAX and then
 * ran one failing solve for 12 s): 1001 is refused by name for both solvers, 1000 accepted. */
static void test_iteration_cap_is_bounded(void) {
    stewart_inverse_options o = test_options(STEWART_FULL);
    o.max_iterations = 1001;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                          stewart_inverse_options_check(&o, msg, sizeof msg));
    assert_contains(msg, "max_iterations = 1001");
    o.max_iterations = 1000;
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_inverse_options_check(&o, msg, sizeof msg),
                                  msg);
    stewart_forward_options f;
    stewart_forward_options_default(&f);
    f.max_iterations = 2147483647;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                          stewart_forward_options_check(&f, msg, sizeof msg));
    assert_contains(msg, "max_iterations = 2147483647");
}

/* A value as messages print it: the fewest digits (at most 17) that read back as the same double. */
static void exact_text(double value, char *text, size_t size) {
    for (int digits = 6; digits <= 17; ++digits) {
        snprintf(text, size, "%.*g", digits, value);
        if (strtod(text, NULL) == value) return;
    }
}

/* Issue 15 item 9: a pose rate or acceleration too large to solve with is named as the input it
 * is (x_dot .. yaw_ddot) with its value, at every level, never as an internal coordinate. */
static void test_overflowing_rates_name_the_input(void) {
    const char *names[6] = {"x", "y", "z", "roll", "pitch", "yaw"};
    const double values[3] = {DBL_MAX, -DBL_MAX, 1e200};
    char expected[64], value[32];
    for (int f = STEWART_KINEMATIC; f <= STEWART_FULL; ++f)
        for (int row = 1; row <= 2; ++row)
            for (int i = 0; i < 6; ++i)
                for (int v = 0; v < 3; ++v) {
                    stewart_pose pose = {{0, 0, 0.5, 0, 0, 0}, {0}, {0}};
                    (row == 1 ? pose.q_dot : pose.q_ddot)[i] = values[v];
                    exact_text(values[v], value, sizeof value);
                    snprintf(expected, sizeof expected, "%s%s = %s", names[i],
                             row == 1 ? "_dot" : "_ddot", value);
                    stewart_inverse_options o = test_options((stewart_fidelity)f);
                    stewart_inverse_output out;
                    const stewart_status s = solve_as(data, &o, &pose, &out);
                    if (s == STEWART_OK) { /* solvable: the outputs are finite */
                        for (int k = 0; k < 6; ++k)
                            TEST_ASSERT_TRUE(isfinite(out.force[k]) &&
                                             isfinite(out.lengths.length_accel[k]));
                        continue;
                    }
                    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_ERR_ARGUMENT, s,
                                                  stewart_inverse_message(data));
                    assert_contains(stewart_inverse_message(data), expected);
                    TEST_ASSERT_NULL_MESSAGE(strstr(stewart_inverse_message(data), "q_d"),
                                             stewart_inverse_message(data));
                    TEST_ASSERT_NULL_MESSAGE(strstr(stewart_inverse_message(data), "lambda"),
                                             stewart_inverse_message(data));
                }
    /* x_dot = DBL_MAX, the probe's case, is refused at the full level */
    stewart_pose pose = {{0, 0, 0.5, 0, 0, 0}, {DBL_MAX, 0, 0, 0, 0, 0}, {0}};
    assert_rejected(&pose, STEWART_FULL, STEWART_ERR_ARGUMENT, "x_dot = 1.7976931348623157e+308");
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_nan_and_inf_pose_components_are_named);
    RUN_TEST(test_leg_of_zero_length_is_unreachable);
    RUN_TEST(test_overflowing_pose_is_rejected);
    RUN_TEST(test_singular_leg_jacobian);
    RUN_TEST(test_invalid_parameters_are_named);
    RUN_TEST(test_invalid_options_and_null_arguments);
    RUN_TEST(test_tolerance_below_machine_precision);
    RUN_TEST(test_iteration_cap_is_bounded);
    RUN_TEST(test_overflowing_rates_name_the_input);
    return UNITY_END();
}
