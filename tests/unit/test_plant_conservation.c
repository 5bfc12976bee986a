/* Forward dynamics against conservation laws: kinetic energy of a free motion, kinetic plus
 * potential under gravity, the power balance of the actuators, the static equilibrium from the
 * inverse side; and the leg bodies' joints and velocities checked from their poses alone. */
#include <math.h>
#include <stdio.h>

#include "stewart/stewart_plant.h"
#include "test_plant_support.h"
#include "test_support.h"
#include "unity.h"

static stewart_params params;
static stewart_model *model;

void setUp(void) {
    stewart_params_default(&params);
    heavy_legs(&params);
    model = NULL;
}

void tearDown(void) {
    stewart_model_free(model);
    model = NULL;
}

static const double kZero[6] = {0};

/* A small twist that keeps every leg within its stroke for 10 s. */
static const double kStartPose[6] = {0.01, -0.02, 0.52, 0.02, -0.03, 0.05};
static const double kStartRate[6] = {0.004, -0.003, 0.002, 0.02, -0.015, 0.03};

static void free_motion_keeps_kinetic_energy(int fidelity) {
    params.gravity[2] = 0;
    model = test_model(&params);
    stewart_plant *plant = test_plant(model, fidelity, 1e-13, 1e-15);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(plant, 0, kStartPose, kStartRate));
    double T0, U0, T, U, worst = 0;
    plant_energy(&params, plant, fidelity, &T0, &U0);
    TEST_ASSERT_TRUE(T0 > 1e-3);
    for (int i = 1; i <= 10000; ++i) {
        step_ok(plant, 1e-3, kZero, kZero, NULL, NULL);
        plant_energy(&params, plant, fidelity, &T, &U);
        if (fabs(T - T0) > worst) worst = fabs(T - T0);
    }
    stewart_plant_statistics st;
    stewart_plant_statistics_get(plant, &st);
    printf("free motion, fidelity %d: T0 = %.6g J, max |T - T0| / T0 = %.3g over 10 s "
           "(%ld steps, %ld rhs)\n",
           fidelity, T0, worst / T0, st.total_steps, st.total_rhs_evaluations);
    TEST_ASSERT_TRUE(worst <= 1e-9 * T0);
    stewart_plant_free(plant);
}

static void test_free_motion_keeps_kinetic_energy_full(void) {
    free_motion_keeps_kinetic_energy(STEWART_FULL);
}

static void test_free_motion_keeps_kinetic_energy_massless(void) {
    free_motion_keeps_kinetic_energy(STEWART_MASSLESS);
}


/* Gravity on, no forces: the platform falls; kinetic plus potential energy stays constant until
 * the first leg leaves its stroke (the plant's warning). */
static void test_fall_keeps_total_energy(void) {
    model = test_model(&params);
    stewart_plant *plant = test_plant(model, STEWART_FULL, 1e-13, 1e-15);
    const double rate[6] = {0.01, 0.02, 0.8, 0.1, -0.05, 0.2}; /* thrown upward first */
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(plant, 0, kStartPose, rate));
    double T0, U0, T, U, worst = 0, t = 0;
    plant_energy(&params, plant, STEWART_FULL, &T0, &U0);
    stewart_plant_output out;
    for (;;) {
        step_ok(plant, 1e-3, kZero, kZero, NULL, NULL);
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &out));
        if (out.warnings & STEWART_WARN_STROKE) break;
        t = out.time;
        plant_energy(&params, plant, STEWART_FULL, &T, &U);
        if (fabs(T + U - T0 - U0) > worst) worst = fabs(T + U - T0 - U0);
    }
    printf("fall: %.3f s until %s; max |E - E0| / T0 = %.3g\n", out.time,
           stewart_plant_message(plant), worst / T0);
    TEST_ASSERT_TRUE(t > 0.15);
    TEST_ASSERT_TRUE(worst <= 1e-9 * T0);
    stewart_plant_free(plant);
}

/* A forced motion: the actuators' work int sum F_k L_dot_k dt (Simpson's rule over the
 * communication points) equals the change of kinetic plus potential energy. */
