/* Tool and user frames, and length_offset (docs/api.md): every direction of a model with a tool
 * frame (an offset, turned pivot on the platform) and a user frame (shifted and turned on the
 * base) against a model without frames, the poses transformed by hand here (rotation code of
 * this file's own) and their rates and accelerations by finite differences in time of the
 * transformed pose; inverse <-> forward round trips; bad frames refused by name; the sensor
 * readings against lengths computed here. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "stewart/stewart.h"
#include "stewart/stewart_forward.h"
#include "stewart/stewart_plant.h"
#include "test_plant_support.h"
#include "test_support.h"
#include "unity.h"

static const double kTool[6] = {0.02, -0.01, 0.10, 0.05, -0.04, 0.30};
static const double kUser[6] = {0.01, -0.02, 0.45, 0.02, -0.03, 0.40};

static stewart_params plain, framed;
static stewart_model *plain_model, *framed_model;

static void set_frames(stewart_params *p, const double tool[6], const double user[6]) {
    memcpy(p->tool_frame, tool, sizeof p->tool_frame);
    memcpy(p->user_frame, user, sizeof p->user_frame);
}

void setUp(void) {
    stewart_params_default(&plain);
    framed = plain;
    set_frames(&framed, kTool, kUser);
    plain_model = test_model(&plain);
    framed_model = test_model(&framed);
}

void tearDown(void) {
    stewart_model_free(plain_model);
    stewart_model_free(framed_model);
}

/* ---- this file's own rotations: R = Rz(yaw) Ry(pitch) Rx(roll) ---- */

static void rpy_to_matrix(const double a[3], double R[3][3]) {
    const double Rx[3][3] = {{1, 0, 0}, {0, cos(a[0]), -sin(a[0])}, {0, sin(a[0]), cos(a[0])}};
    const double Ry[3][3] = {{cos(a[1]), 0, sin(a[1])}, {0, 1, 0}, {-sin(a[1]), 0, cos(a[1])}};
    const double Rz[3][3] = {{cos(a[2]), -sin(a[2]), 0}, {sin(a[2]), cos(a[2]), 0}, {0, 0, 1}};
    double ZY[3][3] = {{0}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) ZY[i][j] += Rz[i][k] * Ry[k][j];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            R[i][j] = 0;
            for (int k = 0; k < 3; ++k) R[i][j] += ZY[i][k] * Rx[k][j];
        }
}

/* C = A B, with A transposed first if transpose_a. */
static void multiply(const double A[3][3], int transpose_a, const double B[3][3], double C[3][3]) {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double s = 0;
            for (int k = 0; k < 3; ++k) s += (transpose_a ? A[k][i] : A[i][k]) * B[k][j];
            C[i][j] = s;
        }
}

/* The angles of R with roll and yaw within pi of near's. */
static void matrix_to_rpy(const double R[3][3], const double near[3], double a[3]) {
    a[1] = asin(-R[2][0]);
    a[0] = atan2(R[2][1], R[2][2]);
    a[2] = atan2(R[1][0], R[0][0]);
    for (int i = 0; i < 3; i += 2) {
        while (a[i] - near[i] > M_PI) a[i] -= 2 * M_PI;
        while (a[i] - near[i] < -M_PI) a[i] += 2 * M_PI;
    }
}

/* The tool's pose in the user frame when the platform is at q (base frame), by hand:
 * o = p + Rp d, q_tool = (Ru^T (o - u), angles of Ru^T Rp Rd). */
