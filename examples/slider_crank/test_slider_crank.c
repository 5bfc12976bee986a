/* The thesis' slider-crank on the core: slider position, velocity and acceleration against the
 * closed form, q_dot and q_ddot against finite differences of q, and the crank torque against
 * the energy balance tau phi_dot = dE/dt. */
#include <math.h>
#include <string.h>

#include "slider_crank.h"
#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#include "unity.h"

#define NQ 28

static slider_crank_params params;
static slider_crank_layout layout;
static mbs_model *model;
static mbs_data *data;
static mbs_options options;
static const double omega = 10.0 * 2.0 * M_PI / 60.0; /* 10 rpm */

void setUp(void) {
    slider_crank_params_default(&params);
    char msg[MBS_MESSAGE_SIZE];
    model = slider_crank_create(&params, &layout, msg, sizeof msg);
    if (!model) TEST_FAIL_MESSAGE(msg);
    TEST_ASSERT_EQUAL(NQ, mbs_coordinate_count(model));
    data = mbs_data_create(model, MBS_LINEAR_AUTOMATIC);
    TEST_ASSERT_NOT_NULL(data);
    mbs_options_default(&options);
}

void tearDown(void) {
    mbs_data_free(data);
    mbs_model_free(model);
}

static void step(mbs_data *d, double t) {
    mbs_set_driver(d, layout.crank_driver, omega * t, omega, 0.0);
    TEST_ASSERT_EQUAL_MESSAGE(MBS_OK, mbs_step(d, t, &options), mbs_data_message(d));
}

/* Two turns: x = r cos phi + sqrt(l^2 - r^2 sin^2 phi) and its derivatives at constant phi_dot. */
static void test_slider_closed_form(void) {
    const double r = 1.0, l = 2.0;
    double x_min = 10, x_max = -10;
    int max_iterations = 0;
    for (int i = 0; i <= 1200; ++i) {
        const double t = 0.01 * i, phi = omega * t, s = sin(phi), c = cos(phi);
        step(data, t);
        const double D = sqrt(l * l - r * r * s * s);
        const double x = r * c + D;
        const double x_dot = -omega * r * s * (1 + r * c / D);
        const double x_ddot =
            -omega * omega *
            (r * c + r * r * (c * c - s * s) / D + pow(r * r * s * c, 2) / pow(D, 3));
        const int b = MBS_BODY_R(layout.slider);
        TEST_ASSERT_DOUBLE_WITHIN(1e-11, x, mbs_q(data)[b]);
        TEST_ASSERT_DOUBLE_WITHIN(1e-11, 0.0, mbs_q(data)[b + 1]);
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, x_dot, mbs_q_dot(data)[b]);
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, x_ddot, mbs_q_ddot(data)[b]);
        /* The crank pin stays on its circle. */
        const double *qc = mbs_q(data) + MBS_BODY_R(layout.crank);
        TEST_ASSERT_DOUBLE_WITHIN(1e-11, 0.5 * c, qc[0]);
        TEST_ASSERT_DOUBLE_WITHIN(1e-11, 0.5 * s, qc[1]);
        if (x < x_min) x_min = mbs_q(data)[b];
        if (x > x_max) x_max = mbs_q(data)[b];
        if (mbs_iterations(data) > max_iterations) max_iterations = mbs_iterations(data);
    }
    TEST_ASSERT_DOUBLE_WITHIN(1e-6, 1.0, x_min);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 3.0, x_max);
    TEST_ASSERT_TRUE(max_iterations <= 3); /* the predictor keeps Newton short */
}

/* q_dot and q_ddot of every coordinate against central differences of q(t). */
static void test_rates_against_finite_differences(void) {
    mbs_data *side = mbs_data_create(model, MBS_LINEAR_DENSE);
    /* q is exact to the Newton tolerance (1e-12): h = 1e-4 for the first difference, 1e-3 for
     * the second keep that noise below the truncation error. */
    const double steps[2] = {1e-4, 1e-3};
    for (int i = 0; i <= 1200; i += 37)
        for (int which = 0; which < 2; ++which) {
            const double t = 0.01 * i, h = steps[which];
            double qp[NQ], qm[NQ], q0[NQ];
            /* Step a side copy to t - h and t + h so Euler-parameter signs stay continuous. */
            step(data, t);
            TEST_ASSERT_EQUAL(MBS_OK, mbs_data_copy(side, data));
            step(side, t + h);
            memcpy(qp, mbs_q(side), sizeof qp);
            TEST_ASSERT_EQUAL(MBS_OK, mbs_data_copy(side, data));
            step(side, t - h);
            memcpy(qm, mbs_q(side), sizeof qm);
            memcpy(q0, mbs_q(data), sizeof q0);
            for (int k = 0; k < NQ; ++k) {
                if (which == 0)
                    TEST_ASSERT_DOUBLE_WITHIN(1e-7, (qp[k] - qm[k]) / (2 * h), mbs_q_dot(data)[k]);
                else
                    TEST_ASSERT_DOUBLE_WITHIN(1e-5, (qp[k] - 2 * q0[k] + qm[k]) / (h * h),
                                              mbs_q_ddot(data)[k]);
            }
        }
    mbs_data_free(side);
}

