/* Threads: eight jobs on ONE shared stewart_model (the documented sharing: a model is read-only
 * and may serve many solver objects), each with its own solver objects, its own forward-kinematics
 * tracking and its own plant, and eight FMU instances (FMI 2, linked in statically). Every job is
 * run sequentially first, then all at once in threads; the two runs must agree bit for bit.
 * Any hidden shared mutable state (a static scratch buffer, a global in the library or in
 * SUNDIALS' use) shows up as a difference here, or as a report under ThreadSanitizer
 * (tests/gates/tsan.sh builds this test with -fsanitize=thread).
 *
 * usage: test_threads [STEPS]   (communication steps per job; default 1000) */
#include <math.h>
#include <pthread.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "stewart/stewart.h"
#include "stewart/stewart_forward.h"
#include "stewart/stewart_plant.h"
#include "test_support.h"
#include "unity.h"
#include "variables.h"

#define JOBS 8
#define STEP_SIZE 1e-3

static int steps = 1000;
static stewart_model *shared_model;

/* ---- digests: FNV-1a over the bits of every value a job produced ---- */

static void digest_doubles(uint64_t *h, const double *values, int n) {
    for (int i = 0; i < n; ++i) {
        uint64_t bits;
        memcpy(&bits, &values[i], sizeof bits);
        for (int b = 0; b < 8; ++b) *h = (*h ^ ((bits >> (8 * b)) & 0xff)) * 1099511628211ull;
    }
}

static void digest_int(uint64_t *h, int value) {
    const double as_double = value;
    digest_doubles(h, &as_double, 1);
}

/* What one job produced: a digest per stream, the first failure, and the largest distance
 * between the commanded pose and the pose forward kinematics found from the lengths. */
typedef struct job_result {
    uint64_t inverse, forward, plant, fmu;
    int failed_step; /* -1 if every call returned OK */
    char failure[160];
    double forward_pose_error;
    long plant_rhs_evaluations;
} job_result;

static void fail(job_result *r, int step, const char *what, const char *message) {
    if (r->failed_step >= 0) return;
    r->failed_step = step;
    snprintf(r->failure, sizeof r->failure, "%s: %s", what, message);
}

/* ---- one library job: inverse solve, forward kinematics and plant along one manoeuvre ---- */

/* The combined manoeuvre, shifted in time per job so that jobs differ. */
static stewart_pose job_pose(int job, int step) {
    return combined_pose(0.37 * job + step * STEP_SIZE);
}

