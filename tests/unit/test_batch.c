/* The batch entry points (stewart_batch.h) against the equivalent loops of single calls on a
 * second data block or plant: the same numbers bit for bit, and the documented per-row statuses
 * (a failing row does not stop a solve or forward batch; a refused plant step stops the run and
 * the rows after it are marked not run). */
#include <math.h>
#include <string.h>

#include "platform_fixture.h"
#include "stewart/stewart_batch.h"
#include "test_support.h"
#include "unity.h"

#define ROWS 24

/* A smooth manoeuvre around home (all six axes, within the stroke) and its derivatives. */
static void manoeuvre(double t, double q[6], double q_dot[6], double q_ddot[6]) {
    const double amplitude[6] = {0.05, -0.04, 0.03, 0.05, -0.04, 0.06};
    const double w = 2.0;
    for (int i = 0; i < 6; ++i) {
        const double phase = 0.3 * i;
        q[i] = amplitude[i] * sin(w * t + phase) + (i == 2 ? params.home_height : 0.0);
        q_dot[i] = amplitude[i] * w * cos(w * t + phase);
        q_ddot[i] = -amplitude[i] * w * w * sin(w * t + phase);
    }
}

static double times[ROWS], q[ROWS][6], q_dot[ROWS][6], q_ddot[ROWS][6];

/* Each test starts from the manoeuvre's rows (the fixture's setUp builds the platform). */
static void fill_rows(void) {
    for (int j = 0; j < ROWS; ++j) {
        times[j] = 0.05 * j;
        manoeuvre(times[j], q[j], q_dot[j], q_ddot[j]);
    }
}

/* Row j of the manoeuvre as a stewart_pose. */
static stewart_pose pose_of_row(int j) {
    stewart_pose p;
    memcpy(p.q, q[j], sizeof p.q);
    memcpy(p.q_dot, q_dot[j], sizeof p.q_dot);
    memcpy(p.q_ddot, q_ddot[j], sizeof p.q_ddot);
    return p;
}

static void test_solve_batch_equals_the_loop(void) {
    fill_rows();
    q[5][0] = NAN;          /* a bad row: the rows after it are still solved */
    q_dot[9][1] = INFINITY; /* a bad rate */
    stewart_inverse_options o;
    stewart_inverse_options_default(&o);
    o.fidelity = STEWART_FULL;
    double length[ROWS][6], force[ROWS][6], condition[ROWS];
    int status[ROWS], iterations[ROWS], stroke_legs[ROWS];
    const stewart_inverse_batch_outputs out = {.length = &length[0][0],
                                               .force = &force[0][0],
                                               .condition = condition,
                                               .iterations = iterations,
                                               .stroke_legs = stroke_legs,
                                               .status = status};
    size_t rows[4], first_failed = 0;
    char text[4 * STEWART_MESSAGE_SIZE];
    stewart_batch_messages messages = {4, 0, rows, text};
    stewart_inverse *batch = stewart_inverse_create(model, &o, NULL, 0);
    TEST_ASSERT_NOT_NULL(batch);
    const stewart_status s = stewart_inverse_batch(batch, ROWS, &q[0][0], &q_dot[0][0],
                                                   &q_ddot[0][0], &out, &messages, &first_failed);
    stewart_inverse_free(batch);
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, s);
    TEST_ASSERT_EQUAL_size_t(5, first_failed);
    TEST_ASSERT_EQUAL_size_t(2, messages.count);
    TEST_ASSERT_EQUAL_size_t(5, rows[0]);
    TEST_ASSERT_EQUAL_size_t(9, rows[1]);

    stewart_inverse *loop = test_inverse(model);
    for (int j = 0; j < ROWS; ++j) {
        const stewart_pose p = pose_of_row(j);
        stewart_inverse_output r;
        memset(&r, 0, sizeof r);
        const stewart_status sj = solve_as(loop, &o, &p, &r);
        TEST_ASSERT_EQUAL_INT(sj, status[j]);
        TEST_ASSERT_EQUAL_INT(j == 5 || j == 9 ? 1 : 0, sj != STEWART_OK);
        if (sj != STEWART_OK) memset(&r, 0, sizeof r);
        TEST_ASSERT_EQUAL_MEMORY(r.lengths.length, length[j], sizeof r.lengths.length);
        TEST_ASSERT_EQUAL_MEMORY(r.force, force[j], sizeof r.force);
        TEST_ASSERT_EQUAL_MEMORY(&r.condition, &condition[j], sizeof r.condition);
        TEST_ASSERT_EQUAL_INT(r.iterations, iterations[j]);
        TEST_ASSERT_EQUAL_INT(r.stroke_legs, stroke_legs[j]);
    }
    stewart_inverse_free(loop);
}

