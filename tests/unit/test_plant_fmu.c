/*
 * The plant FMU (fmu/models/plant on fmu/runtime) driven through its FMI 2 and FMI 3 functions,
 * linked in statically, so that the ASan+UBSan build (tests/gates/sanitize.sh) and the TSan gate
 * (tests/gates/tsan.sh) run it. References independent of the unit: the inverse side's static
 * forces (stewart_inverse_solve) and the platform's weight for the rest state, closed-form leg lengths,
 * a second instance that never saw a bad input, sequential runs for the threaded ones.
 *
 * One executable links one model (every model defines the same fmi2* / fmi3* symbols): this one
 * links StewartPlant_model.
 */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plant_fmu_unit.h"
#include "stewart/stewart.h"
#include "test_support.h"
#include "unity.h"

/* A force history near the static forces: smooth, so the platform moves a little. */
static void wobbling_forces(const double statics[6], int step, double force[6]) {
    for (int k = 0; k < 6; ++k) force[k] = statics[k] * (1 + 0.02 * sin(0.05 * step + k));
}

void setUp(void) {}
void tearDown(void) {}

/* ---------------------------------------------------------------- at rest */

/* Under the inverse side's static forces the platform stays at home. It is a saddle (docs/
 * forward-dynamics.md: fastest mode lambda = 5.12 1/s), so an acceleration error a (forces of
 * the two sides that disagree, integration error) moves it by a (cosh(lambda t) - 1) / lambda^2,
 * 3.2 a over 1 s: the bound of 1e-12 m asks both sides to agree to 3e-13 m/s^2, 3e-14 of g
 * (measured 2.7e-14 m full, 4.4e-15 m massless). The legs keep their closed-form home lengths,
 * and the base carries the weight of the moving bodies. */
static void at_rest(int v3, int fidelity) {
    double force[6];
    static_forces(fidelity, force);
    unit u;
    unit_start(&u, v3, fidelity, force);
    double last = -1;
    for (int i = 0; i < 1000; ++i)
        TEST_ASSERT_EQUAL_MESSAGE(fmi2OK, do_step(&u, i * STEP, STEP, &last), u.log.last);
    TEST_ASSERT_EQUAL_DOUBLE(999 * STEP + STEP, last);
    const snapshot s = outputs(&u);
    stewart_params params;
    stewart_params_default(&params);
    const stewart_pose home = {{0, 0, params.home_height, 0, 0, 0}, {0}, {0}};
    double pose_error = 0, rate_error = 0, length_error = 0;
    for (int c = 0; c < 6; ++c) {
        pose_error = fmax(pose_error, fabs(s.real[c] - home.q[c]));
        rate_error = fmax(rate_error, fabs(s.real[6 + c]));
        length_error =
            fmax(length_error, fabs(s.real[12 + c] - closed_form_length(&params, &home, c)));
    }
    /* the weight of the moving bodies: the platform, and at full fidelity the twelve leg bodies */
    double mass = params.platform_mass + params.payload_mass;
    if (fidelity == STEWART_FULL) mass += 6 * (params.cylinder_mass + params.piston_mass);
    const double weight[3] = {mass * params.gravity[0], mass * params.gravity[1],
                              mass * params.gravity[2]};
    double wrench_error = 0;
    for (int i = 0; i < 3; ++i) wrench_error = fmax(wrench_error, fabs(s.real[24 + i] - weight[i]));
    printf("at rest (FMI %d, fidelity %d), 1 s: pose %.3g, rates %.3g, lengths %.3g, base force "
           "%.3g N off the weight %.6g N\n",
           v3 ? 3 : 2, fidelity, pose_error, rate_error, length_error, wrench_error, weight[2]);
    TEST_ASSERT_TRUE(pose_error <= 1e-12);
    TEST_ASSERT_TRUE(rate_error <= 1e-11);
    TEST_ASSERT_TRUE(length_error <= 1e-12);
    TEST_ASSERT_TRUE(wrench_error <= 1e-8 * fabs(weight[2]));
    TEST_ASSERT_EQUAL_INT(0, s.integer[0]);
    TEST_ASSERT_TRUE(s.integer[6] >= 1000); /* total_steps: at least one per communication step */
    unit_free(&u);
}

static void test_at_rest_fmi2_full(void) { at_rest(0, STEWART_FULL); }
static void test_at_rest_fmi3_full(void) { at_rest(1, STEWART_FULL); }
static void test_at_rest_fmi2_massless(void) { at_rest(0, STEWART_MASSLESS); }
static void test_at_rest_fmi3_massless(void) { at_rest(1, STEWART_MASSLESS); }