static void tool_pose_by_hand(const double tool[6], const double user[6], const double q[6],
                              double out[6]) {
    double Rp[3][3], Ru[3][3], Rd[3][3], RpRd[3][3], Rt[3][3];
    rpy_to_matrix(q + 3, Rp);
    rpy_to_matrix(user + 3, Ru);
    rpy_to_matrix(tool + 3, Rd);
    double o[3];
    for (int i = 0; i < 3; ++i)
        o[i] = q[i] + Rp[i][0] * tool[0] + Rp[i][1] * tool[1] + Rp[i][2] * tool[2];
    for (int i = 0; i < 3; ++i)
        out[i] =
            Ru[0][i] * (o[0] - user[0]) + Ru[1][i] * (o[1] - user[1]) + Ru[2][i] * (o[2] - user[2]);
    multiply(Rp, 0, Rd, RpRd);
    multiply(Ru, 1, RpRd, Rt);
    const double near[3] = {q[3] + tool[3] - user[3], 0, q[5] + tool[5] - user[5]};
    matrix_to_rpy(Rt, near, out + 3);
}

/* The platform's pose (base frame) when the tool is at q (user frame), by hand:
 * Rp = Ru Rt Rd^T, p = u + Ru q_position - Rp d. */
static void platform_pose_by_hand(const double tool[6], const double user[6], const double q[6],
                                  double out[6]) {
    double Rt[3][3], Ru[3][3], Rd[3][3], RuRt[3][3], Rp[3][3], Rdt[3][3];
    rpy_to_matrix(q + 3, Rt);
    rpy_to_matrix(user + 3, Ru);
    rpy_to_matrix(tool + 3, Rd);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) Rdt[i][j] = Rd[j][i];
    multiply(Ru, 0, Rt, RuRt);
    multiply(RuRt, 0, Rdt, Rp);
    for (int i = 0; i < 3; ++i)
        out[i] = user[i] + Ru[i][0] * q[0] + Ru[i][1] * q[1] + Ru[i][2] * q[2] -
                 (Rp[i][0] * tool[0] + Rp[i][1] * tool[1] + Rp[i][2] * tool[2]);
    const double near[3] = {q[3] - tool[3] + user[3], 0, q[5] - tool[5] + user[5]};
    matrix_to_rpy(Rp, near, out + 3);
}

/* The tool's pose along the platform's combined manoeuvre, with rates and accelerations by
 * five-point central differences in time of the hand-transformed pose. */
static stewart_pose tool_trajectory(const double tool[6], const double user[6], double t) {
    const double dt = 1e-3;
    double q[5][6];
    for (int s = 0; s < 5; ++s) {
        const stewart_pose p = combined_pose(t + (s - 2) * dt);
        tool_pose_by_hand(tool, user, p.q, q[s]);
    }
    stewart_pose out;
    for (int i = 0; i < 6; ++i) {
        out.q[i] = q[2][i];
        out.q_dot[i] = (q[0][i] - 8 * q[1][i] + 8 * q[3][i] - q[4][i]) / (12 * dt);
        out.q_ddot[i] =
            (-q[0][i] + 16 * q[1][i] - 30 * q[2][i] + 16 * q[3][i] - q[4][i]) / (12 * dt * dt);
    }
    return out;
}

static stewart_inverse_output inverse_ok(const stewart_model *m, stewart_fidelity fidelity,
                                         const stewart_pose *pose) {
    stewart_inverse *d = test_inverse(m);
    const stewart_inverse_output out = solve_ok(d, fidelity, pose);
    stewart_inverse_free(d);
    return out;
}

static stewart_forward *forward_of(const stewart_model *m) {
    stewart_forward_options o;
    stewart_forward_options_default(&o);
    char msg[STEWART_MESSAGE_SIZE];
    stewart_forward *f = stewart_forward_create(m, &o, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(f, msg);
    return f;
}

/* Forward kinematics of lengths at time t (tracking), with `derivatives`; fails the test with
 * the solver's message unless it solves. */
static stewart_forward_output track(stewart_forward *f, double t, const stewart_lengths *lengths,
                                    int derivatives) {
    stewart_forward_input in = {0};
    in.time = t;
    in.lengths = *lengths;
    in.derivatives = derivatives;
    stewart_forward_output out;
    TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK, stewart_forward_solve(f, &in, &out),
                              stewart_forward_message(f));
    return out;
}