static void run_library_job(int job, job_result *r) {
    const stewart_inverse_options inverse_options = test_options((stewart_fidelity)(job % 3));
    const stewart_inverse_options feed_options = test_options(STEWART_MASSLESS);
    stewart_forward_options forward_options;
    stewart_forward_options_default(&forward_options);
    stewart_plant_options plant_options;
    stewart_plant_options_default(&plant_options);
    plant_options.fidelity = (job % 2) ? STEWART_MASSLESS : STEWART_FULL;
    plant_options.method = job % 4; /* Adams, BDF (CVODE), ERK, ERK5 (ARKODE) */
    plant_options.relative_tolerance = 1e-8;
    plant_options.absolute_tolerance = 1e-10;

    char message[STEWART_MESSAGE_SIZE];
    stewart_inverse *inverse = stewart_inverse_create(shared_model, &inverse_options, NULL, 0);
    stewart_inverse *feed = stewart_inverse_create(shared_model, &feed_options, NULL, 0);
    stewart_forward *forward = stewart_forward_create(shared_model, &forward_options, NULL, 0);
    stewart_plant *plant =
        stewart_plant_create(shared_model, &plant_options, message, sizeof message);
    r->inverse = r->forward = r->plant = 14695981039346656037ull;
    if (!inverse || !feed || !forward || !plant) {
        fail(r, 0, "create", plant ? "solver object" : message);
        goto done;
    }
    const stewart_pose start = job_pose(job, 0);
    if (stewart_plant_set_state(plant, 0.0, start.q, start.q_dot) != STEWART_OK) {
        fail(r, 0, "plant_set_state", stewart_plant_message(plant));
        goto done;
    }
    double force0[STEWART_LEGS];
    for (int step = 0; step <= steps; ++step) {
        const stewart_pose pose = job_pose(job, step);
        stewart_inverse_output out, feed_out;
        const stewart_inverse_input in = {pose};
        if (stewart_inverse_solve(inverse, &in, &out) != STEWART_OK) {
            fail(r, step, "solve", stewart_inverse_message(inverse));
            break;
        }
        digest_doubles(&r->inverse, &out.lengths.length[0], 4 * STEWART_LEGS);
        digest_doubles(&r->inverse, &out.condition, 1);
        digest_doubles(&r->inverse, &out.residual, 1);
        digest_doubles(&r->inverse, out.base_force, 3);
        digest_doubles(&r->inverse, out.base_torque, 3);
        digest_int(&r->inverse, out.iterations);
        digest_int(&r->inverse, out.warnings);

        stewart_forward_input measured = {step * STEP_SIZE, out.lengths, 2, 0, {0}};
        stewart_forward_output fk;
        if (stewart_forward_solve(forward, &measured, &fk) != STEWART_OK) {
            fail(r, step, "forward_solve", stewart_forward_message(forward));
            break;
        }
        digest_doubles(&r->forward, fk.pose.q, 18);
        digest_doubles(&r->forward, &fk.residual, 1);
        digest_doubles(&r->forward, &fk.condition, 1);
        digest_doubles(&r->forward, &fk.jump, 1);
        digest_int(&r->forward, fk.iterations);
        digest_int(&r->forward, fk.start);
        for (int i = 0; i < 6; ++i)
            r->forward_pose_error = fmax(r->forward_pose_error, fabs(fk.pose.q[i] - pose.q[i]));

        /* The plant is driven open loop by the massless inverse forces of the same manoeuvre. */
        if (stewart_inverse_solve(feed, &in, &feed_out) != STEWART_OK) {
            fail(r, step, "feed solve", stewart_inverse_message(feed));
            break;
        }
        stewart_plant_input held = {STEP_SIZE, {0}, {0}, 0, {0}, {0}};
        memcpy(held.force_start, force0, sizeof held.force_start);
        memcpy(held.force_end, feed_out.force, sizeof held.force_end);
        stewart_plant_output stepped;
        if (step > 0 && stewart_plant_step(plant, &held, &stepped) != STEWART_OK) {
            fail(r, step, "plant_step", stewart_plant_message(plant));
            break;
        }
        memcpy(force0, feed_out.force, sizeof force0);
        stewart_plant_output po;
        if (stewart_plant_output_get(plant, NULL, &po) != STEWART_OK) {
            fail(r, step, "plant_output_get", stewart_plant_message(plant));
            break;
        }
        digest_doubles(&r->plant, &po.time,
                       (int)(offsetof(stewart_plant_output, warnings) / sizeof(double)));
        digest_int(&r->plant, po.warnings);
    }
    stewart_plant_statistics stats;
    stewart_plant_statistics_get(plant, &stats);
    digest_int(&r->plant, (int)stats.total_rhs_evaluations);
    r->plant_rhs_evaluations = stats.total_rhs_evaluations;
done:
    stewart_plant_free(plant);
    stewart_forward_free(forward);
    stewart_inverse_free(feed);
    stewart_inverse_free(inverse);
}

/* ---- one FMU job: an FMI 2 instance stepping the same manoeuvre ---- */

static void fmu_logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                       fmi2String category, fmi2String message, ...) {
    (void)env, (void)name, (void)status, (void)category, (void)message;
}

static unsigned value_reference(const char *name) {
    for (size_t i = 0; i < fmu_n_variables; ++i)
        if (strcmp(fmu_variables[i].name, name) == 0) return fmu_variables[i].vr;
    return (unsigned)-1;
}

static void run_fmu_job(int job, job_result *r) {
    const fmi2CallbackFunctions callbacks = {fmu_logger, calloc, free, NULL, NULL};
    r->fmu = 14695981039346656037ull;
    fmi2Component c = fmi2Instantiate("threads", fmi2CoSimulation, FMU_GUID, "", &callbacks,
                                      fmi2False, fmi2False);
    if (!c) {
        fail(r, 0, "fmi2Instantiate", "NULL");
        return;
    }
    const fmi2ValueReference option_vr[2] = {value_reference("fidelity"),
                                             value_reference("derivatives")};
    const fmi2Integer option_value[2] = {job % 3, (job / 3) % 2};
    fmi2ValueReference pose_vr[18], output_vr[64];
    size_t n_outputs = 0;
    for (int i = 0; i < 18; ++i) pose_vr[i] = (fmi2ValueReference)i;
    for (size_t i = 0; i < fmu_n_variables && n_outputs < 64; ++i)
        if (fmu_variables[i].type == FMU_REAL && fmu_variables[i].causality == FMU_OUTPUT_VAR)
            output_vr[n_outputs++] = fmu_variables[i].vr;
    if (fmi2SetInteger(c, option_vr, 2, option_value) != fmi2OK ||
        fmi2SetupExperiment(c, fmi2False, 0, 0, fmi2False, 0) != fmi2OK ||
        fmi2EnterInitializationMode(c) != fmi2OK || fmi2ExitInitializationMode(c) != fmi2OK) {
        fail(r, 0, "fmu initialisation", "not OK");
        fmi2FreeInstance(c);
        return;
    }
    for (int step = 0; step < steps; ++step) {
        const stewart_pose pose = job_pose(job, step + 1);
        fmi2Real inputs[18], outputs[64];
        memcpy(inputs, pose.q, sizeof pose.q);
        memcpy(inputs + 6, pose.q_dot, sizeof pose.q_dot);
        memcpy(inputs + 12, pose.q_ddot, sizeof pose.q_ddot);
        if (fmi2SetReal(c, pose_vr, 18, inputs) != fmi2OK ||
            fmi2DoStep(c, step * STEP_SIZE, STEP_SIZE, fmi2True) != fmi2OK ||
            fmi2GetReal(c, output_vr, n_outputs, outputs) != fmi2OK) {
            fail(r, step, "fmu step", "not OK");
            break;
        }
        digest_doubles(&r->fmu, outputs, (int)n_outputs);
    }
    fmi2Terminate(c);
    fmi2FreeInstance(c);
}

