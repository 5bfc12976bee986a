/* Linearisation with tool and user frames (stewart_linearize.h): the state, inputs and outputs are
 * the tool's pose in the user frame, as every pose of the library. Checked against central
 * differences of nonlinear functions that do not share the linearisation's code:
 * - A, B and C's length rows against stewart_plant_derivatives (csrc/plant: the platform's pose
 *   from the tool's by kinematics/frames.cpp's platform_pose, the angles by atan2, the tool's
 *   accelerations by tool_pose), and the linearisation's values against its values;
 * - the inverse side's Jacobian against stewart_inverse_solve with the same frames (the 14-body
 *   model at full fidelity);
 * at random operating points of both fidelities, with frames that turn about every axis. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "linearize_support.h"
#include "platform_fixture.h"
#include "stewart/stewart_linearize.h"
#include "stewart/stewart_plant.h"
#include "test_support.h"
#include "unity.h"

static const double kStepState = LINEARIZE_STEP_STATE;
static const double kStepForce = LINEARIZE_STEP_FORCE;
static const double kStepAccel = LINEARIZE_STEP_ACCEL;
static const double kRelative = 1e-7;

static const double kTool[6] = {0.02, -0.03, 0.15, 0.1, -0.2, 0.3};
static const double kUser[6] = {0.05, 0.01, -0.02, 0.05, 0.1, -0.4};

static double uniform(uint64_t *rng, double a, double b) {
    return a + (b - a) * (double)(test_random(rng) >> 11) / 9007199254740992.0;
}

/* R = Rz(yaw) Ry(pitch) Rx(roll) of angles a[0..2]. */
static void rotation(const double a[3], double R[3][3]) {
    stewart_pose p;
    memset(&p, 0, sizeof p);
    for (int i = 0; i < 3; ++i) p.q[3 + i] = a[i];
    pose_rotation(&p, R);
}

/* The tool's pose in the user frame with the platform at home: p_t = U^T (h e_z + d - u),
 * R_t = U^T T, its angles by atan2 (written out here, not the library's). */
static void tool_home(double q[6]) {
    double U[3][3], T[3][3];
    rotation(kUser + 3, U);
    rotation(kTool + 3, T);
    const double p[3] = {kTool[0] - kUser[0], kTool[1] - kUser[1],
                         params.home_height + kTool[2] - kUser[2]};
    double Rt[3][3];
    for (int i = 0; i < 3; ++i) {
        q[i] = U[0][i] * p[0] + U[1][i] * p[1] + U[2][i] * p[2];
        for (int j = 0; j < 3; ++j)
            Rt[i][j] = U[0][i] * T[0][j] + U[1][i] * T[1][j] + U[2][i] * T[2][j];
    }
    q[3] = atan2(Rt[2][1], Rt[2][2]);
    q[4] = -asin(Rt[2][0]);
    q[5] = atan2(Rt[1][0], Rt[0][0]);
}

/* A random tool pose near home with random rates and accelerations. */
static stewart_pose random_tool_pose(uint64_t *rng) {
    stewart_pose p;
    double home[6];
    tool_home(home);
    const double q_half[6] = {0.05, 0.05, 0.04, 0.1, 0.1, 0.15};
    for (int i = 0; i < 6; ++i) {
        p.q[i] = home[i] + uniform(rng, -q_half[i], q_half[i]);
        p.q_dot[i] = uniform(rng, -0.5, 0.5);
        p.q_ddot[i] = uniform(rng, -2, 2);
    }
    return p;
}

static void with_frames(void) {
    memcpy(params.tool_frame, kTool, sizeof kTool);
    memcpy(params.user_frame, kUser, sizeof kUser);
    rebuild_platform();
}

static stewart_plant *make_plant(int fidelity) {
    const stewart_plant_options o = test_plant_options(fidelity);
    return test_plant_with(model, &o);
}