static void power_balance(int fidelity) {
    model = test_model(&params);
    stewart_plant *plant = test_plant(model, fidelity, 1e-13, 1e-15);
    const double h = 1e-4;
    const int steps = 10000; /* 1 s */
    double T0, U0, T, U, work = 0, power_prev = 0, f_prev[6];
    plant_energy(&params, plant, fidelity, &T0, &U0);
    /* The static forces at home (inverse side) plus sinusoids of 1 %. */
    stewart_inverse *data = test_inverse(model);
    stewart_pose home = {{0, 0, params.home_height, 0, 0, 0}, {0}, {0}};
    const stewart_inverse_output statics = solve_ok(data, fidelity, &home);
    stewart_inverse_free(data);
    for (int i = 0; i <= steps; ++i) {
        const double t = i * h;
        double f[6], power = 0;
        for (int k = 0; k < 6; ++k) f[k] = statics.force[k] * (1.0 + 0.01 * sin((2.0 + k) * t + k));
        if (i > 0) step_ok(plant, h, f_prev, f, NULL, NULL);
        stewart_plant_output out;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, f, &out));
        TEST_ASSERT_EQUAL(0, out.warnings);
        for (int k = 0; k < 6; ++k) power += f[k] * out.lengths.length_rate[k], f_prev[k] = f[k];
        /* Simpson over [t - 2h, t] on every second point; power_prev holds the middle one. */
        static double power_first;
        if (i == 0) power_first = power;
        else if (i % 2 == 0)
            work += h / 3.0 * (power_first + 4.0 * power_prev + power), power_first = power;
        power_prev = power;
    }
    plant_energy(&params, plant, fidelity, &T, &U);
    const double change = T + U - T0 - U0;
    printf("power balance, fidelity %d: work %.12g J, energy change %.12g J, difference %.3g\n",
           fidelity, work, change, work - change);
    TEST_ASSERT_TRUE(fabs(work) > 1e-3);
    TEST_ASSERT_DOUBLE_WITHIN(1e-8 * fabs(work), work, change);
    stewart_plant_free(plant);
}

static void test_power_balance_full(void) { power_balance(STEWART_FULL); }
static void test_power_balance_massless(void) { power_balance(STEWART_MASSLESS); }

/* F = the static forces of a pose from the inverse side: the platform stays at rest. */
static void equilibrium(int fidelity, const double pose_q[6], double seconds, double bound) {
    model = test_model(&params);
    stewart_inverse *data = test_inverse(model);
    stewart_pose pose = {{0}, {0}, {0}};
    for (int i = 0; i < 6; ++i) pose.q[i] = pose_q[i];
    const stewart_inverse_output inverse = solve_ok(data, fidelity, &pose);
    stewart_plant *plant = test_plant(model, fidelity, 1e-10, 1e-12);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(plant, 0, pose.q, kZero));
    double worst = 0, worst_t = 0;
    const int steps = (int)(seconds / 1e-3 + 0.5);
    for (int i = 1; i <= steps; ++i) {
        step_ok(plant, 1e-3, inverse.force, inverse.force, NULL, NULL);
        stewart_plant_output out;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &out));
        for (int c = 0; c < 3; ++c)
            if (fabs(out.pose.q[c] - pose.q[c]) > worst)
                worst = fabs(out.pose.q[c] - pose.q[c]), worst_t = out.time;
    }
    printf("equilibrium, fidelity %d: max displacement %.3g m (at t = %g s) over %g s\n", fidelity,
           worst, worst_t, seconds);
    TEST_ASSERT_TRUE(worst <= bound);
    stewart_plant_free(plant);
    stewart_inverse_free(data);
}

static void test_equilibrium_full(void) {
    const double home[6] = {0, 0, 0.5, 0, 0, 0};
    equilibrium(STEWART_FULL, home, 2.0, 1e-12);
}

static void test_equilibrium_massless_tilted(void) {
    const double tilted[6] = {0.02, -0.01, 0.53, 0.05, -0.04, 0.1};
    equilibrium(STEWART_MASSLESS, tilted, 2.0, 1e-12);
}


/* Every leg body on its joints as model.md defines them, from the bodies' poses and the
 * platform pose output alone: Cardan centres on a_k and on p + R b_k, cross arms perpendicular,
 * cylinder and piston on one axis; and the bodies' velocities equal to differences of their
 * positions and rotations over a step. */