static void assert_close(double expected, double actual, double bound, const char *what) {
    char text[160];
    snprintf(text, sizeof text, "%s: expected %.17g, got %.17g (bound %g)", what, expected, actual,
             bound);
    TEST_ASSERT_TRUE_MESSAGE(fabs(expected - actual) <= bound, text);
}

/* ---- inverse ---- */

/* The tool's pose in the user frame gives the lengths, rates, accelerations and forces the
 * platform's pose gives a model without frames (rates and accelerations to the finite
 * differences' accuracy). */
static void test_inverse_takes_the_tool_pose_in_the_user_frame(void) {
    for (int i = 0; i <= 20; ++i) {
        const double t = 0.05 * i;
        const stewart_pose platform = combined_pose(t);
        const stewart_pose tool = tool_trajectory(kTool, kUser, t);
        const stewart_inverse_output want = inverse_ok(plain_model, STEWART_MASSLESS, &platform);
        const stewart_inverse_output got = inverse_ok(framed_model, STEWART_MASSLESS, &tool);
        for (int k = 0; k < 6; ++k) {
            assert_close(want.lengths.length[k], got.lengths.length[k], 1e-13, "length");
            assert_close(want.lengths.length_rate[k], got.lengths.length_rate[k], 1e-9, "rate");
            assert_close(want.lengths.length_accel[k], got.lengths.length_accel[k], 1e-7, "accel");
            assert_close(want.force[k], got.force[k], 1e-8 * fabs(want.force[k]) + 1e-7, "force");
        }
        TEST_ASSERT_EQUAL_INT(want.warnings, got.warnings);
    }
}

/* The full level too: the same lengths and (to the differences' accuracy) forces. */
static void test_full_level_takes_the_tool_pose(void) {
    const stewart_pose platform = combined_pose(0.3);
    const stewart_pose tool = tool_trajectory(kTool, kUser, 0.3);
    const stewart_inverse_output want = inverse_ok(plain_model, STEWART_FULL, &platform);
    const stewart_inverse_output got = inverse_ok(framed_model, STEWART_FULL, &tool);
    for (int k = 0; k < 6; ++k) {
        assert_close(want.lengths.length[k], got.lengths.length[k], 1e-13, "length");
        assert_close(want.force[k], got.force[k], 1e-8 * fabs(want.force[k]) + 1e-7, "force");
    }
}

/* ---- forward ---- */

/* Tracking the lengths of the platform's manoeuvre gives the tool's pose by hand, and its rates
 * and accelerations to the finite differences' accuracy. */
static void test_forward_returns_the_tool_pose(void) {
    stewart_forward *f = forward_of(framed_model);
    for (int i = 0; i <= 40; ++i) {
        const double t = 0.025 * i;
        const stewart_pose platform = combined_pose(t);
        const stewart_inverse_output legs = inverse_ok(plain_model, STEWART_KINEMATIC, &platform);
        const stewart_forward_output out = track(f, t, &legs.lengths, 2);
        const stewart_pose tool = tool_trajectory(kTool, kUser, t);
        for (int c = 0; c < 6; ++c) {
            assert_close(tool.q[c], out.pose.q[c], 1e-11, "pose");
            assert_close(tool.q_dot[c], out.pose.q_dot[c], 1e-9, "pose rate");
            assert_close(tool.q_ddot[c], out.pose.q_ddot[c], 1e-7, "pose acceleration");
        }
        if (i > 0) TEST_ASSERT_NOT_EQUAL(STEWART_START_HOME, out.start);
    }
    stewart_forward_free(f);
}