/* Kinetic + potential energy of crank, rod and slider, planar, written out here. */
static double energy(const double *q, const double *v) {
    const int bodies[3] = {layout.crank, layout.rod, layout.slider};
    const double mass[3] = {1.0, 2.0, 3.0}, inertia[3] = {1.0 / 12, 2.0 * 4 / 12, 0.0};
    double e = 0;
    for (int i = 0; i < 3; ++i) {
        const double *r = q + MBS_BODY_R(bodies[i]), *rd = v + MBS_BODY_R(bodies[i]);
        const double *p = r + 3, *pd = rd + 3;
        /* planar rotation about z: p = (cos th/2, 0, 0, sin th/2), th_dot = 2 (e0 e3_dot - e3 e0_dot) */
        const double th_dot = 2 * (p[0] * pd[3] - p[3] * pd[0]);
        e += 0.5 * mass[i] * (rd[0] * rd[0] + rd[1] * rd[1] + rd[2] * rd[2]) +
             0.5 * inertia[i] * th_dot * th_dot + mass[i] * 9.81 * r[1];
    }
    return e;
}

/* mbs_energy (the core's general form) against the planar one written out above. */
static void test_core_energy_equals_planar_energy(void) {
    for (int i = 0; i <= 1200; i += 17) {
        step(data, 0.01 * i);
        const double e = energy(mbs_q(data), mbs_q_dot(data));
        TEST_ASSERT_DOUBLE_WITHIN(1e-12 * (1 + fabs(e)), e,
                                  mbs_energy(data, mbs_q(data), mbs_q_dot(data)));
    }
}

/* Joint reactions against Newton's laws: the slider (no rotary inertia) moves as the Cardan and
 * the guide push it, m (a - g) = F_cardan + F_guide, with no net torque; the crank bearing pushes
 * the ground and the crank equally and oppositely. */
static void test_joint_reactions_obey_newton(void) {
    const double slider_mass = 3.0, g = 9.81;
    for (int i = 0; i <= 1200; i += 19) {
        step(data, 0.01 * i);
        double fc[3], nc[3], fg[3], ng[3], f0[3], n0[3], f1[3], n1[3];
        TEST_ASSERT_EQUAL(MBS_OK, mbs_joint_reaction(data, layout.rod_slider_cardan, 1, fc, nc));
        TEST_ASSERT_EQUAL(MBS_OK, mbs_joint_reaction(data, layout.slider_guide, 1, fg, ng));
        const double *a = mbs_q_ddot(data) + MBS_BODY_R(layout.slider);
        const double weight[3] = {0, -slider_mass * g, 0};
        for (int c = 0; c < 3; ++c) {
            TEST_ASSERT_DOUBLE_WITHIN(1e-9, slider_mass * a[c] - weight[c], fc[c] + fg[c]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-9, 0.0, nc[c] + ng[c]);
        }
        TEST_ASSERT_EQUAL(MBS_OK, mbs_joint_reaction(data, layout.crank_bearing, 0, f0, n0));
        TEST_ASSERT_EQUAL(MBS_OK, mbs_joint_reaction(data, layout.crank_bearing, 1, f1, n1));
        for (int c = 0; c < 3; ++c) TEST_ASSERT_DOUBLE_WITHIN(1e-9, 0.0, f0[c] + f1[c]);
    }
    double f[3], n[3];
    TEST_ASSERT_EQUAL(MBS_ERR_ARGUMENT, mbs_joint_reaction(data, 99, 0, f, n));
    TEST_ASSERT_EQUAL(MBS_ERR_ARGUMENT, mbs_joint_reaction(data, layout.slider_guide, 2, f, n));
}

static void test_crank_torque_energy_balance(void) {
    mbs_data *side = mbs_data_create(model, MBS_LINEAR_AUTOMATIC);
    const int row = mbs_joint_first_row(model, layout.crank_driver_joint);
    double torque_min = 1e9, torque_max = -1e9;
    for (int i = 0; i <= 1200; i += 13) {
        const double t = 0.01 * i, h = 1e-5;
        step(data, t);
        const double tau = mbs_lambda(data)[row];
        mbs_data_copy(side, data);
        step(side, t + h);
        const double ep = energy(mbs_q(side), mbs_q_dot(side));
        mbs_data_copy(side, data);
        step(side, t - h);
        const double em = energy(mbs_q(side), mbs_q_dot(side));
        TEST_ASSERT_DOUBLE_WITHIN(1e-6, (ep - em) / (2 * h), tau * omega);
        if (tau < torque_min) torque_min = tau;
        if (tau > torque_max) torque_max = tau;
    }
    /* Gravity dominates at 10 rpm: the torque swings both ways, of order m g r. */
    TEST_ASSERT_TRUE(torque_min < -1.0 && torque_max > 1.0);
    mbs_data_free(side);
}

/* Modified Newton reaches the same answer. */
static void test_modified_newton(void) {
    mbs_data *other = mbs_data_create(model, MBS_LINEAR_DENSE);
    mbs_options modified = options;
    modified.modified_newton = 1;
    for (int i = 0; i <= 600; i += 5) {
        const double t = 0.02 * i;
        step(data, t);
        mbs_set_driver(other, layout.crank_driver, omega * t, omega, 0.0);
        TEST_ASSERT_EQUAL(MBS_OK, mbs_step(other, t, &modified));
        for (int k = 0; k < NQ; ++k)
            TEST_ASSERT_DOUBLE_WITHIN(1e-11, mbs_q(data)[k], mbs_q(other)[k]);
    }
    mbs_data_free(other);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_slider_closed_form);
    RUN_TEST(test_rates_against_finite_differences);
    RUN_TEST(test_crank_torque_energy_balance);
    RUN_TEST(test_core_energy_equals_planar_energy);
    RUN_TEST(test_joint_reactions_obey_newton);
    RUN_TEST(test_modified_newton);
    return UNITY_END();
}