static void test_leg_bodies_on_their_joints(void) {
    params.gravity[2] = 0;
    model = test_model(&params);
    stewart_plant *plant = test_plant(model, STEWART_FULL, 1e-12, 1e-14);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(plant, 0, kStartPose, kStartRate));
    const double h = 1e-4;
    double worst_joint = 0, worst_velocity = 0, worst_omega = 0;
    stewart_plant_body before[STEWART_PLANT_BODIES], after[STEWART_PLANT_BODIES];
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_bodies(plant, before));
    for (int i = 1; i <= 2000; ++i) {
        const double f[6] = {5 * sin(3.0 * i * h), -4.0, 3.0, 2 * cos(i * h), 0, 1};
        step_ok(plant, h, f, f, NULL, NULL);
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_bodies(plant, after));
        stewart_plant_output out;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, f, &out));
        const double e = leg_joint_error(&params, out.pose.q, after);
        if (e > worst_joint) worst_joint = e;
        for (int b = 0; b < STEWART_PLANT_BODIES; ++b) {
            /* (r1 - r0) / h against the mean velocity; skew part of R1 R0^T / h against omega */
            double dR[3][3];
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c) {
                    dR[r][c] = 0;
                    for (int j = 0; j < 3; ++j)
                        dR[r][c] += after[b].rotation[3 * r + j] * before[b].rotation[3 * c + j];
                }
            const double w[3] = {(dR[2][1] - dR[1][2]) / (2 * h), (dR[0][2] - dR[2][0]) / (2 * h),
                                 (dR[1][0] - dR[0][1]) / (2 * h)};
            for (int r = 0; r < 3; ++r) {
                const double v_mean = 0.5 * (after[b].velocity[r] + before[b].velocity[r]);
                const double w_mean = 0.5 * (after[b].omega[r] + before[b].omega[r]);
                const double dv = fabs((after[b].position[r] - before[b].position[r]) / h - v_mean);
                if (dv > worst_velocity) worst_velocity = dv;
                if (fabs(w[r] - w_mean) > worst_omega) worst_omega = fabs(w[r] - w_mean);
            }
        }
        for (int b = 0; b < STEWART_PLANT_BODIES; ++b) before[b] = after[b];
    }
    printf("leg bodies: joint error %.3g, velocity vs difference %.3g m/s, omega vs difference "
           "%.3g rad/s\n",
           worst_joint, worst_velocity, worst_omega);
    TEST_ASSERT_TRUE(worst_joint <= 1e-12);
    TEST_ASSERT_TRUE(worst_velocity <= 1e-8);
    TEST_ASSERT_TRUE(worst_omega <= 1e-8);
    stewart_plant_free(plant);
}


/* The four integrators (ARKODE explicit Runge-Kutta 4(3) and 5(4), CVODE Adams, CVODE BDF with
 * a dense Jacobian) agree along a forced motion of the heavy-legged platform. */
static void test_integrators_agree(void) {
    model = test_model(&params);
    stewart_inverse *data = test_inverse(model);
    stewart_pose home = {{0, 0, params.home_height, 0, 0, 0}, {0}, {0}};
    const stewart_inverse_output statics = solve_ok(data, STEWART_FULL, &home);
    stewart_inverse_free(data);
    double pose[4][6];
    for (int method = 0; method < 4; ++method) {
        stewart_plant_options o;
        stewart_plant_options_default(&o);
        o.method = method;
        o.relative_tolerance = 1e-12;
        o.absolute_tolerance = 1e-14;
        o.max_internal_steps = 100000;
        char msg[STEWART_MESSAGE_SIZE];
        stewart_plant *plant = stewart_plant_create(model, &o, msg, sizeof msg);
        TEST_ASSERT_NOT_NULL_MESSAGE(plant, msg);
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(plant, 0, kStartPose, kStartRate));
        double f0[6], f1[6];
        for (int k = 0; k < 6; ++k) f0[k] = statics.force[k];
        for (int i = 1; i <= 500; ++i) {
            for (int k = 0; k < 6; ++k) f1[k] = statics.force[k] * (1 + 0.02 * sin(0.01 * i + k));
            step_ok(plant, 1e-3, f0, f1, NULL, NULL);
            for (int k = 0; k < 6; ++k) f0[k] = f1[k];
        }
        stewart_plant_output out;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &out));
        for (int c = 0; c < 6; ++c) pose[method][c] = out.pose.q[c];
        stewart_plant_free(plant);
    }
    double worst = 0;
    for (int method = 1; method < 4; ++method)
        for (int c = 0; c < 6; ++c)
            if (fabs(pose[method][c] - pose[0][c]) > worst)
                worst = fabs(pose[method][c] - pose[0][c]);
    printf("integrators: max pose difference %.3g after 0.5 s\n", worst);
    TEST_ASSERT_TRUE(worst <= 1e-9);
}