/* ---------------------------------------------------------------- FMU state */

/* Steps `count` steps from step `first` with the wobbling forces (and in FMI 2 their rates),
 * keeping the outputs after each. */
static void run_steps(unit *u, const double statics[6], int first, int count, snapshot *out) {
    for (int i = 0; i < count; ++i) {
        const int step = first + i;
        double force[6], next[6], rate[6], last;
        wobbling_forces(statics, step, force);
        wobbling_forces(statics, step + 1, next);
        for (int k = 0; k < 6; ++k) rate[k] = (next[k] - force[k]) / STEP;
        TEST_ASSERT_EQUAL(fmi2OK, set_forces(u, force));
        if (!u->v3) TEST_ASSERT_EQUAL(fmi2OK, set_force_rates(u, rate));
        TEST_ASSERT_EQUAL_MESSAGE(fmi2OK, do_step(u, step * STEP, STEP, &last), u->log.last);
        out[i] = outputs(u);
    }
}

/* Rolled back (in memory, and serialised into another instance built with the other fidelity)
 * the unit repeats its outputs and statistics bit for bit. */
static void rollback(int v3) {
    double statics[6];
    static_forces(STEWART_FULL, statics);
    unit u, other;
    unit_start(&u, v3, STEWART_FULL, statics);
    unit_start(&other, v3, STEWART_MASSLESS, statics);
    snapshot warm_up[100], first[50], again[50], elsewhere[50];
    run_steps(&u, statics, 0, 100, warm_up); /* move away from rest */
    void *state = NULL;
    TEST_ASSERT_EQUAL(fmi2OK,
                      v3 ? (int)fmi3GetFMUState(u.c, &state) : (int)fmi2GetFMUstate(u.c, &state));
    run_steps(&u, statics, 100, 50, first);
    TEST_ASSERT_EQUAL(fmi2OK,
                      v3 ? (int)fmi3SetFMUState(u.c, state) : (int)fmi2SetFMUstate(u.c, state));
    run_steps(&u, statics, 100, 50, again);
    size_t size = 0;
    TEST_ASSERT_EQUAL(fmi2OK, v3 ? (int)fmi3SerializedFMUStateSize(u.c, state, &size)
                                 : (int)fmi2SerializedFMUstateSize(u.c, state, &size));
    unsigned char *bytes = malloc(size);
    TEST_ASSERT_EQUAL(fmi2OK, v3 ? (int)fmi3SerializeFMUState(u.c, state, bytes, size)
                                 : (int)fmi2SerializeFMUstate(u.c, state, (fmi2Byte *)bytes, size));
    void *copy = NULL;
    TEST_ASSERT_EQUAL(fmi2OK,
                      v3 ? (int)fmi3DeserializeFMUState(other.c, bytes, size, &copy)
                         : (int)fmi2DeSerializeFMUstate(other.c, (fmi2Byte *)bytes, size, &copy));
    TEST_ASSERT_EQUAL_MESSAGE(fmi2OK,
                              v3 ? (int)fmi3SetFMUState(other.c, copy)
                                 : (int)fmi2SetFMUstate(other.c, copy),
                              other.log.last);
    run_steps(&other, statics, 100, 50, elsewhere);
    for (int i = 0; i < 50; ++i) {
        assert_same_bits(&first[i], &again[i], "rolled back in memory");
        assert_same_bits(&first[i], &elsewhere[i], "deserialised on an instance of fidelity 1");
    }
    TEST_ASSERT_TRUE(first[49].real[2] != first[0].real[2]); /* the platform moved */
    if (v3) {
        fmi3FreeFMUState(u.c, &state);
        fmi3FreeFMUState(other.c, &copy);
    } else {
        fmi2FreeFMUstate(u.c, &state);
        fmi2FreeFMUstate(other.c, &copy);
    }
    free(bytes);
    unit_free(&u);
    unit_free(&other);
}

static void test_rollback_bit_for_bit_fmi2(void) { rollback(0); }
static void test_rollback_bit_for_bit_fmi3(void) { rollback(1); }

/* ---------------------------------------------------------------- bad input */

/* A NaN or infinite force (or FMI 2 force rate) is Discard naming it, status 3, outputs and time
 * kept; the next good step gives what an instance that never saw the bad input gives. */