/* The plant's right-hand side: q_ddot (6), then L and L_dot (12). */
static void plant_values(stewart_plant *p, const stewart_linearize_input *in, double v[18]) {
    stewart_plant_derivative_input d;
    memset(&d, 0, sizeof d);
    d.pose = in->pose;
    memcpy(d.force, in->force, sizeof d.force);
    stewart_plant_output out;
    TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK, stewart_plant_derivatives(p, &d, &out),
                              stewart_plant_message(p));
    memcpy(v, out.pose.q_ddot, 6 * sizeof v[0]);
    memcpy(v + 6, out.lengths.length, 6 * sizeof v[0]);
    memcpy(v + 12, out.lengths.length_rate, 6 * sizeof v[0]);
}

/* Prints what was checked and its worst errors (the second step: a force or an acceleration);
 * fails unless the worst block error is within kRelative and the values within 1e-9. */
static void expect_close(const char *check, int fidelity, double second_step, double worst,
                         double worst_value) {
    printf("frames, fidelity %d: %s (steps %g, %g), worst block error %.2e; values against its "
           "%.2e\n",
           fidelity, check, kStepState, second_step, worst, worst_value);
    TEST_ASSERT_LESS_THAN_DOUBLE(kRelative, worst);
    TEST_ASSERT_LESS_THAN_DOUBLE(1e-9, worst_value);
}

static void plant_against_differences(int fidelity) {
    with_frames();
    stewart_linearize *l = linearize_make(fidelity);
    stewart_plant *plant = make_plant(fidelity);
    uint64_t rng = 0xf4a3e5u + (uint64_t)fidelity;
    double worst = 0, worst_value = 0;
    for (int n = 0; n < 10; ++n) {
        stewart_linearize_input in;
        in.pose = random_tool_pose(&rng);
        const stewart_inverse_output inverse = solve_ok(data, fidelity, &in.pose);
        for (int k = 0; k < 6; ++k) in.force[k] = inverse.force[k] * uniform(&rng, 0.8, 1.2);
        stewart_linearize_output exact;
        TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK, stewart_linearize_plant(l, &in, &exact),
                                  stewart_linearize_message(l));
        double value[18];
        plant_values(plant, &in, value);
        double scale[3] = {0, 0, 0}; /* q_ddot, L, L_dot */
        for (int i = 0; i < 18; ++i) scale[i / 6] = fmax(scale[i / 6], fabs(value[i]));
        for (int i = 0; i < 6; ++i) {
            TEST_ASSERT_EQUAL_DOUBLE(in.pose.q[i], exact.output[i]);
            TEST_ASSERT_EQUAL_DOUBLE(in.pose.q_dot[i], exact.output[6 + i]);
            worst_value = fmax(worst_value, fabs(exact.state_rate[6 + i] - value[i]) / scale[0]);
            worst_value = fmax(worst_value, fabs(exact.output[12 + i] - value[6 + i]) / scale[1]);
            worst_value = fmax(worst_value, fabs(exact.output[18 + i] - value[12 + i]) / scale[2]);
        }
        /* blocks: (q_ddot, L, L_dot) x (q, q_dot, F) */
        block_error blocks[3][3] = {{{0, 0}}};
        for (int j = 0; j < 18; ++j) {
            stewart_linearize_input plus = in, minus = in;
            double h;
            if (j < 6) {
                h = kStepState;
                plus.pose.q[j] += h;
                minus.pose.q[j] -= h;
            } else if (j < 12) {
                h = kStepState;
                plus.pose.q_dot[j - 6] += h;
                minus.pose.q_dot[j - 6] -= h;
            } else {
                h = kStepForce;
                plus.force[j - 12] += h;
                minus.force[j - 12] -= h;
            }
            double up[18], down[18];
            plant_values(plant, &plus, up);
            plant_values(plant, &minus, down);
            for (int i = 0; i < 18; ++i) {
                const double difference = (up[i] - down[i]) / (2 * h);
                double analytic;
                if (i < 6) analytic = j < 12 ? exact.A[6 + i][j] : exact.B[6 + i][j - 12];
                else analytic = j < 12 ? exact.C[6 + i][j] : exact.D[6 + i][j - 12];
                block_add(&blocks[i / 6][j / 6], analytic, difference);
            }
        }
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) {
                const double e =
                    block_relative(blocks[r][c], scale[r], c < 2 ? kStepState : kStepForce);
                if (e > worst) worst = e;
            }
        for (int i = 0; i < 6; ++i) /* the identity rows */
            for (int j = 0; j < 12; ++j) {
                TEST_ASSERT_EQUAL_DOUBLE(j == 6 + i ? 1 : 0, exact.A[i][j]);
                TEST_ASSERT_EQUAL_DOUBLE(j == i ? 1 : 0, exact.C[i][j]);
            }
    }
    expect_close("A, B, C against central differences of stewart_plant_derivatives", fidelity,
                 kStepForce, worst, worst_value);
    stewart_plant_free(plant);
    stewart_linearize_free(l);
}
static void test_plant_massless_with_frames(void) { plant_against_differences(STEWART_MASSLESS); }
static void test_plant_full_with_frames(void) { plant_against_differences(STEWART_FULL); }