/* The lengths, rates and accelerations of the manoeuvre (the inverse side's closed form). */
static void leg_motion(double L[ROWS][6], double L_dot[ROWS][6], double L_ddot[ROWS][6]) {
    stewart_inverse_options o;
    stewart_inverse_options_default(&o);
    o.fidelity = STEWART_KINEMATIC;
    for (int j = 0; j < ROWS; ++j) {
        const stewart_pose p = pose_of_row(j);
        stewart_inverse_output r;
        TEST_ASSERT_EQUAL_INT(STEWART_OK, solve_as(data, &o, &p, &r));
        memcpy(L[j], r.lengths.length, sizeof r.lengths.length);
        memcpy(L_dot[j], r.lengths.length_rate, sizeof r.lengths.length_rate);
        memcpy(L_ddot[j], r.lengths.length_accel, sizeof r.lengths.length_accel);
    }
}

static void test_forward_batch_equals_the_loop(void) {
    fill_rows();
    double L[ROWS][6], L_dot[ROWS][6], L_ddot[ROWS][6];
    leg_motion(L, L_dot, L_ddot);
    L[7][3] = INFINITY;                                                    /* a bad measurement */
    L[12][0] = L[12][1] = L[12][2] = L[12][3] = L[12][4] = L[12][5] = 0.1; /* unreachable */
    stewart_forward_options o;
    stewart_forward_options_default(&o);
    double pose[ROWS][6], rate[ROWS][6], accel[ROWS][6], residual[ROWS];
    int status[ROWS], iterations[ROWS], start[ROWS], branch[ROWS];
    const stewart_forward_batch_outputs out = {.pose = &pose[0][0],
                                               .pose_rate = &rate[0][0],
                                               .pose_accel = &accel[0][0],
                                               .residual = residual,
                                               .iterations = iterations,
                                               .branch = branch,
                                               .start = start,
                                               .status = status};
    size_t first_failed = 0;
    stewart_forward *batch = stewart_forward_create(model, &o, NULL, 0);
    TEST_ASSERT_NOT_NULL(batch);
    const stewart_status s = stewart_forward_batch(batch, ROWS, times, &L[0][0], &L_dot[0][0],
                                                   &L_ddot[0][0], NULL, &out, NULL, &first_failed);
    stewart_forward_free(batch);
    TEST_ASSERT_NOT_EQUAL_INT(STEWART_OK, s);
    TEST_ASSERT_EQUAL_size_t(7, first_failed);
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, status[7]);
    TEST_ASSERT_NOT_EQUAL_INT(STEWART_OK, status[12]);

    stewart_forward *loop = stewart_forward_create(model, &o, NULL, 0);
    for (int j = 0; j < ROWS; ++j) {
        stewart_forward_output r;
        memset(&r, 0, sizeof r);
        stewart_forward_input in = {times[j], {{0}}, 2, 0, {0}};
        memcpy(in.lengths.length, L[j], sizeof L[j]);
        memcpy(in.lengths.length_rate, L_dot[j], sizeof L_dot[j]);
        memcpy(in.lengths.length_accel, L_ddot[j], sizeof L_ddot[j]);
        const stewart_status sj = stewart_forward_solve(loop, &in, &r);
        TEST_ASSERT_EQUAL_INT(sj, status[j]);
        TEST_ASSERT_EQUAL_INT(j == 7 || j == 12 ? 1 : 0, sj != STEWART_OK);
        if (sj != STEWART_OK) {
            for (int i = 0; i < 6; ++i) TEST_ASSERT_EQUAL_DOUBLE(0.0, pose[j][i]);
            continue;
        }
        TEST_ASSERT_EQUAL_MEMORY(r.pose.q, pose[j], sizeof r.pose.q);
        TEST_ASSERT_EQUAL_MEMORY(r.pose.q_dot, rate[j], sizeof r.pose.q_dot);
        TEST_ASSERT_EQUAL_MEMORY(r.pose.q_ddot, accel[j], sizeof r.pose.q_ddot);
        TEST_ASSERT_EQUAL_MEMORY(&r.residual, &residual[j], sizeof r.residual);
        TEST_ASSERT_EQUAL_INT(r.iterations, iterations[j]);
        TEST_ASSERT_EQUAL_INT(r.start, start[j]);
        TEST_ASSERT_EQUAL_INT(r.branch, branch[j]);
        /* and the poses are the manoeuvre's (the inverse side's closed form) */
        for (int i = 0; i < 6; ++i) TEST_ASSERT_DOUBLE_WITHIN(1e-12, q[j][i], pose[j][i]);
    }
    stewart_forward_free(loop);
}

