/* The inverse's drive columns through the C API: the published reflected mass of an electric
 * cylinder (looms-polimi/Parallel_manipulators' defaults), no drive leaves every other column
 * as it was and the drive columns zero, a drive leaves the other columns unchanged, the batch's
 * vector path gives the single solve's drive columns to rounding, and the currents' rates along
 * a trajectory are central differences written out here. */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "stewart/stewart_batch.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

#define ROWS 40
static char message[STEWART_MESSAGE_SIZE];

/* A smooth manoeuvre around the thesis platform's home, all six axes. */
static void manoeuvre(double t, stewart_pose *p) {
    const double amplitude[6] = {0.05, -0.04, 0.03, 0.05, -0.04, 0.06}, w = 2.0;
    for (int i = 0; i < 6; ++i) {
        const double phase = 0.3 * i;
        p->q[i] = amplitude[i] * sin(w * t + phase) + (i == 2 ? 0.5 : 0.0);
        p->q_dot[i] = amplitude[i] * w * cos(w * t + phase);
        p->q_ddot[i] = -amplitude[i] * w * w * sin(w * t + phase);
    }
}

/* The electric cylinder of looms-polimi/Parallel_manipulators on every leg: 5 mm lead, gear
 * ratio 3, rotor inertia 1.37e-4 kg.m2; a motor of 0.5 N.m/A, 1.2 Ohm, 3 mH; friction. */
static void looms_drives(stewart_params *p) {
    for (int k = 0; k < STEWART_LEGS; ++k) {
        p->screw_lead[k] = 0.005;
        p->gear_ratio[k] = 3;
        p->rotor_inertia[k] = 1.37e-4;
        p->torque_constant[k] = 0.5;
        p->winding_resistance[k] = 1.2;
        p->winding_inductance[k] = 3e-3;
        p->screw_efficiency[k] = 0.9;
        p->screw_back_efficiency[k] = 0.8;
        p->coulomb_friction[k] = 20;
        p->stribeck_friction[k] = 30;
        p->stribeck_speed[k] = 0.01;
        p->viscous_friction[k] = 100;
    }
}

static stewart_inverse *solver(const stewart_params *p, int fidelity, stewart_model **m) {
    *m = stewart_model_create(p, message, sizeof message);
    TEST_ASSERT_NOT_NULL_MESSAGE(*m, message);
    stewart_inverse_options o;
    stewart_inverse_options_default(&o);
    o.fidelity = fidelity;
    stewart_inverse *inv = stewart_inverse_create(*m, &o, message, sizeof message);
    TEST_ASSERT_NOT_NULL_MESSAGE(inv, message);
    return inv;
}

static void test_the_published_reflected_mass(void) {
    stewart_params p;
    stewart_params_default(&p);
    looms_drives(&p);
    p.screw_lead[5] = 0; /* leg 6 without a drive */
    p.gear_ratio[5] = 1, p.rotor_inertia[5] = 0, p.torque_constant[5] = 0;
    p.winding_resistance[5] = p.winding_inductance[5] = 0;
    p.screw_efficiency[5] = p.screw_back_efficiency[5] = 1;
    p.coulomb_friction[5] = p.stribeck_friction[5] = p.stribeck_speed[5] = 0;
    p.viscous_friction[5] = 0;
    stewart_model *m = stewart_model_create(&p, message, sizeof message);
    TEST_ASSERT_NOT_NULL_MESSAGE(m, message);
    double mass[STEWART_LEGS];
    stewart_model_reflected_mass(m, mass);
    for (int k = 0; k < 5; ++k) TEST_ASSERT_DOUBLE_WITHIN(0.005, 1947.08, mass[k]);
    TEST_ASSERT_EQUAL_DOUBLE(0.0, mass[5]);
    stewart_model_free(m);
}

/* Every column before the drives' equal, bit for bit. */
static void assert_same_legs(const stewart_inverse_output *a, const stewart_inverse_output *b) {
    TEST_ASSERT_EQUAL_MEMORY(&a->lengths, &b->lengths, sizeof a->lengths);
    TEST_ASSERT_EQUAL_MEMORY(a->force, b->force, sizeof a->force);
    TEST_ASSERT_EQUAL_MEMORY(&a->condition, &b->condition, sizeof a->condition);
    TEST_ASSERT_EQUAL_MEMORY(&a->residual, &b->residual, sizeof a->residual);
    TEST_ASSERT_EQUAL_MEMORY(a->base_force, b->base_force, sizeof a->base_force);
    TEST_ASSERT_EQUAL_MEMORY(a->base_torque, b->base_torque, sizeof a->base_torque);
    TEST_ASSERT_EQUAL_INT(a->iterations, b->iterations);
    TEST_ASSERT_EQUAL_INT(a->warnings, b->warnings);
    TEST_ASSERT_EQUAL_INT(a->stroke_legs, b->stroke_legs);
}

