/* stewart_plant_derivatives (the plant's right-hand side in pose coordinates, what the Model
 * Exchange unit evaluates) against the inverse side: the forces stewart_inverse_solve gives for
 * a pose, its rates and accelerations must give back those accelerations, lengths, length rates
 * and accelerations, and the base wrench (both fidelities, along a combined manoeuvre); free fall
 * in closed form; the refusals (pitch at +-90 degrees, a zero-length leg, non-finite input) with
 * messages naming the value; the plant's own state untouched. */
#include <math.h>
#include <string.h>

#include "stewart/stewart_plant.h"
#include "test_plant_support.h"
#include "test_support.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

static stewart_model *model;
static stewart_model *framed; /* tool and user frames and length offsets */

/* |a - b| over n values, relative to max(1, |b|). */
static double error(const double *a, const double *b, int n) {
    double e = 0, scale = 1;
    for (int i = 0; i < n; ++i) {
        e = fmax(e, fabs(a[i] - b[i]));
        scale = fmax(scale, fabs(b[i]));
    }
    return e / scale;
}

static void inverse_round_trip(const stewart_model *model, int fidelity, double tolerance) {
    stewart_inverse_options io = test_options(fidelity);
    char msg[STEWART_MESSAGE_SIZE];
    stewart_inverse *inv = stewart_inverse_create(model, &io, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(inv, msg);
    stewart_plant *plant = test_plant(model, fidelity, 1e-10, 1e-12);
    double worst[4] = {0, 0, 0, 0};
    for (int i = 0; i < 40; ++i) {
        stewart_inverse_input in = {combined_pose(0.05 * i)};
        stewart_inverse_output legs;
        TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK, stewart_inverse_solve(inv, &in, &legs),
                                  stewart_inverse_message(inv));
        stewart_plant_derivative_input d = {0.05 * i, in.pose, {0}};
        memcpy(d.force, legs.force, sizeof d.force);
        stewart_plant_output out;
        TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK, stewart_plant_derivatives(plant, &d, &out),
                                  stewart_plant_message(plant));
        TEST_ASSERT_EQUAL_DOUBLE_ARRAY(in.pose.q_dot, out.pose.q_dot, 6);
        worst[0] = fmax(worst[0], error(out.pose.q_ddot, in.pose.q_ddot, 6));
        worst[1] =
            fmax(worst[1], fmax(error(out.lengths.length, legs.lengths.length, 6),
                                error(out.lengths.length_rate, legs.lengths.length_rate, 6)));
        worst[2] = fmax(worst[2], error(out.lengths.length_accel, legs.lengths.length_accel, 6));
        worst[3] = fmax(worst[3], fmax(error(out.base_force, legs.base_force, 3),
                                       error(out.base_torque, legs.base_torque, 3)));
    }
    printf("fidelity %d: accelerations %.2g, lengths and rates %.2g, length accelerations %.2g, "
           "base wrench %.2g (relative)\n",
           fidelity, worst[0], worst[1], worst[2], worst[3]);
    TEST_ASSERT_TRUE(worst[0] < tolerance);
    TEST_ASSERT_TRUE(worst[1] < 1e-12);
    TEST_ASSERT_TRUE(worst[2] < tolerance);
    TEST_ASSERT_TRUE(worst[3] < tolerance);
    stewart_plant_free(plant);
    stewart_inverse_free(inv);
}

static void test_the_inverse_sides_forces_give_back_the_accelerations(void) {
    /* measured 2e-14 and 1e-13: two formulations of the same equations, to rounding */
    inverse_round_trip(model, STEWART_MASSLESS, 1e-11);
    inverse_round_trip(model, STEWART_FULL, 1e-10);
    /* the tool's pose in the user frame, lengths read with offsets: the same, through both
     * sides' frame transforms */
    inverse_round_trip(framed, STEWART_MASSLESS, 1e-10);
    inverse_round_trip(framed, STEWART_FULL, 1e-9);
}