/* The guess is the tool's pose too: the exact one converges at once. */
static void test_forward_guess_is_the_tool_pose(void) {
    stewart_forward *f = forward_of(framed_model);
    const stewart_pose platform = combined_pose(0.7);
    const stewart_inverse_output legs = inverse_ok(plain_model, STEWART_KINEMATIC, &platform);
    stewart_forward_input in = {0};
    in.lengths = legs.lengths;
    in.use_guess = 1;
    tool_pose_by_hand(kTool, kUser, platform.q, in.guess);
    stewart_forward_output out;
    TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK, stewart_forward_solve(f, &in, &out),
                              stewart_forward_message(f));
    TEST_ASSERT_EQUAL_INT(STEWART_START_GUESS, out.start);
    TEST_ASSERT_TRUE(out.iterations <= 1);
    for (int c = 0; c < 6; ++c) assert_close(in.guess[c], out.pose.q[c], 1e-11, "pose");
    stewart_forward_free(f);
}

/* Inverse then forward on the framed model: the tool's pose, rates and accelerations back. */
static void test_round_trip_inverse_forward(void) {
    stewart_forward *f = forward_of(framed_model);
    for (int i = 0; i <= 20; ++i) {
        const double t = 0.05 * i;
        const stewart_pose tool = tool_trajectory(kTool, kUser, t);
        const stewart_inverse_output legs = inverse_ok(framed_model, STEWART_KINEMATIC, &tool);
        const stewart_forward_output out = track(f, t, &legs.lengths, 2);
        for (int c = 0; c < 6; ++c) {
            assert_close(tool.q[c], out.pose.q[c], 1e-11, "pose");
            assert_close(tool.q_dot[c], out.pose.q_dot[c], 1e-11, "pose rate");
            assert_close(tool.q_ddot[c], out.pose.q_ddot[c], 1e-9, "pose acceleration");
        }
    }
    stewart_forward_free(f);
}

/* A tool turned by pi - 0.05 about z: its yaw crosses pi as the platform yaws, and the outputs
 * stay continuous (no jump of 2 pi), inverse <-> forward agreeing. */
static void test_tool_yaw_is_continuous_across_pi(void) {
    const double tool[6] = {0.05, 0, 0.05, 0, 0, M_PI - 0.05};
    const double user[6] = {0, 0, 0, 0, 0, 0};
    stewart_params p = plain;
    set_frames(&p, tool, user);
    stewart_model *m = test_model(&p);
    stewart_forward *f = forward_of(m);
    double last_yaw = 0, largest = -10;
    for (int i = 0; i <= 60; ++i) {
        const double t = 0.05 * i;
        const stewart_pose platform = combined_pose(t);
        const stewart_inverse_output legs = inverse_ok(plain_model, STEWART_KINEMATIC, &platform);
        const stewart_forward_output out = track(f, t, &legs.lengths, 0);
        double by_hand[6];
        tool_pose_by_hand(tool, user, platform.q, by_hand);
        /* the same rotation: the angles agree modulo 2 pi */
        assert_close(0, remainder(by_hand[5] - out.pose.q[5], 2 * M_PI), 1e-11, "yaw mod 2 pi");
        if (i > 0) TEST_ASSERT_TRUE(fabs(out.pose.q[5] - last_yaw) < 0.2);
        last_yaw = out.pose.q[5];
        if (out.pose.q[5] > largest) largest = out.pose.q[5];
    }
    TEST_ASSERT_TRUE(largest > M_PI); /* it did cross pi */
    stewart_forward_free(f);
    stewart_model_free(m);
}

/* Frames that do not turn (offsets alone) leave the angles, their rates and accelerations as
 * the platform's, bit for bit; identity frames leave every output bit for bit (the defaults:
 * studies/bench/compare_outputs.py --bound 0 compares them with the build before the frames). */