/* Solves A x = b (6 x 6, partial pivoting); A and b are overwritten. */
static void solve6(double A[6][6], double b[6]) {
    for (int c = 0; c < 6; ++c) {
        int p = c;
        for (int r = c + 1; r < 6; ++r)
            if (fabs(A[r][c]) > fabs(A[p][c])) p = r;
        for (int j = 0; j < 6; ++j) {
            const double t = A[c][j];
            A[c][j] = A[p][j], A[p][j] = t;
        }
        const double t = b[c];
        b[c] = b[p], b[p] = t;
        for (int r = c + 1; r < 6; ++r) {
            const double f = A[r][c] / A[c][c];
            for (int j = c; j < 6; ++j) A[r][j] -= f * A[c][j];
            b[r] -= f * b[c];
        }
    }
    for (int c = 5; c >= 0; --c) {
        for (int j = c + 1; j < 6; ++j) b[c] -= A[c][j] * b[j];
        b[c] /= A[c][c];
    }
}

/* Why the equilibrium check stops at 2 s: under its static forces the platform is a saddle. The
 * inverse side alone predicts the fastest divergence: with F(q, q_dot, q_ddot) its forces, the
 * plant at constant F moves as F_q dq + F_qddot dq_ddot = 0, so dq_ddot = A dq with
 * A = -F_qddot^-1 F_q (central differences of stewart_inverse_solve), whose largest eigenvalue
 * lambda^2 (power iteration) gives dq(t) = dq(0) cosh(lambda t) along its eigenvector. The
 * plant, started there, must follow it. */
static void test_equilibrium_is_a_saddle_at_the_predicted_rate(void) {
    stewart_params_default(&params); /* the thesis legs; the massless level */
    model = test_model(&params);
    stewart_inverse *data = test_inverse(model);
    stewart_pose pose = {{0, 0, params.home_height, 0, 0, 0}, {0}, {0}};
    const stewart_inverse_output statics = solve_ok(data, STEWART_MASSLESS, &pose);
    double Fq[6][6], Fa[6][6];
    const double delta = 1e-6;
    for (int j = 0; j < 6; ++j) {
        double *rows[2] = {pose.q, pose.q_ddot};
        for (int which = 0; which < 2; ++which) {
            rows[which][j] += delta;
            const stewart_inverse_output plus = solve_ok(data, STEWART_MASSLESS, &pose);
            rows[which][j] -= 2 * delta;
            const stewart_inverse_output minus = solve_ok(data, STEWART_MASSLESS, &pose);
            rows[which][j] += delta;
            for (int k = 0; k < 6; ++k)
                (which ? Fa : Fq)[k][j] = (plus.force[k] - minus.force[k]) / (2 * delta);
        }
    }
    stewart_inverse_free(data);
    double v[6] = {1, 0.3, -0.2, 0.5, 0.1, -0.4}, lambda2 = 0;
    for (int it = 0; it < 300; ++it) {
        double w[6], M[6][6], norm = 0, v_norm = 0;
        for (int k = 0; k < 6; ++k) {
            w[k] = 0;
            for (int j = 0; j < 6; ++j) w[k] -= Fq[k][j] * v[j], M[k][j] = Fa[k][j];
        }
        solve6(M, w); /* w = A v */
        for (int k = 0; k < 6; ++k) norm += w[k] * w[k], v_norm += v[k] * v[k];
        lambda2 = sqrt(norm / v_norm);
        for (int k = 0; k < 6; ++k) v[k] = w[k] / sqrt(norm);
    }
    const double lambda = sqrt(lambda2);
    stewart_plant *plant = test_plant(model, STEWART_MASSLESS, 1e-13, 1e-18);
    const double eps = 1e-9;
    double start[6];
    for (int c = 0; c < 6; ++c) start[c] = pose.q[c] + eps * v[c];
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(plant, 0, start, kZero));
    for (int i = 0; i < 2000; ++i) step_ok(plant, 1e-3, statics.force, statics.force, NULL, NULL);
    stewart_plant_output out;
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &out));
    double worst = 0;
    for (int c = 0; c < 6; ++c) {
        const double expected = eps * v[c] * cosh(lambda * 2.0);
        if (fabs(out.pose.q[c] - pose.q[c] - expected) > worst)
            worst = fabs(out.pose.q[c] - pose.q[c] - expected);
    }
    printf("saddle: fastest divergence %.4f 1/s predicted by the inverse side; after 2 s the plant "
           "is off the prediction by %.3g of the %.3g m grown\n",
           lambda, worst / (eps * cosh(2 * lambda)), eps * cosh(2 * lambda));
    TEST_ASSERT_TRUE(lambda > 4.0); /* a saddle: 1e-16 grows past 1e-12 within 2 to 3 s */
    TEST_ASSERT_TRUE(worst <= 1e-3 * eps * cosh(2 * lambda));
    stewart_plant_free(plant);
}