static void test_drives_change_no_other_column_and_none_gives_zeros(void) {
    stewart_params plain, driven;
    stewart_params_default(&plain);
    driven = plain;
    looms_drives(&driven);
    const double zeros[STEWART_LEGS] = {0};
    for (int fidelity = STEWART_KINEMATIC; fidelity <= STEWART_FULL; ++fidelity) {
        stewart_model *mp, *md;
        stewart_inverse *a = solver(&plain, fidelity, &mp), *b = solver(&driven, fidelity, &md);
        for (int j = 0; j < ROWS; ++j) {
            stewart_inverse_input in = {{{0}}};
            manoeuvre(0.05 * j, &in.pose);
            stewart_inverse_output oa, ob;
            memset(&oa, 0x5a, sizeof oa);
            TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_inverse_solve(a, &in, &oa));
            TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_inverse_solve(b, &in, &ob));
            assert_same_legs(&oa, &ob);
            const double *columns[] = {oa.motor_angle,  oa.motor_speed,      oa.motor_accel,
                                       oa.motor_torque, oa.current,          oa.current_rate,
                                       oa.voltage,      oa.electrical_power, oa.motor_power};
            for (size_t c = 0; c < sizeof columns / sizeof columns[0]; ++c)
                TEST_ASSERT_EQUAL_MEMORY(zeros, columns[c], sizeof zeros);
            TEST_ASSERT_EQUAL_INT(0, oa.current_max_legs | oa.voltage_max_legs |
                                         oa.motor_speed_max_legs);
            TEST_ASSERT_TRUE(ob.motor_speed[0] != 0 && ob.current[0] != 0);
        }
        stewart_inverse_free(a), stewart_inverse_free(b);
        stewart_model_free(mp), stewart_model_free(md);
    }
}

static double t[ROWS], q[ROWS][6], qd[ROWS][6], qdd[ROWS][6];
static double current[ROWS][6], rate[ROWS][6], voltage[ROWS][6], torque[ROWS][6], speed[ROWS][6],
    power[ROWS][6], force[ROWS][6], length[ROWS][6], length_rate[ROWS][6], length_accel[ROWS][6];
static int status[ROWS], volt_legs[ROWS];

static stewart_inverse_batch_outputs batch_columns(void) {
    stewart_inverse_batch_outputs out = {0};
    out.length = &length[0][0], out.length_rate = &length_rate[0][0];
    out.length_accel = &length_accel[0][0], out.force = &force[0][0];
    out.current = &current[0][0], out.current_rate = &rate[0][0];
    out.voltage = &voltage[0][0], out.motor_torque = &torque[0][0];
    out.motor_speed = &speed[0][0], out.electrical_power = &power[0][0];
    out.voltage_max_legs = volt_legs, out.status = status;
    return out;
}