static void bad_force(int v3, int which) {
    double statics[6];
    static_forces(STEWART_FULL, statics);
    unit u, clean;
    unit_start(&u, v3, STEWART_FULL, statics);
    unit_start(&clean, v3, STEWART_FULL, statics);
    snapshot before[10], reference[11];
    run_steps(&u, statics, 0, 10, before);
    run_steps(&clean, statics, 0, 11, reference);
    double bad[6], last = -1;
    wobbling_forces(statics, 10, bad);
    const char *expected = NULL;
    if (which == 0) {
        bad[2] = NAN;
        expected = "input F[3] = nan is not finite";
    } else if (which == 1) {
        bad[5] = -INFINITY;
        expected = "input F[6] = -inf is not finite";
    } else {
        TEST_ASSERT_EQUAL(fmi2OK, set_forces(&u, bad));
        const double rate[6] = {0, NAN, 0, 0, 0, 0};
        TEST_ASSERT_EQUAL(fmi2OK, set_force_rates(&u, rate));
        expected = "input derivative dF[2]/dt = nan is not finite";
    }
    if (which < 2) TEST_ASSERT_EQUAL(fmi2OK, set_forces(&u, bad));
    TEST_ASSERT_EQUAL(fmi2Discard, do_step(&u, 10 * STEP, STEP, &last));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(u.log.last, expected), u.log.last);
    TEST_ASSERT_EQUAL_DOUBLE(10 * STEP, last);
    snapshot refused = outputs(&u);
    TEST_ASSERT_EQUAL_INT(3, refused.integer[0]);
    refused.integer[0] = before[9].integer[0];
    assert_same_bits(&before[9], &refused, "outputs kept after the refused step");
    snapshot after[1];
    run_steps(&u, statics, 10, 1, after);
    assert_same_bits(&reference[10], &after[0], "the good step after the refused one");
    unit_free(&u);
    unit_free(&clean);
}

static void test_nan_force_discard_fmi2(void) { bad_force(0, 0); }
static void test_nan_force_discard_fmi3(void) { bad_force(1, 0); }
static void test_infinite_force_discard_fmi2(void) { bad_force(0, 1); }
static void test_nan_force_rate_discard_fmi2(void) { bad_force(0, 2); }

/* Forces so large that the accelerations pass 1e100, and a step the integrator cannot finish
 * within max_internal_steps: Discard with the plant's reason, then the instance steps on. */
static void test_refused_steps_leave_the_instance_usable(void) {
    double statics[6], huge[6], last;
    static_forces(STEWART_FULL, statics);
    unit u;
    unit_start(&u, 0, STEWART_FULL, statics);
    for (int k = 0; k < 6; ++k) huge[k] = 1e300;
    TEST_ASSERT_EQUAL(fmi2OK, set_forces(&u, huge));
    TEST_ASSERT_EQUAL(fmi2Discard, do_step(&u, 0, STEP, &last));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(u.log.last, "step refused"), u.log.last);
    TEST_ASSERT_EQUAL_DOUBLE(0, last);
    TEST_ASSERT_EQUAL(fmi2OK, set_forces(&u, statics));
    /* a 100 s step at 1e-10 needs far more than 10000 internal steps of the saddle */
    TEST_ASSERT_EQUAL(fmi2Discard, do_step(&u, 0, 100.0, &last));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(u.log.last, "step refused"), u.log.last);
    TEST_ASSERT_EQUAL_DOUBLE(0, last);
    TEST_ASSERT_EQUAL_MESSAGE(fmi2OK, do_step(&u, 0, STEP, &last), u.log.last);
    TEST_ASSERT_EQUAL_DOUBLE(STEP, last);
    /* a gap in time is an Error naming both times */
    TEST_ASSERT_EQUAL(fmi2Error, do_step(&u, 2 * STEP, STEP, &last));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(u.log.last, "cannot skip time"), u.log.last);
    unit_free(&u);
}

/* ---------------------------------------------------------------- side by side */

/* Two instances stepped alternately (FMI 2 and FMI 3, held forces) give what one instance alone
 * gives, bit for bit. */