static void test_free_fall_without_forces_or_leg_mass(void) {
    stewart_plant *plant = test_plant(model, STEWART_MASSLESS, 1e-10, 1e-12);
    stewart_plant_derivative_input d = {
        0, {{0.01, -0.02, 0.45, 0.1, -0.2, 0.3}, {0.1, 0.2, -0.3, 0, 0, 0}, {0}}, {0}};
    stewart_plant_output out;
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_derivatives(plant, &d, &out));
    const double g[6] = {0, 0, -9.81, 0, 0, 0};
    for (int i = 0; i < 6; ++i) TEST_ASSERT_DOUBLE_WITHIN(1e-12, g[i], out.pose.q_ddot[i]);
    stewart_plant_free(plant);
}

static void test_refusals_name_the_value_and_leave_the_plant_alone(void) {
    stewart_plant *plant = test_plant(model, STEWART_FULL, 1e-10, 1e-12);
    stewart_plant_output before, after, out;
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &before));
    memset(&out, 0x5a, sizeof out);
    const stewart_plant_output untouched = out;
    stewart_plant_derivative_input d = {0, {{0, 0, 0.5, 0, M_PI / 2, 0}, {0}, {0}}, {0}};
    TEST_ASSERT_EQUAL(STEWART_ERR_SINGULAR, stewart_plant_derivatives(plant, &d, &out));
    TEST_ASSERT_NOT_NULL(strstr(stewart_plant_message(plant), "pitch = 1.5707963267948966"));
    d.pose.q[4] = 0;
    d.force[1] = NAN;
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, stewart_plant_derivatives(plant, &d, &out));
    TEST_ASSERT_NOT_NULL(strstr(stewart_plant_message(plant), "F[2] = nan"));
    d.force[1] = 0;
    d.pose.q_dot[3] = INFINITY;
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, stewart_plant_derivatives(plant, &d, &out));
    TEST_ASSERT_NOT_NULL(strstr(stewart_plant_message(plant), "roll_dot = inf"));
    d.pose.q_dot[3] = 0;
    /* a zero-length leg 1, found from the call's own lengths: L1^2(p) = |p + c|^2 at the home
     * rotation, so three displaced evaluations give w = p0 + c, and p0 - w puts leg 1 at zero
     * length */
    const double h = 0.05;
    double w[3], base;
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_derivatives(plant, &d, &out));
    base = out.lengths.length[0] * out.lengths.length[0];
    for (int i = 0; i < 3; ++i) {
        stewart_plant_derivative_input moved = d;
        moved.pose.q[i] += h;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_derivatives(plant, &moved, &out));
        w[i] = (out.lengths.length[0] * out.lengths.length[0] - base - h * h) / (2 * h);
    }
    for (int i = 0; i < 3; ++i) d.pose.q[i] -= w[i];
    memcpy(&out, &untouched, sizeof out);
    TEST_ASSERT_EQUAL(STEWART_ERR_UNREACHABLE, stewart_plant_derivatives(plant, &d, &out));
    TEST_ASSERT_NOT_NULL(strstr(stewart_plant_message(plant), "leg 1 has zero length"));
    TEST_ASSERT_EQUAL_MEMORY(&untouched, &out, sizeof out);
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, stewart_plant_derivatives(plant, NULL, &out));
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, stewart_plant_derivatives(NULL, &d, &out));
    /* the plant's own state is what it was */
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &after));
    TEST_ASSERT_EQUAL_MEMORY(&before, &after, sizeof before);
    stewart_plant_free(plant);
}

int main(void) {
    stewart_params params;
    stewart_params_default(&params);
    model = test_model(&params);
    const double tool[6] = {0.01, -0.02, 0.05, 0.1, -0.05, 0.2};
    const double user[6] = {0.02, 0.01, -0.03, 0.05, 0.04, -0.3};
    for (int i = 0; i < 6; ++i) {
        params.tool_frame[i] = tool[i];
        params.user_frame[i] = user[i];
        params.length_offset[i] = 0.01 * (i + 1);
    }
    framed = test_model(&params);
    UNITY_BEGIN();
    RUN_TEST(test_the_inverse_sides_forces_give_back_the_accelerations);
    RUN_TEST(test_free_fall_without_forces_or_leg_mass);
    RUN_TEST(test_refusals_name_the_value_and_leave_the_plant_alone);
    const int failures = UNITY_END();
    stewart_model_free(framed);
    stewart_model_free(model);
    return failures;
}