/* Joint reactions against two balances they do not enter: the base wrench (momentum of all the
 * moving bodies) must be minus the base Cardans' reactions, and the platform's acceleration
 * (central differences of its velocity) must follow from the platform Cardans' reactions and
 * gravity. Heavy legs, a forced motion, both fidelities. */
static void joint_reactions_balance(int fidelity) {
    model = test_model(&params);
    stewart_inverse *data = test_inverse(model);
    stewart_pose home = {{0, 0, params.home_height, 0, 0, 0}, {0}, {0}};
    const stewart_inverse_output statics = solve_ok(data, fidelity, &home);
    stewart_inverse_free(data);
    stewart_plant *plant = test_plant(model, fidelity, 1e-12, 1e-14);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(plant, 0, kStartPose, kStartRate));
    const double h = 1e-3;
    double f_prev[6], f[6], v_prev[3] = {0}, v_now[3] = {0}, worst_base = 0, worst_platform = 0;
    stewart_plant_reactions r_now;
    for (int k = 0; k < 6; ++k) f_prev[k] = statics.force[k];
    for (int i = 1; i <= 300; ++i) {
        for (int k = 0; k < 6; ++k) f[k] = statics.force[k] * (1 + 0.05 * sin(20.0 * i * h + k));
        step_ok(plant, h, f_prev, f, NULL, NULL);
        stewart_plant_body bodies[STEWART_PLANT_BODIES];
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_bodies(plant, bodies));
        if (i % 50 == 1 && i > 1) {
            /* at the point of the reactions (the step before this one): the platform's
             * acceleration from its velocity either side */
            double residual = 0;
            for (int a = 0; a < 3; ++a) {
                const double acc = (bodies[0].velocity[a] - v_prev[a]) / (2 * h);
                double applied = params.platform_mass * params.gravity[a];
                for (int k = 0; k < 6; ++k) applied -= r_now.platform_cardan_force[k][a];
                residual = fmax(residual, fabs(params.platform_mass * acc - applied));
            }
            worst_platform = fmax(worst_platform, residual);
        }
        if (i % 50 == 0) {
            stewart_plant_output out;
            TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, f, &out));
            TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_reactions_get(plant, f, &r_now));
            worst_base = fmax(worst_base, base_wrench_error(&params, &r_now, &out));
            for (int a = 0; a < 3; ++a) v_prev[a] = v_now[a]; /* the step before */
        }
        for (int a = 0; a < 3; ++a) v_now[a] = bodies[0].velocity[a];
        for (int k = 0; k < 6; ++k) f_prev[k] = f[k];
    }
    printf("joint reactions, fidelity %d: base wrench %.3g N or N m off the momentum balance, "
           "platform %.3g N off Newton's law (differences of velocities)\n",
           fidelity, worst_base, worst_platform);
    TEST_ASSERT_TRUE(worst_base <= 1e-9);
    TEST_ASSERT_TRUE(worst_platform <= 1e-3); /* of about 1040 N of weight */
    stewart_plant_free(plant);
}

static void test_joint_reactions_balance_full(void) { joint_reactions_balance(STEWART_FULL); }
static void test_joint_reactions_balance_massless(void) {
    joint_reactions_balance(STEWART_MASSLESS);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_free_motion_keeps_kinetic_energy_full);
    RUN_TEST(test_free_motion_keeps_kinetic_energy_massless);
    RUN_TEST(test_leg_bodies_on_their_joints);
    RUN_TEST(test_integrators_agree);
    RUN_TEST(test_joint_reactions_balance_full);
    RUN_TEST(test_joint_reactions_balance_massless);
    RUN_TEST(test_fall_keeps_total_energy);
    RUN_TEST(test_power_balance_full);
    RUN_TEST(test_power_balance_massless);
    RUN_TEST(test_equilibrium_full);
    RUN_TEST(test_equilibrium_massless_tilted);
    RUN_TEST(test_equilibrium_is_a_saddle_at_the_predicted_rate);
    return UNITY_END();
}