static void test_the_batch_gives_the_solves_drive_columns(void) {
    stewart_params p;
    stewart_params_default(&p);
    looms_drives(&p);
    for (int j = 0; j < ROWS; ++j) {
        stewart_pose pose;
        t[j] = 0.05 * j;
        manoeuvre(t[j], &pose);
        memcpy(q[j], pose.q, sizeof q[j]), memcpy(qd[j], pose.q_dot, sizeof qd[j]);
        memcpy(qdd[j], pose.q_ddot, sizeof qdd[j]);
    }
    stewart_model *m;
    stewart_inverse *inv = solver(&p, STEWART_MASSLESS, &m);
    const stewart_inverse_batch_outputs out = batch_columns();
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_inverse_batch(inv, ROWS, &q[0][0], &qd[0][0],
                                                            &qdd[0][0], &out, NULL, NULL));
    for (int j = 0; j < ROWS; ++j) {
        stewart_inverse_input in;
        memcpy(in.pose.q, q[j], sizeof q[j]), memcpy(in.pose.q_dot, qd[j], sizeof qd[j]);
        memcpy(in.pose.q_ddot, qdd[j], sizeof qdd[j]);
        stewart_inverse_output o;
        TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_inverse_solve(inv, &in, &o));
        for (int k = 0; k < 6; ++k) { /* the vector kernel's forces: the solve's to rounding */
            TEST_ASSERT_DOUBLE_WITHIN(1e-11 * (1 + fabs(o.motor_torque[k])), o.motor_torque[k],
                                      torque[j][k]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-11 * (1 + fabs(o.voltage[k])), o.voltage[k],
                                      voltage[j][k]);
            TEST_ASSERT_EQUAL_DOUBLE(0.0, rate[j][k]);
        }
    }
    /* Along the trajectory: dI/dt by central differences (uniform steps here), one-sided at
     * the ends, and the voltage gains L dI/dt. */
    double before[ROWS][6];
    memcpy(before, voltage, sizeof before);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_inverse_batch_current_rates(m, ROWS, t, &out, message,
                                                                          sizeof message));
    for (int j = 0; j < ROWS; ++j)
        for (int k = 0; k < 6; ++k) {
            const double expected =
                j == 0          ? (current[1][k] - current[0][k]) / (t[1] - t[0])
                : j == ROWS - 1 ? (current[j][k] - current[j - 1][k]) / (t[j] - t[j - 1])
                                : (current[j + 1][k] - current[j - 1][k]) / (t[j + 1] - t[j - 1]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-9 * (1 + fabs(expected)), expected, rate[j][k]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-12 * (1 + fabs(before[j][k])),
                                      before[j][k] + 3e-3 * rate[j][k], voltage[j][k]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-12 * (1 + fabs(power[j][k])),
                                      voltage[j][k] * current[j][k], power[j][k]);
        }
    stewart_inverse_free(inv);
    stewart_model_free(m);
}

static void test_current_rates_refuse_times_that_do_not_increase(void) {
    stewart_params p;
    stewart_params_default(&p);
    looms_drives(&p);
    stewart_model *m = stewart_model_create(&p, message, sizeof message);
    const stewart_inverse_batch_outputs out = batch_columns();
    double times[3] = {0, 0.1, 0.1};
    for (int j = 0; j < 3; ++j) status[j] = STEWART_OK;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT,
                          stewart_inverse_batch_current_rates(m, 3, times, &out, message,
                                                              sizeof message));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(message, "t[2] = 0.10000000000000001 s"), message);
    times[2] = NAN;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT,
                          stewart_inverse_batch_current_rates(m, 3, times, &out, message,
                                                              sizeof message));
    stewart_model_free(m);
}

static void test_limit_flags_name_the_legs_over(void) {
    stewart_params p;
    stewart_params_default(&p);
    looms_drives(&p);
    stewart_model *m;
    stewart_inverse *inv = solver(&p, STEWART_FULL, &m);
    stewart_inverse_input in = {{{0}}};
    manoeuvre(0.3, &in.pose);
    stewart_inverse_output o;
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_inverse_solve(inv, &in, &o));
    stewart_inverse_free(inv), stewart_model_free(m);
    /* limits between the legs' values: the legs above them flagged, the others not */
    int expected_current = 0, expected_speed = 0;
    for (int k = 0; k < 6; ++k) {
        p.current_max[k] = 0.5 * fabs(o.current[k]) + 0.5 * fabs(o.current[(k + 1) % 6]);
        p.motor_speed_max[k] = fabs(o.motor_speed[(k + 2) % 6]);
        if (fabs(o.current[k]) > p.current_max[k]) expected_current |= 1 << k;
        if (fabs(o.motor_speed[k]) > p.motor_speed_max[k]) expected_speed |= 1 << k;
    }
    inv = solver(&p, STEWART_FULL, &m);
    stewart_inverse_output flagged;
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_inverse_solve(inv, &in, &flagged));
    TEST_ASSERT_EQUAL_INT(expected_current, flagged.current_max_legs);
    TEST_ASSERT_EQUAL_INT(expected_speed, flagged.motor_speed_max_legs);
    TEST_ASSERT_EQUAL_INT(0, flagged.voltage_max_legs);
    TEST_ASSERT_TRUE(expected_current != 0 && expected_current != 63);
    stewart_inverse_free(inv), stewart_model_free(m);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_the_published_reflected_mass);
    RUN_TEST(test_drives_change_no_other_column_and_none_gives_zeros);
    RUN_TEST(test_the_batch_gives_the_solves_drive_columns);
    RUN_TEST(test_current_rates_refuse_times_that_do_not_increase);
    RUN_TEST(test_limit_flags_name_the_legs_over);
    return UNITY_END();
}
