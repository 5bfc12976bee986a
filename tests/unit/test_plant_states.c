/* The plant's saved states and the steps they lead to: a load either refuses a state with a
 * message and keeps the plant as it was, or the plant then steps normally with outputs consistent
 * with the closed form (thousands of random mutations of a saved state); a saved step hint no
 * step leaves, a step that does not advance time, pitch through +-90 degrees, a leg driven to zero
 * length and a tolerance no plant can use are refused with messages naming them. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "plant_fixture.h"
#include "stewart/stewart_plant.h"
#include "test_plant_support.h"
#include "test_support.h"
#include "unity.h"

#define MAX_STATE 64

static size_t state_size(void) {
    TEST_ASSERT_TRUE(plant_state_doubles() <= MAX_STATE);
    return plant_state_doubles();
}

static void save(const stewart_plant *p, double *state) { plant_save_doubles(p, state); }

/* Fails unless the message of the plant holds the fragment. */
static void expect_message(const stewart_plant *p, const char *fragment) {
    if (strstr(stewart_plant_message(p), fragment)) return;
    char text[STEWART_MESSAGE_SIZE + 64];
    snprintf(text, sizeof text, "message '%s' lacks '%s'", stewart_plant_message(p), fragment);
    TEST_FAIL_MESSAGE(text);
}

/* The inverse side's forces at rest at home (full fidelity). */
static void static_forces(double force[6]) {
    stewart_inverse *data = test_inverse(model);
    const stewart_pose home = {{0, 0, params.home_height, 0, 0, 0}, {0}, {0}};
    const stewart_inverse_output out = solve_ok(data, STEWART_FULL, &home);
    memcpy(force, out.force, sizeof out.force);
    stewart_inverse_free(data);
}

/* ---------------------------------------------------------------- item: the step hint */

/* A saved state whose step hint is subnormal (4.9e-324 s) is refused naming the hint; the smallest
 * hint a load takes (1e-100 s) leads to a step that reaches its end, and the plant goes on. */
static void test_step_hint_below_any_step_refused(void) {
    double force[6], state[MAX_STATE], before[MAX_STATE];
    static_forces(force);
    step_ok(plant, 1e-3, force, force, NULL, NULL);
    save(plant, state);
    memcpy(before, state, sizeof state);
    state[state_size() - 1] = 4.9e-324;
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, plant_load_doubles(plant, state, state_size()));
    expect_message(plant, "step hint 4.94066e-324");
    double now[MAX_STATE];
    save(plant, now);
    TEST_ASSERT_EQUAL_MEMORY(before, now, sizeof(double) * state_size());
    step_ok(plant, 1e-3, force, force, NULL, NULL); /* the refusal left the integrator clean */
    TEST_ASSERT_EQUAL(STEWART_OK, plant_load_doubles(plant, before, state_size()));
    state[state_size() - 1] = 1e-100;
    TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK, plant_load_doubles(plant, state, state_size()),
                              stewart_plant_message(plant));
    for (int i = 0; i < 3; ++i) {
        step_ok(plant, 1e-3, force, force, NULL, NULL);
        stewart_plant_output out;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, force, &out));
        TEST_ASSERT_EQUAL_DOUBLE(state[0] + (i + 1) * 1e-3, out.time);
        TEST_ASSERT_TRUE(fabs(out.pose.q[2] - params.home_height) < 1e-9);
    }
}

/* A step that does not advance time is refused naming h: subnormal at t = 0, below the
 * resolution of t at t = 100 s. */
static void test_step_that_does_not_advance_time_refused(void) {
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT,
                      plant_step_arrays(plant, 4.9e-324, kZero, kZero, NULL, NULL));
    expect_message(plant, "h = 4.94066e-324 s does not advance time");
    const double home[6] = {0, 0, params.home_height, 0, 0, 0};
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(plant, 100.0, home, kZero));
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT,
                      plant_step_arrays(plant, 1e-15, kZero, kZero, NULL, NULL));
    expect_message(plant, "h = 1e-15 s does not advance time t = 100");
    step_ok(plant, 1e-3, kZero, kZero, NULL, NULL);
    /* the plant's clock ends at 1e10 s: no step takes it beyond (a load would refuse the state) */
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(plant, 1e10 - 1e-4, home, kZero));
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT,
                      plant_step_arrays(plant, 1e-3, kZero, kZero, NULL, NULL));
    expect_message(plant, "takes time beyond 1e+10 s");
}

/* ---------------------------------------------------------------- pitch at +-90 degrees */

/* A free rotation about the platform's y axis at 1 rad/s from pitch 1.5 rad (no gravity, no
 * forces, massless legs: the platform turns uniformly) reaches 90 degrees after 70.8 ms: the
 * 1 ms step that would take it through is refused naming pitch, the state stays at the last good
 * point, and roll and yaw were 0 all the way (no jump by pi). Every integrator, and the
 * fixed steps (written out, they hand the step with the root to ARKODE). */