static void test_offsets_alone_keep_the_angles_bit_for_bit(void) {
    const double tool[6] = {0.01, 0.02, 0.08, 0, 0, 0}, user[6] = {-0.03, 0.01, 0.02, 0, 0, 0};
    stewart_params p = plain;
    set_frames(&p, tool, user);
    stewart_model *m = test_model(&p);
    stewart_forward *a = forward_of(plain_model), *b = forward_of(m);
    for (int i = 0; i <= 10; ++i) {
        const stewart_pose platform = combined_pose(0.1 * i);
        const stewart_inverse_output legs = inverse_ok(plain_model, STEWART_KINEMATIC, &platform);
        const stewart_forward_output out_a = track(a, 0.1 * i, &legs.lengths, 2);
        const stewart_forward_output out_b = track(b, 0.1 * i, &legs.lengths, 2);
        TEST_ASSERT_EQUAL_MEMORY(out_a.pose.q + 3, out_b.pose.q + 3, 3 * sizeof(double));
        TEST_ASSERT_EQUAL_MEMORY(out_a.pose.q_dot + 3, out_b.pose.q_dot + 3, 3 * sizeof(double));
        TEST_ASSERT_EQUAL_MEMORY(out_a.pose.q_ddot + 3, out_b.pose.q_ddot + 3, 3 * sizeof(double));
        double by_hand[6];
        tool_pose_by_hand(tool, user, platform.q, by_hand);
        for (int c = 0; c < 3; ++c) assert_close(by_hand[c], out_b.pose.q[c], 1e-11, "position");
    }
    stewart_forward_free(a);
    stewart_forward_free(b);
    stewart_model_free(m);
}

/* ---- plant ---- */

/* A plant started at the tool's pose (rates by differences) and one without frames at the
 * platform's, under the same forces: the framed one's outputs are the other's transformed by
 * hand, its rates the differences in time of those, its lengths the same. */
static void test_plant_outputs_the_tool_pose(void) {
    stewart_plant *a = test_plant(plain_model, STEWART_MASSLESS, 1e-12, 1e-14);
    stewart_plant *b = test_plant(framed_model, STEWART_MASSLESS, 1e-12, 1e-14);
    const stewart_pose platform = combined_pose(0);
    const stewart_pose tool = tool_trajectory(kTool, kUser, 0);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(a, 0, platform.q, platform.q_dot));
    TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK, stewart_plant_set_state(b, 0, tool.q, tool.q_dot),
                              stewart_plant_message(b));
    const stewart_inverse_output hold = inverse_ok(plain_model, STEWART_MASSLESS, &platform);
    const double h = 1e-4;
    double previous[6] = {0}, current[6] = {0};
    stewart_plant_output last_b;
    for (int i = 1; i <= 60; ++i) {
        stewart_plant_input in = {0};
        in.h = h;
        memcpy(in.force_start, hold.force, sizeof in.force_start);
        memcpy(in.force_end, hold.force, sizeof in.force_end);
        stewart_plant_output out_a, out_b;
        TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK, stewart_plant_step(a, &in, &out_a),
                                  stewart_plant_message(a));
        TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK, stewart_plant_step(b, &in, &out_b),
                                  stewart_plant_message(b));
        double by_hand[6];
        tool_pose_by_hand(kTool, kUser, out_a.pose.q, by_hand);
        for (int c = 0; c < 6; ++c) assert_close(by_hand[c], out_b.pose.q[c], 1e-9, "plant pose");
        for (int k = 0; k < 6; ++k)
            assert_close(out_a.lengths.length[k], out_b.lengths.length[k], 1e-9, "plant length");
        if (i >= 3) /* the rates at the previous step: central differences of the poses */
            for (int c = 0; c < 6; ++c)
                assert_close((by_hand[c] - previous[c]) / (2 * h), last_b.pose.q_dot[c], 1e-6,
                             "plant pose rate");
        memcpy(previous, current, sizeof previous);
        memcpy(current, by_hand, sizeof current);
        last_b = out_b;
    }
    stewart_plant_free(a);
    stewart_plant_free(b);
}

/* The plant's start state is the tool's pose: read back unchanged, and home (reset) stays the
 * platform's. */