/* ---- sequential, then threaded ---- */

typedef struct job {
    int index;
    int with_fmu;
    job_result result;
} job;

static void *run_job(void *arg) {
    job *j = arg;
    memset(&j->result, 0, sizeof j->result);
    j->result.failed_step = -1;
    run_library_job(j->index, &j->result);
    if (j->with_fmu) run_fmu_job(j->index, &j->result);
    return NULL;
}

static void run_all(job jobs[JOBS], int threaded) {
    pthread_t threads[JOBS];
    for (int i = 0; i < JOBS; ++i) {
        if (!threaded) run_job(&jobs[i]);
        else TEST_ASSERT_EQUAL_INT(0, pthread_create(&threads[i], NULL, run_job, &jobs[i]));
    }
    for (int i = 0; i < JOBS && threaded; ++i)
        TEST_ASSERT_EQUAL_INT(0, pthread_join(threads[i], NULL));
}

void setUp(void) {
    stewart_params params;
    stewart_params_default(&params);
    shared_model = test_model(&params);
}

void tearDown(void) { stewart_model_free(shared_model); }

static void test_threads_match_sequential_runs_bit_for_bit(void) {
    job sequential[JOBS], threaded[JOBS];
    for (int i = 0; i < JOBS; ++i) {
        sequential[i] = (job){.index = i, .with_fmu = 1};
        threaded[i] = sequential[i];
    }
    run_all(sequential, 0);
    run_all(threaded, 1);
    char what[256];
    for (int i = 0; i < JOBS; ++i) {
        const job_result *s = &sequential[i].result, *t = &threaded[i].result;
        snprintf(what, sizeof what, "job %d failed at step %d: %s", i, s->failed_step, s->failure);
        TEST_ASSERT_EQUAL_INT_MESSAGE(-1, s->failed_step, what);
        snprintf(what, sizeof what, "job %d (threaded) failed at step %d: %s", i, t->failed_step,
                 t->failure);
        TEST_ASSERT_EQUAL_INT_MESSAGE(-1, t->failed_step, what);
        /* The forward run is a real one: it recovers the commanded pose from the lengths. */
        TEST_ASSERT_TRUE_MESSAGE(s->forward_pose_error < 1e-9,
                                 "forward pose differs from the command");
        printf("job %d: inverse fidelity %d, plant fidelity %d method %d: %d steps, forward pose "
               "error %.3g, plant rhs evaluations %ld\n",
               i, i % 3, (i % 2) ? 1 : 2, i % 4, steps, s->forward_pose_error,
               s->plant_rhs_evaluations);
        snprintf(what, sizeof what, "job %d: threaded results differ from the sequential run", i);
        TEST_ASSERT_TRUE_MESSAGE(s->inverse == t->inverse, what);
        TEST_ASSERT_TRUE_MESSAGE(s->forward == t->forward, what);
        TEST_ASSERT_TRUE_MESSAGE(s->plant == t->plant, what);
        TEST_ASSERT_TRUE_MESSAGE(s->fmu == t->fmu, what);
    }
    /* Jobs differ (fidelity, phase): equal digests across jobs would mean nothing was hashed. */
    TEST_ASSERT_TRUE(sequential[0].result.inverse != sequential[3].result.inverse);
    TEST_ASSERT_TRUE(sequential[0].result.plant != sequential[2].result.plant);
}

int main(int argc, char **argv) {
    if (argc > 1) steps = atoi(argv[1]);
    if (steps < 1) steps = 1;
    UNITY_BEGIN();
    RUN_TEST(test_threads_match_sequential_runs_bit_for_bit);
    return UNITY_END();
}
