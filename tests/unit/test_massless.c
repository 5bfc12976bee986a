/* Massless-leg level: forces against statics by hand, heave in closed form, the power balance
 * of the platform, and the wrench on the base. */
#include <math.h>

#include "platform_fixture.h"
#include "test_support.h"
#include "unity.h"

/* At home, six identical legs share the weight: F = m g L / (6 h), h = 0.5 m. */
static void test_static_home_shares_weight(void) {
    stewart_pose home = {{0, 0, 0.5, 0, 0, 0}, {0}, {0}};
    stewart_inverse_output out = solve_ok(data, STEWART_MASSLESS, &home);
    const double m = params.platform_mass, g = 9.81;
    TEST_ASSERT_DOUBLE_WITHIN(5e-3, 106.03, m); /* the thesis' platform mass */
    for (int k = 0; k < 6; ++k) {
        TEST_ASSERT_DOUBLE_WITHIN(1e-10, m * g * out.lengths.length[k] / (6 * 0.5), out.force[k]);
        TEST_ASSERT_TRUE(out.force[k] > 0); /* a platform at rest loads its legs in compression */
    }
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 0.0, out.base_force[0]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 0.0, out.base_force[1]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, -m * g, out.base_force[2]);
    TEST_ASSERT_TRUE(out.condition >= 1.0);
}

/* Pure heave: six identical legs share m (g + z_ddot), each along its own axis: F = m (g + z_ddot) L / (6 z). */
static void test_heave_closed_form(void) {
    for (int i = 0; i <= 120; ++i) {
        stewart_pose pose = thesis_pose(2, 0.1 * i);
        stewart_inverse_output out = solve_ok(data, STEWART_MASSLESS, &pose);
        const double z = pose.q[2];
        const double expected = params.platform_mass * (9.81 + pose.q_ddot[2]) / (6 * z);
        for (int k = 0; k < 6; ++k)
            TEST_ASSERT_DOUBLE_WITHIN(1e-9 * expected * out.lengths.length[k],
                                      expected * out.lengths.length[k], out.force[k]);
    }
}

/* Static equilibrium with a payload off centre, checked about the world origin from the test's
 * own geometry: sum of leg forces and moments balances the weights. */
static void test_static_offset_payload_balances(void) {
    params.payload_mass = 80.0;
    params.payload_com[0] = 0.2;
    params.payload_com[1] = -0.1;
    params.payload_com[2] = 0.3;
    params.payload_inertia[0] = params.payload_inertia[1] = params.payload_inertia[2] = 2.0;
    rebuild_platform();

    const double x = 0.03, y = -0.02, z = 0.52, yaw = 0.2; /* no roll or pitch: R = Rz(yaw) */
    stewart_pose pose = {{x, y, z, 0, 0, yaw}, {0}, {0}};
    stewart_inverse_output out = solve_ok(data, STEWART_MASSLESS, &pose);
    const double c = cos(yaw), s = sin(yaw), g = 9.81;
    double f[3] = {0, 0, 0}, moment[3] = {0, 0, 0};
    for (int k = 0; k < 6; ++k) {
        const double bx = 0.5 * cos(params.platform_angle[k]),
                     by = 0.5 * sin(params.platform_angle[k]);
        const double P[3] = {x + c * bx - s * by, y + s * bx + c * by, z};
        const double A[3] = {0.5 * cos(params.base_angle[k]), 0.5 * sin(params.base_angle[k]), 0};
        double n[3] = {P[0] - A[0], P[1] - A[1], P[2] - A[2]};
        const double L = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double F[3];
        for (int i = 0; i < 3; ++i) F[i] = out.force[k] * n[i] / L;
        for (int i = 0; i < 3; ++i) f[i] += F[i];
        moment[0] += P[1] * F[2] - P[2] * F[1];
        moment[1] += P[2] * F[0] - P[0] * F[2];
        moment[2] += P[0] * F[1] - P[1] * F[0];
    }
    const double pc[3] = {0.2, -0.1, 0.3};
    const double C[3] = {x + c * pc[0] - s * pc[1], y + s * pc[0] + c * pc[1], z + pc[2]};
    const double W_plate = params.platform_mass * g, W_load = 80.0 * g;
    /* weights at the plate centre (x, y, z) and at the payload centre C, both along -z */
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 0.0, f[0]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 0.0, f[1]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, W_plate + W_load, f[2]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, W_plate * y + W_load * C[1], moment[0]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, -(W_plate * x + W_load * C[0]), moment[1]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 0.0, moment[2]);
    /* the base carries the whole weight, with the moment of the weights about the origin */
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, -(W_plate + W_load), out.base_force[2]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, -(W_plate * y + W_load * C[1]), out.base_torque[0]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, W_plate * x + W_load * C[0], out.base_torque[1]);
}

/* Kinetic plus potential energy of the platform (a disc with its centre at the origin of its
 * frame), from the pose alone: 1/2 m v^2 + 1/2 w' I w' + m g z, with the body rate w' obtained
 * from finite differences of the rotation matrix. */
static double platform_energy(double t, double h) {
    stewart_pose p = combined_pose(t);
    stewart_pose a = combined_pose(t - h), b = combined_pose(t + h);
    double R[3][3], Ra[3][3], Rb[3][3];
    const stewart_pose *ps[3] = {&p, &a, &b};
    double (*Rs[3])[3] = {R, Ra, Rb};
    for (int j = 0; j < 3; ++j) pose_rotation(ps[j], Rs[j]);
    /* skew(w') = R^T R_dot */
    double W[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            W[i][j] = 0;
            for (int k = 0; k < 3; ++k) W[i][j] += R[k][i] * (Rb[k][j] - Ra[k][j]) / (2 * h);
        }
    const double w[3] = {W[2][1], W[0][2], W[1][0]};
    const double m = params.platform_mass;
    double ke =
        0.5 * m * (p.q_dot[0] * p.q_dot[0] + p.q_dot[1] * p.q_dot[1] + p.q_dot[2] * p.q_dot[2]);
    for (int i = 0; i < 3; ++i) ke += 0.5 * params.platform_inertia[i] * w[i] * w[i];
    return ke + m * 9.81 * p.q[2];
}

/* Power balance: the legs' power sum F_k L_dot_k equals d/dt of the platform's energy. */
static void test_power_balance_combined_manoeuvre(void) {
    const double h = 1e-4;
    for (int i = 0; i < 40; ++i) {
        const double t = 0.2 + 0.211 * i;
        stewart_pose pose = combined_pose(t);
        stewart_inverse_output out = solve_ok(data, STEWART_MASSLESS, &pose);
        double power = 0;
        for (int k = 0; k < 6; ++k) power += out.force[k] * out.lengths.length_rate[k];
        const double dE = (platform_energy(t + h, 1e-6) - platform_energy(t - h, 1e-6)) / (2 * h);
        TEST_ASSERT_DOUBLE_WITHIN(1e-4 * (1 + fabs(power)), dE, power);
    }
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_static_home_shares_weight);
    RUN_TEST(test_heave_closed_form);
    RUN_TEST(test_static_offset_payload_balances);
    RUN_TEST(test_power_balance_combined_manoeuvre);
    return UNITY_END();
}