static void test_plant_start_state_is_the_tool_pose(void) {
    stewart_plant *b = test_plant(framed_model, STEWART_MASSLESS, 1e-10, 1e-12);
    stewart_plant_output out;
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(b, NULL, &out));
    const double home[6] = {0, 0, plain.home_height, 0, 0, 0};
    double tool_home[6];
    tool_pose_by_hand(kTool, kUser, home, tool_home);
    for (int c = 0; c < 6; ++c) assert_close(tool_home[c], out.pose.q[c], 1e-14, "home");
    const double q[6] = {0.01, 0.02, 0.07, 0.1, -0.05, 0.2}, rate[6] = {0};
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(b, 0, q, rate));
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(b, NULL, &out));
    for (int c = 0; c < 6; ++c) assert_close(q[c], out.pose.q[c], 1e-14, "start pose");
    /* the platform's pose behind it, by hand, gives the lengths */
    double platform_q[6];
    platform_pose_by_hand(kTool, kUser, q, platform_q);
    stewart_pose platform = {{0}, {0}, {0}};
    memcpy(platform.q, platform_q, sizeof platform.q);
    for (int k = 0; k < 6; ++k)
        assert_close(closed_form_length(&plain, &platform, k), out.lengths.length[k], 1e-14,
                     "start length");
    stewart_plant_free(b);
}

/* ---- tool pitch at +-90 degrees ---- */

/* A tool pitched by 90 degrees: at home its pitch in the user frame is +90 deg. The pose is
 * returned; its rates are refused with a message (nothing NaN), in forward and in the plant. */
static void test_tool_pitch_at_90_degrees(void) {
    const double tool[6] = {0, 0, 0, 0, M_PI / 2, 0}, user[6] = {0};
    stewart_params p = plain;
    set_frames(&p, tool, user);
    stewart_model *m = test_model(&p);
    stewart_pose home = {{0, 0, plain.home_height, 0, 0, 0}, {0}, {0}};
    const stewart_inverse_output legs = inverse_ok(plain_model, STEWART_KINEMATIC, &home);
    stewart_forward *f = forward_of(m);
    stewart_forward_input in = {0};
    in.lengths = legs.lengths;
    stewart_forward_output out;
    TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK, stewart_forward_solve(f, &in, &out),
                              stewart_forward_message(f));
    assert_close(M_PI / 2, out.pose.q[4], 1e-7, "pitch");
    in.derivatives = 1;
    stewart_forward_output untouched = out;
    TEST_ASSERT_EQUAL(STEWART_ERR_SINGULAR, stewart_forward_solve(f, &in, &out));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(stewart_forward_message(f), "tool frame's pitch"),
                                 stewart_forward_message(f));
    TEST_ASSERT_EQUAL_MEMORY(&untouched, &out, sizeof out);
    /* the inverse takes that pose (its rates are defined there) */
    stewart_pose at_90 = {{0, 0, plain.home_height, 0, M_PI / 2, 0}, {0.1, 0, 0, 0.2, 0, 0.3}, {0}};
    stewart_inverse *d = test_inverse(m);
    stewart_inverse_output inv;
    TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK,
                              stewart_inverse_solve(d, &(stewart_inverse_input){at_90}, &inv),
                              stewart_inverse_message(d));
    for (int k = 0; k < 6; ++k)
        assert_close(legs.lengths.length[k], inv.lengths.length[k], 1e-14, "length");
    stewart_inverse_free(d);
    /* the plant at home: no output with rates, a step refused with a message */
    stewart_plant *plant = test_plant(m, STEWART_MASSLESS, 1e-10, 1e-12);
    stewart_plant_output po;
    TEST_ASSERT_EQUAL(STEWART_ERR_SINGULAR, stewart_plant_output_get(plant, NULL, &po));
    const double force[6] = {0};
    TEST_ASSERT_EQUAL(STEWART_ERR_SINGULAR,
                      plant_step_arrays(plant, 1e-4, force, force, NULL, NULL));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(stewart_plant_message(plant), "tool frame's pitch"),
                                 stewart_plant_message(plant));
    TEST_ASSERT_EQUAL_DOUBLE(0, stewart_plant_time(plant));
    stewart_plant_free(plant);
    stewart_forward_free(f);
    stewart_model_free(m);
}