static void test_two_instances_side_by_side_bit_for_bit(void) {
    double statics[6];
    static_forces(STEWART_FULL, statics);
    unit alone, a, b;
    unit_start(&alone, 0, STEWART_FULL, statics);
    unit_start(&a, 0, STEWART_FULL, statics);
    unit_start(&b, 1, STEWART_FULL, statics);
    for (int step = 0; step < 200; ++step) {
        double force[6], last;
        wobbling_forces(statics, step, force);
        unit *units[3] = {&alone, &a, &b};
        for (int i = 0; i < 3; ++i) {
            TEST_ASSERT_EQUAL(fmi2OK, set_forces(units[i], force));
            TEST_ASSERT_EQUAL(fmi2OK, do_step(units[i], step * STEP, STEP, &last));
        }
        const snapshot s = outputs(&alone), sa = outputs(&a), sb = outputs(&b);
        assert_same_bits(&s, &sa, "FMI 2 instance beside another");
        assert_same_bits(&s, &sb, "FMI 3 instance beside another");
    }
    unit_free(&alone);
    unit_free(&a);
    unit_free(&b);
}

/* ---------------------------------------------------------------- threads */

#define THREADS 4
static int thread_steps = 200;

typedef struct thread_job {
    int index;
    snapshot last;
    int failed; /* the step that did not return OK, or -1 */
} thread_job;

/* One instance per job (FMI 2 for even jobs, FMI 3 for odd, both fidelities, FMI 2 with force
 * rates), no Unity assertion inside a thread: failures are recorded. */
static void *run_thread_job(void *arg) {
    thread_job *job = arg;
    const int v3 = job->index % 2, fidelity = job->index < 2 ? STEWART_FULL : STEWART_MASSLESS;
    double statics[6];
    static_forces(fidelity, statics);
    unit u;
    job->failed = 0;
    if (!unit_open(&u, v3, fidelity, statics)) return NULL;
    job->failed = -1;
    for (int step = 0; step < thread_steps && job->failed < 0; ++step) {
        double force[6], next[6], rate[6], last;
        wobbling_forces(statics, step, force);
        wobbling_forces(statics, step + 1, next);
        for (int k = 0; k < 6; ++k) rate[k] = (next[k] - force[k]) / STEP;
        if (set_forces(&u, force) != 0 || (!v3 && set_force_rates(&u, rate) != 0) ||
            do_step_status(&u, step * STEP, STEP, &last) != 0)
            job->failed = step;
    }
    if (!read_outputs(&u, &job->last)) job->failed = thread_steps;
    unit_free(&u);
    return NULL;
}

static void test_threads_match_sequential_runs_bit_for_bit(void) {
    thread_job sequential[THREADS], threaded[THREADS];
    pthread_t threads[THREADS];
    for (int i = 0; i < THREADS; ++i) {
        sequential[i] = (thread_job){.index = i};
        threaded[i] = sequential[i];
        run_thread_job(&sequential[i]);
        TEST_ASSERT_EQUAL_INT_MESSAGE(-1, sequential[i].failed, "sequential job");
    }
    for (int i = 0; i < THREADS; ++i)
        TEST_ASSERT_EQUAL_INT(0, pthread_create(&threads[i], NULL, run_thread_job, &threaded[i]));
    for (int i = 0; i < THREADS; ++i) TEST_ASSERT_EQUAL_INT(0, pthread_join(threads[i], NULL));
    for (int i = 0; i < THREADS; ++i) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(-1, threaded[i].failed, "threaded job");
        TEST_ASSERT_EQUAL_MEMORY(&sequential[i].last, &threaded[i].last, sizeof(snapshot));
    }
}

/* usage: test_plant_fmu [STEPS per thread job = 200] [--threads-only] (the TSan gate) */
int main(int argc, char **argv) {
    int threads_only = 0;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--threads-only") == 0) threads_only = 1;
        else thread_steps = atoi(argv[i]);
    }
    UNITY_BEGIN();
    if (!threads_only) {
        RUN_TEST(test_at_rest_fmi2_full);
        RUN_TEST(test_at_rest_fmi3_full);
        RUN_TEST(test_at_rest_fmi2_massless);
        RUN_TEST(test_at_rest_fmi3_massless);
        RUN_TEST(test_rollback_bit_for_bit_fmi2);
        RUN_TEST(test_rollback_bit_for_bit_fmi3);
        RUN_TEST(test_nan_force_discard_fmi2);
        RUN_TEST(test_nan_force_discard_fmi3);
        RUN_TEST(test_infinite_force_discard_fmi2);
        RUN_TEST(test_nan_force_rate_discard_fmi2);
        RUN_TEST(test_refused_steps_leave_the_instance_usable);
        RUN_TEST(test_two_instances_side_by_side_bit_for_bit);
    }
    RUN_TEST(test_threads_match_sequential_runs_bit_for_bit);
    return UNITY_END();
}