static void pitch_through_90_degrees(int method, int fixed_steps) {
    stewart_params free_params = params;
    free_params.gravity[2] = 0;
    stewart_model *free_model = test_model(&free_params);
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    o.fidelity = STEWART_MASSLESS;
    o.method = method;
    o.fixed_steps = fixed_steps;
    char message[STEWART_MESSAGE_SIZE];
    stewart_plant *p = stewart_plant_create(free_model, &o, message, sizeof message);
    TEST_ASSERT_NOT_NULL_MESSAGE(p, message);
    const double pose[6] = {0, 0, params.home_height, 0, 1.5, 0}, rate[6] = {0, 0, 0, 0, 1.0, 0};
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(p, 0, pose, rate));
    stewart_status s = STEWART_OK;
    int step = 0;
    double before[MAX_STATE], after[MAX_STATE];
    for (; step < 200; ++step) {
        save(p, before);
        s = plant_step_arrays(p, 1e-3, kZero, kZero, NULL, NULL);
        if (s != STEWART_OK) break;
        stewart_plant_output out;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(p, kZero, &out));
        TEST_ASSERT_TRUE_MESSAGE(fabs(out.pose.q[3]) < 1e-6 && fabs(out.pose.q[5]) < 1e-6,
                                 "roll and yaw stay 0 before the refusal");
        TEST_ASSERT_DOUBLE_WITHIN(1e-6, 1.5 + (step + 1) * 1e-3, out.pose.q[4]);
    }
    printf("pitch at 90 degrees, method %d: step %d (t = %g s): %s: %s\n", method, step,
           step * 1e-3, stewart_status_name(s), stewart_plant_message(p));
    TEST_ASSERT_EQUAL(STEWART_ERR_SINGULAR, s);
    TEST_ASSERT_EQUAL_INT(70, step); /* from 70 ms (pitch 1.570) through 1.5708 */
    expect_message(p, "pitch through +-90 degrees near t + 0.0007");
    save(p, after);
    TEST_ASSERT_EQUAL_MEMORY(before, after, sizeof(double) * state_size());
    stewart_plant_free(p);
    stewart_model_free(free_model);
}

static void test_pitch_through_90_degrees_refused(void) {
    for (int method = STEWART_PLANT_ADAMS; method <= STEWART_PLANT_ERK5; ++method)
        pitch_through_90_degrees(method, 0);
    pitch_through_90_degrees(STEWART_PLANT_ERK, 1); /* written out, handed to ARKODE at the root */
    pitch_through_90_degrees(STEWART_PLANT_ERK, 3);
}

/* ---------------------------------------------------------------- a leg driven to zero length */

/* The legs pulled at 1 kN from 2 cm above the pose where legs 1, 3, 5 have zero length (full
 * level, 1 ms steps): the legs' bodies swing ever faster as a leg shortens, and the step that
 * cannot get past is refused as unreachable, naming the leg, with the state kept. */
static void test_leg_driven_to_zero_length_is_unreachable(void) {
    const double pose[6] = {0, 0, 0.02, 0, 0, M_PI / 6}, rate[6] = {0};
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(plant, 0, pose, rate));
    const double pull[6] = {-1e3, -1e3, -1e3, -1e3, -1e3, -1e3};
    double before[MAX_STATE], after[MAX_STATE];
    stewart_status s = STEWART_OK;
    for (int i = 0; i < 100 && s == STEWART_OK; ++i) {
        save(plant, before);
        s = plant_step_arrays(plant, 1e-3, pull, pull, NULL, NULL);
    }
    printf("leg driven to zero length: %s: %s\n", stewart_status_name(s),
           stewart_plant_message(plant));
    TEST_ASSERT_EQUAL(STEWART_ERR_UNREACHABLE, s);
    expect_message(plant, "unreachable, leg ");
    save(plant, after);
    TEST_ASSERT_EQUAL_MEMORY(before, after, sizeof(double) * state_size());
}

/* ---------------------------------------------------------------- tolerances */

/* An absolute tolerance no plant can use is refused by the option check, naming it; the floor
 * itself makes a plant that steps. */
static void test_tolerance_no_plant_can_use_refused(void) {
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    char message[STEWART_MESSAGE_SIZE];
    o.absolute_tolerance = 1e-300;
    TEST_ASSERT_EQUAL(STEWART_ERR_PARAMETER,
                      stewart_plant_options_check(&o, message, sizeof message));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(message, "absolute_tolerance = 1e-300"), message);
    TEST_ASSERT_NULL(stewart_plant_create(model, &o, message, sizeof message));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(message, "absolute_tolerance = 1e-300"), message);
    o.absolute_tolerance = 1e-20;
    stewart_plant *p = stewart_plant_create(model, &o, message, sizeof message);
    TEST_ASSERT_NOT_NULL_MESSAGE(p, message);
    double force[6];
    static_forces(force);
    step_ok(p, 1e-3, force, force, NULL, NULL);
    stewart_plant_free(p);
}