/* ---- bad frames and offsets ---- */

static void expect_refused(const char *name, double value, const char *unit) {
    stewart_params p = plain;
    char msg[STEWART_MESSAGE_SIZE];
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_params_set(&p, name, value, msg, sizeof msg));
    TEST_ASSERT_NULL_MESSAGE(stewart_model_create(&p, msg, sizeof msg), name);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, name), msg);
    if (unit) {
        char with_unit[32];
        snprintf(with_unit, sizeof with_unit, " %s must", unit);
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, with_unit), msg);
    }
}

static void test_bad_frames_and_offsets_are_refused_by_name(void) {
    expect_refused("tool_frame[1]", NAN, NULL);
    expect_refused("tool_frame[5]", INFINITY, NULL);
    expect_refused("user_frame[2]", 1e300, "m");
    expect_refused("user_frame[6]", -5000, "rad");
    expect_refused("tool_frame[3]", 1001, "m");
    expect_refused("length_offset[3]", NAN, NULL);
    expect_refused("length_offset[4]", 2e3, "m");
    /* the edges of the range are taken */
    stewart_params p = plain;
    p.tool_frame[0] = 1e3;
    p.user_frame[5] = -1e3;
    p.length_offset[1] = 1e3;
    char msg[STEWART_MESSAGE_SIZE];
    stewart_model *m = stewart_model_create(&p, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(m, msg);
    stewart_model_free(m);
}

/* A finite pose whose platform motion overflows through the frames (the tool offset's
 * centripetal term): refused naming the input, the output untouched. */
static void test_pose_overflowing_through_the_frames_is_refused(void) {
    stewart_inverse *d = test_inverse(framed_model);
    stewart_pose pose = combined_pose(0);
    pose.q_dot[5] = 1e200; /* omega x (omega x r): (1e200)^2 overflows */
    pose.q_ddot[5] = 0;
    stewart_inverse_output out;
    memset(&out, 0x5a, sizeof out);
    const stewart_inverse_output untouched = out;
    const stewart_status s = stewart_inverse_solve(d, &(stewart_inverse_input){pose}, &out);
    TEST_ASSERT_EQUAL_MESSAGE(STEWART_ERR_ARGUMENT, s, stewart_inverse_message(d));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(stewart_inverse_message(d), "yaw_dot"),
                                 stewart_inverse_message(d));
    TEST_ASSERT_EQUAL_MEMORY(&untouched, &out, sizeof out);
    stewart_inverse_free(d);
}

/* ---- length_offset ---- */

static const double kOffset[6] = {0.001, -0.002, 0.3, 0, 0.0005, -0.1};

/* Lengths given and returned are the sensors' readings, Cardan-to-Cardan length - offset (the
 * lengths computed here); the stroke is checked on Cardan-to-Cardan lengths. */
