/* rotation_order and frame_convention through the C API (docs/geometry.md, "Rotation order and
 * frames"): a pose whose angles are Rx Ry Rz against the closed-form lengths of the same rotation
 * written as Rz Ry Rx angles (rotation matrices and angle extraction of this file's own); the
 * thesis platform given z down (its azimuths seen from below) against the z-up one at the same
 * physical poses; the plant's state
 * given and returned in the order; bad values refused by name. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "stewart/stewart.h"
#include "stewart/stewart_plant.h"
#include "test_plant_support.h"
#include "test_support.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

static void multiply(const double A[3][3], const double B[3][3], double C[3][3]) {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            C[i][j] = 0;
            for (int k = 0; k < 3; ++k) C[i][j] += A[i][k] * B[k][j];
        }
}

/* R = Rx(a[0]) Ry(a[1]) Rz(a[2]). */
static void xyz_matrix(const double a[3], double R[3][3]) {
    const double Rx[3][3] = {{1, 0, 0}, {0, cos(a[0]), -sin(a[0])}, {0, sin(a[0]), cos(a[0])}};
    const double Ry[3][3] = {{cos(a[1]), 0, sin(a[1])}, {0, 1, 0}, {-sin(a[1]), 0, cos(a[1])}};
    const double Rz[3][3] = {{cos(a[2]), -sin(a[2]), 0}, {sin(a[2]), cos(a[2]), 0}, {0, 0, 1}};
    double XY[3][3];
    multiply(Rx, Ry, XY);
    multiply(XY, Rz, R);
}

/* The pose with the same rotation as xyz's Rx Ry Rz angles, as Rz Ry Rx angles. */
static stewart_pose as_zyx(const stewart_pose *xyz) {
    double R[3][3];
    xyz_matrix(xyz->q + 3, R);
    stewart_pose p = *xyz;
    p.q[3] = atan2(R[2][1], R[2][2]);
    p.q[4] = asin(-R[2][0]);
    p.q[5] = atan2(R[1][0], R[0][0]);
    return p;
}

static double lengths_of(stewart_model *m, const stewart_pose *pose, int k) {
    stewart_inverse *d = test_inverse(m);
    const stewart_inverse_output out = solve_ok(d, STEWART_KINEMATIC, pose);
    stewart_inverse_free(d);
    return out.lengths.length[k];
}

void test_xyz_pose_has_the_lengths_of_its_rotation(void) {
    stewart_params plain, xyz;
    stewart_params_default(&plain);
    xyz = plain;
    xyz.rotation_order = 1;
    stewart_model *m = test_model(&xyz);
    double largest_order_gap = 0;
    for (int n = 0; n < 20; ++n) {
        const stewart_pose pose = combined_pose(0.37 * n);
        const stewart_pose zyx = as_zyx(&pose);
        for (int k = 0; k < STEWART_LEGS; ++k) {
            const double got = lengths_of(m, &pose, k);
            TEST_ASSERT_DOUBLE_WITHIN(1e-15, closed_form_length(&plain, &zyx, k), got);
            const double other = closed_form_length(&plain, &pose, k);  // read as Rz Ry Rx
            if (fabs(other - got) > largest_order_gap) largest_order_gap = fabs(other - got);
        }
    }
    TEST_ASSERT_TRUE(largest_order_gap > 1e-5);  // the orders differ at these angles
    stewart_model_free(m);
}

void test_z_down_thesis_has_the_z_up_lengths(void) {
    stewart_params plain, down;
    stewart_params_default(&plain);
    down = plain;
    down.frame_convention = 1;
    /* the same machine seen in the z-down frames: azimuths from x toward y right */
    for (int k = 0; k < STEWART_LEGS; ++k) {
        down.base_angle[k] = -plain.base_angle[k];
        down.platform_angle[k] = -plain.platform_angle[k];
    }
    stewart_model *m = test_model(&down);
    for (int n = 0; n < 20; ++n) {
        const stewart_pose up = combined_pose(0.41 * n);
        /* turned by 180 deg about x: position (x, -y, -z), Rz Ry Rx angles (r, -p, -y) */
        stewart_pose pose = up;
        for (int i = 1; i < 6; ++i)
            if (i != 3) pose.q[i] = -up.q[i];
        for (int k = 0; k < STEWART_LEGS; ++k)
            TEST_ASSERT_DOUBLE_WITHIN(1e-15, closed_form_length(&plain, &up, k),
                                      lengths_of(m, &pose, k));
    }
    stewart_model_free(m);
}

void test_plant_state_is_given_and_returned_in_the_order(void) {
    stewart_params p;
    stewart_params_default(&p);
    p.rotation_order = 1;
    stewart_model *m = test_model(&p);
    stewart_plant *plant = test_plant(m, 1, 1e-10, 1e-12);
    const double q[6] = {0.01, -0.02, 0.52, 0.2, -0.15, 0.3};
    const double rate[6] = {0.1, 0, -0.1, 0.3, 0.2, -0.4};
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(plant, 0, q, rate));
    stewart_plant_output out;
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &out));
    for (int i = 0; i < 6; ++i) {
        TEST_ASSERT_DOUBLE_WITHIN(2e-15, q[i], out.pose.q[i]);
        TEST_ASSERT_DOUBLE_WITHIN(1e-14, rate[i], out.pose.q_dot[i]);
    }
    stewart_plant_free(plant);
    stewart_model_free(m);
}

void test_bad_values_are_refused_by_name(void) {
    const char *names[2] = {"rotation_order", "frame_convention"};
    const double bad[3] = {0.5, 2, -1};
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 3; ++j) {
            stewart_params p;
            stewart_params_default(&p);
            *(i ? &p.frame_convention : &p.rotation_order) = bad[j];
            char msg[STEWART_MESSAGE_SIZE];
            TEST_ASSERT_NULL(stewart_model_create(&p, msg, sizeof msg));
            TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, names[i]), msg);
        }
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_xyz_pose_has_the_lengths_of_its_rotation);
    RUN_TEST(test_z_down_thesis_has_the_z_up_lengths);
    RUN_TEST(test_plant_state_is_given_and_returned_in_the_order);
    RUN_TEST(test_bad_values_are_refused_by_name);
    return UNITY_END();
}