/* The inverse side with frames against central differences of the inverse solver's lengths,
 * forces and base wrench (base frame) at tool poses, and its values against that solver's. */
static void inverse_against_differences(int fidelity) {
    with_frames();
    stewart_linearize *l = linearize_make(fidelity);
    uint64_t rng = 0x1f7au + (uint64_t)fidelity;
    double worst = 0, worst_value = 0;
    for (int n = 0; n < 8; ++n) {
        const stewart_pose pose = random_tool_pose(&rng);
        stewart_linearize_inverse_output exact;
        TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK, stewart_linearize_inverse(l, &pose, &exact),
                                  stewart_linearize_message(l));
        const stewart_inverse_output reference = solve_ok(data, fidelity, &pose);
        double value_scale[6] = {0};
        for (int k = 0; k < 6; ++k) {
            value_scale[0] = fmax(value_scale[0], fabs(reference.lengths.length[k]));
            value_scale[1] = fmax(value_scale[1], fabs(reference.lengths.length_rate[k]));
            value_scale[2] = fmax(value_scale[2], fabs(reference.lengths.length_accel[k]));
            value_scale[3] = fmax(value_scale[3], fabs(reference.force[k]));
        }
        for (int i = 0; i < 3; ++i) {
            value_scale[4] = fmax(value_scale[4], fabs(reference.base_force[i]));
            value_scale[5] = fmax(value_scale[5], fabs(reference.base_torque[i]));
        }
        for (int k = 0; k < 6; ++k) {
            const double e[4] = {exact.lengths.length[k] - reference.lengths.length[k],
                                 exact.lengths.length_rate[k] - reference.lengths.length_rate[k],
                                 exact.lengths.length_accel[k] - reference.lengths.length_accel[k],
                                 exact.force[k] - reference.force[k]};
            for (int r = 0; r < 4; ++r)
                worst_value = fmax(worst_value, fabs(e[r]) / value_scale[r]);
        }
        for (int i = 0; i < 3; ++i) {
            worst_value = fmax(worst_value, fabs(exact.base_force[i] - reference.base_force[i]) /
                                                value_scale[4]);
            worst_value = fmax(worst_value, fabs(exact.base_torque[i] - reference.base_torque[i]) /
                                                value_scale[5]);
        }
        const double e = inverse_jacobian_error(&exact, &pose, fidelity);
        if (e > worst) worst = e;
    }
    expect_close("inverse Jacobian against central differences of the inverse solver", fidelity,
                 kStepAccel, worst, worst_value);
    stewart_linearize_free(l);
}
static void test_inverse_massless_with_frames(void) {
    inverse_against_differences(STEWART_MASSLESS);
}
static void test_inverse_full_with_frames(void) { inverse_against_differences(STEWART_FULL); }

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_plant_massless_with_frames);
    RUN_TEST(test_plant_full_with_frames);
    RUN_TEST(test_inverse_massless_with_frames);
    RUN_TEST(test_inverse_full_with_frames);
    return UNITY_END();
}