/* ---------------------------------------------------------------- random corrupt states */


/* A saved state mutated at random (one to three values, 3000 times): either the load refuses it
 * with a message and the plant keeps its state, or the plant steps 5 ms normally from it (every
 * step OK, outputs finite, every leg length the closed form of the output pose, time advancing by
 * the steps). */
static void test_random_corrupt_states(void) {
    double force[6], base[MAX_STATE];
    static_forces(force);
    for (int k = 0; k < 6; ++k) force[k] *= 1.01; /* the platform moves */
    const double pose[6] = {0.01, -0.02, params.home_height + 0.01, 0.05, -0.03, 0.1};
    const double rate[6] = {0.01, 0.02, -0.01, 0.1, -0.05, 0.2};
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(plant, 2.0, pose, rate));
    for (int i = 0; i < 10; ++i) step_ok(plant, 1e-3, force, force, NULL, NULL);
    save(plant, base);
    const size_t n = state_size();
    uint64_t rng = 0x9E3779B97F4A7C15ULL;
    int refused = 0, accepted = 0, failures = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        TEST_ASSERT_EQUAL(STEWART_OK, plant_load_doubles(plant, base, n));
        double state[MAX_STATE], now[MAX_STATE];
        memcpy(state, base, sizeof state);
        const int edits = 1 + (int)(test_random(&rng) % 3);
        size_t index = 0;
        for (int e = 0; e < edits; ++e) {
            index = test_random(&rng) % n;
            state[index] = corrupted_value(&rng, state[index]);
        }
        if (plant_load_doubles(plant, state, n) != STEWART_OK) {
            ++refused;
            save(plant, now);
            TEST_ASSERT_TRUE(stewart_plant_message(plant)[0] != '\0');
            TEST_ASSERT_EQUAL_MEMORY(base, now, sizeof(double) * n);
            continue;
        }
        ++accepted;
        const char *why = NULL;
        stewart_plant_output out;
        for (int step = 0; step < 5 && !why; ++step) {
            if (plant_step_arrays(plant, 1e-3, force, force, NULL, NULL) != STEWART_OK) {
                why = stewart_plant_message(plant);
                break;
            }
            if (stewart_plant_output_get(plant, force, &out) != STEWART_OK) {
                why = "no outputs";
                break;
            }
            if (out.time != state[0] + (step + 1) * 1e-3 &&
                fabs(out.time - (state[0] + (step + 1) * 1e-3)) > 1e-12 * fabs(state[0]) + 1e-15)
                why = "time does not advance by the steps";
            stewart_pose p = {{0}, {0}, {0}};
            memcpy(p.q, out.pose.q, sizeof p.q);
            for (int k = 0; k < 6 && !why; ++k) {
                const double expected = closed_form_length(&params, &p, k);
                if (!(fabs(out.lengths.length[k] - expected) <= 1e-9 * fmax(1.0, expected)))
                    why = "a leg length is not the closed form of the output pose";
            }
        }
        if (why) {
            ++failures;
            if (failures <= 10)
                printf("trial %d: value %zu %.17g -> %.17g accepted, then: %s\n", trial, index,
                       base[index], state[index], why);
        }
    }
    printf("random corrupt states: %d refused, %d accepted and stepped, %d failures\n", refused,
           accepted, failures);
    TEST_ASSERT_EQUAL_INT(0, failures);
    TEST_ASSERT_TRUE(refused > 0 && accepted > 0);
}

/* The step's outputs against stewart_plant_output_get after it (a fresh evaluation of the
 * equations at the stored state): the step takes the accelerations and base wrench from the
 * integrator's own end-of-step evaluation, at the state before the quaternion's normalisation, so
 * the base wrench may differ by rounding only; everything else is the same bits. Both fidelities,
 * linear and Hermite forces, forces that change every step. */