static void test_length_offset_readings(void) {
    stewart_params p = plain;
    memcpy(p.length_offset, kOffset, sizeof kOffset);
    stewart_model *m = test_model(&p);
    stewart_forward *f = forward_of(m);
    for (int i = 0; i <= 10; ++i) {
        const stewart_pose pose = combined_pose(0.1 * i);
        const stewart_inverse_output out = inverse_ok(m, STEWART_MASSLESS, &pose);
        const stewart_inverse_output plain_out = inverse_ok(plain_model, STEWART_MASSLESS, &pose);
        for (int k = 0; k < 6; ++k) {
            const double reading = closed_form_length(&plain, &pose, k) - kOffset[k];
            assert_close(reading, out.lengths.length[k], 1e-14, "reading");
            TEST_ASSERT_EQUAL_DOUBLE(plain_out.lengths.length_rate[k], out.lengths.length_rate[k]);
            TEST_ASSERT_EQUAL_DOUBLE(plain_out.force[k], out.force[k]);
        }
        /* leg 3 reads about 0.2 m, below stroke_min = 0.4 m, but its joints are 0.5 m apart */
        TEST_ASSERT_EQUAL_INT(plain_out.stroke_legs, out.stroke_legs);
        /* forward kinematics takes the readings */
        const stewart_forward_output back = track(f, 0.1 * i, &out.lengths, 2);
        for (int c = 0; c < 6; ++c) assert_close(pose.q[c], back.pose.q[c], 1e-11, "pose");
        TEST_ASSERT_EQUAL_INT(plain_out.stroke_legs, back.stroke_legs);
    }
    /* a reading that is 0 or negative is fine when the offset makes the length positive ... */
    stewart_forward_input in = {0};
    const stewart_pose home = {{0, 0, plain.home_height, 0, 0, 0}, {0}, {0}};
    for (int k = 0; k < 6; ++k) in.lengths.length[k] = closed_form_length(&plain, &home, k);
    in.lengths.length[5] = -0.05; /* leg 6: offset -0.1 m makes -0.15 m */
    stewart_forward_output out;
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, stewart_forward_solve(f, &in, &out));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(stewart_forward_message(f), "L6 + length_offset[6]"),
                                 stewart_forward_message(f));
    in.lengths.length[5] = closed_form_length(&plain, &home, 5) - kOffset[5];
    in.lengths.length[2] = closed_form_length(&plain, &home, 2) - kOffset[2];
    in.use_guess = 1;
    memcpy(in.guess, home.q, sizeof in.guess);
    in.lengths.length[0] = closed_form_length(&plain, &home, 0) - kOffset[0];
    in.lengths.length[1] = closed_form_length(&plain, &home, 1) - kOffset[1];
    in.lengths.length[4] = closed_form_length(&plain, &home, 4) - kOffset[4];
    TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK, stewart_forward_solve(f, &in, &out),
                              stewart_forward_message(f));
    for (int c = 0; c < 6; ++c) assert_close(home.q[c], out.pose.q[c], 1e-12, "home");
    /* the plant's lengths are readings too */
    stewart_plant *plant = test_plant(m, STEWART_MASSLESS, 1e-10, 1e-12);
    stewart_plant_output po;
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &po));
    for (int k = 0; k < 6; ++k)
        assert_close(closed_form_length(&plain, &home, k) - kOffset[k], po.lengths.length[k], 1e-14,
                     "plant reading");
    TEST_ASSERT_EQUAL_INT(0, po.stroke_legs);
    stewart_plant_free(plant);
    stewart_forward_free(f);
    stewart_model_free(m);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_inverse_takes_the_tool_pose_in_the_user_frame);
    RUN_TEST(test_full_level_takes_the_tool_pose);
    RUN_TEST(test_forward_returns_the_tool_pose);
    RUN_TEST(test_forward_guess_is_the_tool_pose);
    RUN_TEST(test_round_trip_inverse_forward);
    RUN_TEST(test_tool_yaw_is_continuous_across_pi);
    RUN_TEST(test_offsets_alone_keep_the_angles_bit_for_bit);
    RUN_TEST(test_plant_outputs_the_tool_pose);
    RUN_TEST(test_plant_start_state_is_the_tool_pose);
    RUN_TEST(test_tool_pitch_at_90_degrees);
    RUN_TEST(test_bad_frames_and_offsets_are_refused_by_name);
    RUN_TEST(test_pose_overflowing_through_the_frames_is_refused);
    RUN_TEST(test_length_offset_readings);
    return UNITY_END();
}
