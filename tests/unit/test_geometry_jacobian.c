/* stewart_geometry_jacobian (stewart_calibration.h): readings against the tests' written-out
 * closed form, the pose derivatives against central differences of it, the joint derivatives
 * against moving the thesis circles' joints, and bad arguments named. (tests/python/
 * test_calibration_jacobian.py checks every block on general geometries with frames.) */
#include <math.h>
#include <string.h>

#include "platform_fixture.h"
#include "stewart/stewart_calibration.h"
#include "test_support.h"
#include "unity.h"

static stewart_geometry_jacobian_output jacobian_ok(const stewart_model *m, const double q[6]) {
    stewart_geometry_jacobian_output out;
    char message[STEWART_MESSAGE_SIZE];
    if (stewart_geometry_jacobian(m, q, &out, message, sizeof message) != STEWART_OK)
        TEST_FAIL_MESSAGE(message);
    TEST_ASSERT_EQUAL_STRING("", message);
    return out;
}

/* Readings are the closed-form lengths (no offsets in the thesis platform), and the pose block
 * is their derivative along each pose component. */
static void test_readings_and_pose_derivatives(void) {
    const double h = 1e-6;
    for (int i = 0; i < 20; ++i) {
        stewart_pose pose = combined_pose(0.31 * i);
        stewart_geometry_jacobian_output out = jacobian_ok(model, pose.q);
        for (int k = 0; k < 6; ++k) {
            TEST_ASSERT_DOUBLE_WITHIN(1e-15, closed_form_length(&params, &pose, k), out.length[k]);
            TEST_ASSERT_EQUAL_DOUBLE(out.length[k], out.reading[k]);
            TEST_ASSERT_EQUAL_DOUBLE(-1.0, out.length_offset[k]);
            for (int j = 0; j < 6; ++j) {
                stewart_pose plus = pose, minus = pose;
                plus.q[j] += h;
                minus.q[j] -= h;
                const double fd = (closed_form_length(&params, &plus, k) -
                                   closed_form_length(&params, &minus, k)) /
                                  (2 * h);
                TEST_ASSERT_DOUBLE_WITHIN(1e-8, fd, out.pose[k][j]);
            }
        }
    }
}

/* Turning base joint k on its circle by d beta moves it by r d beta along the tangent: the
 * reading changes by the base-joint row dotted with that displacement. */
static void test_base_joint_row_along_the_circle(void) {
    const double h = 1e-7;
    stewart_pose pose = combined_pose(1.7);
    stewart_geometry_jacobian_output out = jacobian_ok(model, pose.q);
    for (int k = 0; k < 6; ++k) {
        const double beta = params.base_angle[k];
        params.base_angle[k] = beta + h;
        const double plus = closed_form_length(&params, &pose, k);
        params.base_angle[k] = beta - h;
        const double minus = closed_form_length(&params, &pose, k);
        params.base_angle[k] = beta;
        const double tangent[3] = {-0.5 * sin(beta), 0.5 * cos(beta), 0};
        double along = 0;
        for (int i = 0; i < 3; ++i) along += out.base_joint[k][i] * tangent[i];
        TEST_ASSERT_DOUBLE_WITHIN(1e-7, (plus - minus) / (2 * h), along);
    }
}

static void test_bad_arguments_are_named(void) {
    stewart_geometry_jacobian_output out, untouched;
    memset(&out, 0x5a, sizeof out);
    untouched = out;
    char message[STEWART_MESSAGE_SIZE];
    double q[6] = {0, 0, 0.5, 0, NAN, 0};
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT,
                      stewart_geometry_jacobian(model, q, &out, message, sizeof message));
    TEST_ASSERT_EQUAL_STRING("pose input pitch is nan: it must be finite", message);
    TEST_ASSERT_EQUAL_MEMORY(&untouched, &out, sizeof out);
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT,
                      stewart_geometry_jacobian(NULL, q, &out, message, sizeof message));
    TEST_ASSERT_EQUAL_STRING("model is NULL", message);
    /* A platform joint on its base joint: the leg has no direction. */
    double on_base[6] = {0.5 - 0.5 * cos(params.platform_angle[0]),
                         -0.5 * sin(params.platform_angle[0]),
                         0,
                         0,
                         0,
                         0};
    TEST_ASSERT_EQUAL(STEWART_ERR_UNREACHABLE,
                      stewart_geometry_jacobian(model, on_base, &out, message, sizeof message));
    TEST_ASSERT_NOT_NULL(strstr(message, "leg 1 has length"));
    TEST_ASSERT_EQUAL_MEMORY(&untouched, &out, sizeof out);
}

static void test_model_joints_are_the_circles(void) {
    double base[18], top[18];
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_model_joints(model, base, top));
    for (int k = 0; k < 6; ++k) {
        TEST_ASSERT_DOUBLE_WITHIN(1e-15, 0.5 * cos(params.base_angle[k]), base[3 * k]);
        TEST_ASSERT_DOUBLE_WITHIN(1e-15, 0.5 * sin(params.platform_angle[k]), top[3 * k + 1]);
    }
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, stewart_model_joints(NULL, base, top));
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_readings_and_pose_derivatives);
    RUN_TEST(test_base_joint_row_along_the_circle);
    RUN_TEST(test_bad_arguments_are_named);
    RUN_TEST(test_model_joints_are_the_circles);
    return UNITY_END();
}