static void expect_step_outputs_fresh(int fidelity, int hermite) {
    stewart_plant *p = test_plant(model, fidelity, 1e-10, 1e-12);
    double force[6];
    static_forces(force);
    for (int n = 0; n < 60; ++n) {
        stewart_plant_input in;
        memset(&in, 0, sizeof in);
        in.h = 1e-3;
        in.derivatives = hermite;
        for (int k = 0; k < 6; ++k) {
            in.force_start[k] = force[k] + 15.0 * sin(0.21 * n + k);
            in.force_end[k] = force[k] + 15.0 * sin(0.21 * (n + 1) + k);
            in.force_rate_start[k] = 15.0 * 210.0 * cos(0.21 * n + k);
            in.force_rate_end[k] = 15.0 * 210.0 * cos(0.21 * (n + 1) + k);
        }
        stewart_plant_output stepped, fresh;
        TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_plant_step(p, &in, &stepped),
                                      stewart_plant_message(p));
        TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_plant_output_get(p, in.force_end, &fresh));
        TEST_ASSERT_EQUAL_MEMORY(&fresh.pose, &stepped.pose, sizeof fresh.pose);
        TEST_ASSERT_EQUAL_MEMORY(&fresh.lengths, &stepped.lengths, sizeof fresh.lengths);
        TEST_ASSERT_EQUAL_INT(fresh.warnings, stepped.warnings);
        for (int i = 0; i < 3; ++i) {
            const double scale = 1.0 + fabs(fresh.base_force[i]) + fabs(fresh.base_torque[i]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-12 * scale, fresh.base_force[i], stepped.base_force[i]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-12 * scale, fresh.base_torque[i], stepped.base_torque[i]);
        }
    }
    stewart_plant_free(p);
}

void test_step_outputs_equal_a_fresh_evaluation(void) {
    for (int fidelity = STEWART_MASSLESS; fidelity <= STEWART_FULL; ++fidelity)
        for (int hermite = 0; hermite <= 1; ++hermite) expect_step_outputs_fresh(fidelity, hermite);
}

/* Fixed steps (stewart_plant_options.fixed_steps = N): every 1 ms step costs exactly 5 N + 1
 * right-hand sides (ERK 4(3): 4 new stages and the end evaluation per step, one at the start),
 * whatever the forces, and the motion stays within the fourth-order error of the adaptive
 * default: over 0.2 s of changing forces, 1e-9 m / rad for one step per ms, less for two. */
void test_fixed_steps_do_fixed_work_near_the_adaptive_result(void) {
    double force[6];
    static_forces(force);
    double worst[3] = {0, 0, 0};
    for (int n_fixed = 0; n_fixed <= 2; ++n_fixed) {
        stewart_plant_options o = test_plant_options(STEWART_FULL); /* the default fidelity */
        o.fixed_steps = n_fixed;
        stewart_plant *p = test_plant_with(model, &o);
        stewart_plant_output out;
        for (int n = 0; n < 200; ++n) {
            stewart_plant_input in;
            memset(&in, 0, sizeof in);
            in.h = 1e-3;
            for (int k = 0; k < 6; ++k) {
                in.force_start[k] = force[k] + 40.0 * sin(0.05 * n + k);
                in.force_end[k] = force[k] + 40.0 * sin(0.05 * (n + 1) + k);
            }
            TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_plant_step(p, &in, &out),
                                          stewart_plant_message(p));
            if (n_fixed > 0) {
                stewart_plant_statistics st;
                stewart_plant_statistics_get(p, &st);
                TEST_ASSERT_EQUAL_INT(5 * n_fixed + 1, st.rhs_evaluations);
                TEST_ASSERT_EQUAL_INT(n_fixed, st.steps);
            }
        }
        static double adaptive[6];
        if (n_fixed == 0) memcpy(adaptive, out.pose.q, sizeof adaptive);
        for (int i = 0; i < 6; ++i)
            worst[n_fixed] = fmax(worst[n_fixed], fabs(out.pose.q[i] - adaptive[i]));
        stewart_plant_free(p);
    }
    printf("fixed steps against the adaptive default after 0.2 s: 1 per ms %.3g, 2 per ms %.3g\n",
           worst[1], worst[2]);
    TEST_ASSERT_TRUE(worst[1] < 1e-9);
    TEST_ASSERT_TRUE(worst[2] < worst[1]);
}

void test_fixed_steps_out_of_range_refused(void) {
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    char msg[STEWART_MESSAGE_SIZE];
    o.fixed_steps = -1;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER, stewart_plant_options_check(&o, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL(strstr(msg, "fixed_steps = -1"));
    o.fixed_steps = 2;
    o.method = STEWART_PLANT_BDF;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER, stewart_plant_options_check(&o, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL(strstr(msg, "needs method 2 or 3"));
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_step_hint_below_any_step_refused);
    RUN_TEST(test_step_that_does_not_advance_time_refused);
    RUN_TEST(test_pitch_through_90_degrees_refused);
    RUN_TEST(test_leg_driven_to_zero_length_is_unreachable);
    RUN_TEST(test_tolerance_no_plant_can_use_refused);
    RUN_TEST(test_random_corrupt_states);
    RUN_TEST(test_step_outputs_equal_a_fresh_evaluation);
    RUN_TEST(test_fixed_steps_do_fixed_work_near_the_adaptive_result);
    RUN_TEST(test_fixed_steps_out_of_range_refused);
    return UNITY_END();
}