/* Forces linear in time: gravity-like support plus a wobble, so the platform moves. */
static void forces(double F[ROWS][6]) {
    for (int j = 0; j < ROWS; ++j)
        for (int k = 0; k < 6; ++k) F[j][k] = 400.0 + 50.0 * sin(3.0 * times[j] + k);
}

static stewart_plant *plant_of(int fidelity) {
    const stewart_plant_options o = test_plant_options(fidelity);
    return test_plant_with(model, &o);
}

static void simulate_equals_the_loop(int fidelity) {
    fill_rows();
    double F[ROWS][6];
    forces(F);
    const double start[6] = {0.01, 0, params.home_height, 0, 0.02, 0};
    double pose[ROWS][6], rate[ROWS][6], length[ROWS][6];
    long steps[ROWS];
    int status[ROWS];
    const stewart_plant_batch_outputs out = {.pose = &pose[0][0],
                                             .pose_rate = &rate[0][0],
                                             .length = &length[0][0],
                                             .steps = steps,
                                             .status = status};
    stewart_plant *batch = plant_of(fidelity), *loop = plant_of(fidelity);
    size_t first_failed = 0;
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_plant_batch(batch, ROWS, times, &F[0][0], start, NULL,
                                                          &out, NULL, &first_failed));
    TEST_ASSERT_EQUAL_size_t(ROWS, first_failed);
    const double at_rest[6] = {0};
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_plant_set_state(loop, times[0], start, at_rest));
    for (int j = 0; j < ROWS; ++j) {
        TEST_ASSERT_EQUAL_INT(STEWART_OK, status[j]);
        stewart_plant_statistics st = {0};
        stewart_plant_output o;
        if (j > 0) {
            stewart_plant_input in = {times[j] - times[j - 1], {0}, {0}, 0, {0}, {0}};
            memcpy(in.force_start, F[j - 1], sizeof in.force_start);
            memcpy(in.force_end, F[j], sizeof in.force_end);
            TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_plant_step(loop, &in, &o));
            stewart_plant_statistics_get(loop, &st);
        } else {
            TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_plant_output_get(loop, F[j], &o));
        }
        TEST_ASSERT_EQUAL_MEMORY(o.pose.q, pose[j], sizeof o.pose.q);
        TEST_ASSERT_EQUAL_MEMORY(o.pose.q_dot, rate[j], sizeof o.pose.q_dot);
        TEST_ASSERT_EQUAL_MEMORY(o.lengths.length, length[j], sizeof o.lengths.length);
        TEST_ASSERT_EQUAL_INT(st.steps, steps[j]);
    }
    TEST_ASSERT_EQUAL_DOUBLE(start[0], pose[0][0]);
    TEST_ASSERT_TRUE(fabs(pose[ROWS - 1][2] - start[2]) > 1e-6); /* it moved */
    stewart_plant_free(batch);
    stewart_plant_free(loop);
}

static void test_simulate_batch_equals_the_loop_massless(void) {
    simulate_equals_the_loop(STEWART_MASSLESS);
}
static void test_simulate_batch_equals_the_loop_full(void) {
    simulate_equals_the_loop(STEWART_FULL);
}

static void test_refused_step_stops_the_run(void) {
    fill_rows();
    double F[ROWS][6];
    forces(F);
    F[10][4] = NAN;
    double pose[ROWS][6];
    int status[ROWS];
    stewart_plant_batch_outputs out;
    memset(&out, 0, sizeof out);
    out.pose = &pose[0][0];
    out.status = status;
    stewart_plant *plant = plant_of(STEWART_MASSLESS);
    char message[STEWART_MESSAGE_SIZE];
    size_t rows[1], first_failed = 0;
    stewart_batch_messages messages = {1, 0, rows, message};
    const stewart_status s = stewart_plant_batch(plant, ROWS, times, &F[0][0], NULL, NULL, &out,
                                                 &messages, &first_failed);
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, s);
    TEST_ASSERT_EQUAL_size_t(10, first_failed);
    TEST_ASSERT_NOT_NULL(strstr(message, "row 10"));
    for (int j = 0; j < ROWS; ++j)
        TEST_ASSERT_EQUAL_INT(j < 10 ? STEWART_OK : j == 10 ? s : STEWART_BATCH_NOT_RUN, status[j]);
    for (int i = 0; i < 6; ++i) TEST_ASSERT_EQUAL_DOUBLE(0.0, pose[ROWS - 1][i]);
    /* the plant stays at row 9 and is usable: a run from there goes on */
    stewart_plant_output now;
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_plant_output_get(plant, NULL, &now));
    TEST_ASSERT_EQUAL_DOUBLE(times[9], now.time);
    TEST_ASSERT_EQUAL_MEMORY(pose[9], now.pose.q, sizeof now.pose.q);
    /* a time that does not increase is refused at its row */
    times[3] = times[2];
    F[10][4] = 0;
    TEST_ASSERT_NOT_EQUAL_INT(STEWART_OK, stewart_plant_batch(plant, ROWS, times, &F[0][0], NULL,
                                                              NULL, &out, NULL, &first_failed));
    TEST_ASSERT_EQUAL_size_t(3, first_failed);
    TEST_ASSERT_EQUAL_INT(STEWART_BATCH_NOT_RUN, status[4]);
    stewart_plant_free(plant);
}

/* stewart_plant_batch_rows in slices of 5 rows equals one stewart_plant_batch bit for bit, and a
 * step refused in a later slice stops the run there, numbered in the whole arrays. */
static void test_plant_batch_in_slices_equals_one_batch(void) {
    fill_rows();
    double F[ROWS][6];
    forces(F);
    const double start[6] = {0.01, 0, params.home_height, 0, 0.02, 0};
    double pose[2][ROWS][6], rate[2][ROWS][6];
    long steps[2][ROWS];
    int status[2][ROWS];
    stewart_plant_batch_outputs out[2];
    for (int i = 0; i < 2; ++i)
        out[i] = (stewart_plant_batch_outputs){.pose = &pose[i][0][0],
                                               .pose_rate = &rate[i][0][0],
                                               .steps = steps[i],
                                               .status = status[i]};
    for (int refused = 0; refused < 2; ++refused) {
        F[17][2] = refused ? INFINITY : F[17][3];
        stewart_plant *whole = plant_of(STEWART_FULL), *sliced = plant_of(STEWART_FULL);
        size_t first_failed = 0;
        const stewart_status s = stewart_plant_batch(whole, ROWS, times, &F[0][0], start, NULL,
                                                     &out[0], NULL, &first_failed);
        TEST_ASSERT_EQUAL_size_t(refused ? 17 : ROWS, first_failed);
        memset(status[1], 0x7f, sizeof status[1]);
        stewart_status t = STEWART_OK;
        size_t first = 0, failed_in_slice = 0;
        for (; first < ROWS && t == STEWART_OK; first += 5) {
            const size_t stop = first + 5 < ROWS ? first + 5 : ROWS;
            t = stewart_plant_batch_rows(sliced, ROWS, first, stop, times, &F[0][0], start, NULL,
                                         &out[1], NULL, &failed_in_slice);
            TEST_ASSERT_EQUAL_size_t(t == STEWART_OK ? stop : 17, failed_in_slice);
        }
        TEST_ASSERT_EQUAL_INT(s, t);
        TEST_ASSERT_EQUAL_MEMORY(status[0], status[1], sizeof status[0]);
        TEST_ASSERT_EQUAL_MEMORY(pose[0], pose[1], sizeof pose[0]);
        TEST_ASSERT_EQUAL_MEMORY(rate[0], rate[1], sizeof rate[0]);
        TEST_ASSERT_EQUAL_MEMORY(steps[0], steps[1], sizeof steps[0]);
        stewart_plant_free(whole);
        stewart_plant_free(sliced);
    }
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_solve_batch_equals_the_loop);
    RUN_TEST(test_forward_batch_equals_the_loop);
    RUN_TEST(test_simulate_batch_equals_the_loop_massless);
    RUN_TEST(test_simulate_batch_equals_the_loop_full);
    RUN_TEST(test_refused_step_stops_the_run);
    RUN_TEST(test_plant_batch_in_slices_equals_one_batch);
    return UNITY_END();
}
