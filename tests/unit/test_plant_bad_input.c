/* The plant's edges: refused inputs and motions leave the state at the last good point with a
 * message naming the cause; rollback is exact; plants are independent of each other. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "plant_fixture.h"
#include "stewart/stewart_plant.h"
#include "test_plant_support.h"
#include "test_support.h"
#include "unity.h"

static void saved(const stewart_plant *p, double *state) { plant_save_doubles(p, state); }

static void expect_refused(stewart_status expected, stewart_status got, const char *fragment) {
    TEST_ASSERT_EQUAL_MESSAGE(expected, got, stewart_plant_message(plant));
    if (!strstr(stewart_plant_message(plant), fragment)) {
        char text[STEWART_MESSAGE_SIZE + 64];
        snprintf(text, sizeof text, "message '%s' lacks '%s'", stewart_plant_message(plant),
                 fragment);
        TEST_FAIL_MESSAGE(text);
    }
}

static void expect_state(const double *expected) {
    double now[32];
    saved(plant, now);
    TEST_ASSERT_EQUAL_MEMORY(expected, now, sizeof(double) * plant_state_doubles());
    stewart_plant_output out;
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &out));
    for (int i = 0; i < 6; ++i)
        TEST_ASSERT_TRUE(isfinite(out.pose.q[i]) && isfinite(out.pose.q_dot[i]));
}

static void test_non_finite_inputs_refused(void) {
    TEST_ASSERT_TRUE(plant_state_doubles() <= 32);
    double before[32];
    step_ok(plant, 1e-3, kZero, kZero, NULL, NULL);
    saved(plant, before);
    double bad[6] = {0, 0, NAN, 0, 0, 0};
    expect_refused(STEWART_ERR_ARGUMENT, plant_step_arrays(plant, 1e-3, bad, kZero, NULL, NULL),
                   "F (start of step)[3] = nan");
    bad[2] = 0, bad[5] = INFINITY;
    expect_refused(STEWART_ERR_ARGUMENT, plant_step_arrays(plant, 1e-3, kZero, bad, NULL, NULL),
                   "F (end of step)[6] = inf");
    expect_refused(STEWART_ERR_ARGUMENT, plant_step_arrays(plant, 1e-3, kZero, kZero, bad, kZero),
                   "dF/dt (start of step)[6]");
    expect_refused(STEWART_ERR_ARGUMENT, plant_step_arrays(plant, 0.0, kZero, kZero, NULL, NULL),
                   "h = 0");
    expect_refused(STEWART_ERR_ARGUMENT, plant_step_arrays(plant, NAN, kZero, kZero, NULL, NULL),
                   "h = nan");
    expect_refused(STEWART_ERR_ARGUMENT, plant_step_arrays(plant, 1e-3, kZero, kZero, kZero, NULL),
                   "derivatives is 2");
    /* Finite but absurd: accelerations overflow. */
    const double huge[6] = {1e308, -1e308, 1e308, -1e308, 1e308, -1e308};
    expect_refused(STEWART_ERR_NOT_CONVERGED,
                   plant_step_arrays(plant, 1e-3, huge, huge, NULL, NULL), "out of range");
    expect_state(before);
    step_ok(plant, 1e-3, kZero, kZero, NULL, NULL); /* still usable */
}

static void test_bad_start_state_refused(void) {
    double before[32];
    saved(plant, before);
    double pose[6] = {0, 0, 0.5, 0, 0, 0};
    const double rate[6] = {0};
    pose[3] = NAN;
    expect_refused(STEWART_ERR_ARGUMENT, stewart_plant_set_state(plant, 0, pose, rate),
                   "roll0 = nan");
    pose[3] = 0, pose[4] = M_PI / 2;
    expect_refused(STEWART_ERR_ARGUMENT, stewart_plant_set_state(plant, 0, pose, rate), "pitch0");
    /* Leg 1's platform point on its base point: yaw 30 degrees, z = 0. */
    pose[4] = 0, pose[2] = 0, pose[5] = M_PI / 6;
    expect_refused(STEWART_ERR_UNREACHABLE, stewart_plant_set_state(plant, 0, pose, rate), "leg 1");
    /* Leg 1 along its base Cardan's arm (tangential at 0 degrees): P1 = a1 + 0.3 e_y. */
    const double b1x = 0.5 * cos(-M_PI / 6), b1y = 0.5 * sin(-M_PI / 6);
    const double locked[6] = {0.5 - b1x, 0.3 - b1y, 0, 0, 0, 0};
    expect_refused(STEWART_ERR_SINGULAR, stewart_plant_set_state(plant, 0, locked, rate),
                   "leg 1 lies along a Cardan arm");
    expect_state(before);
}

/* Dropped from 0.4 mm above the pose where legs 1, 3, 5 have zero length, at 1 m/s: refused. */
static void test_motion_through_zero_length_refused(void) {
    const double pose[6] = {0, 0, 0.0004, 0, 0, M_PI / 6};
    const double rate[6] = {0, 0, -1.0, 0, 0, 0};
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(plant, 0, pose, rate));
    double before[32];
    saved(plant, before);
    const stewart_status s = plant_step_arrays(plant, 1e-3, kZero, kZero, NULL, NULL);
    printf("through zero length: %s: %s\n", stewart_status_name(s), stewart_plant_message(plant));
    TEST_ASSERT_NOT_EQUAL(STEWART_OK, s);
    /* Legs 1, 3 and 5 all reach zero length there. */
    TEST_ASSERT_NOT_NULL(strstr(stewart_plant_message(plant), "zero length"));
    expect_state(before);
}

static void test_integrator_failure_refused(void) {
    stewart_plant_free(plant);
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    o.max_internal_steps = 3;
    char msg[STEWART_MESSAGE_SIZE];
    plant = stewart_plant_create(model, &o, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(plant, msg);
    double before[32];
    saved(plant, before);
    const double push[6] = {300, 0, 300, 0, 300, 0};
    expect_refused(STEWART_ERR_NOT_CONVERGED, plant_step_arrays(plant, 0.5, push, push, NULL, NULL),
                   "TOO_MUCH_WORK");
    expect_state(before);
}

static void test_options_checked(void) {
    stewart_plant_options o;
    char msg[STEWART_MESSAGE_SIZE];
    stewart_plant_options_default(&o);
    o.fidelity = STEWART_KINEMATIC;
    TEST_ASSERT_NULL(stewart_plant_create(model, &o, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL(strstr(msg, "fidelity = 0"));
    stewart_plant_options_default(&o);
    o.relative_tolerance = NAN;
    TEST_ASSERT_EQUAL(STEWART_ERR_PARAMETER, stewart_plant_options_check(&o, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL(strstr(msg, "relative_tolerance"));
    stewart_plant_options_default(&o);
    o.absolute_tolerance = 0;
    TEST_ASSERT_EQUAL(STEWART_ERR_PARAMETER, stewart_plant_options_check(&o, msg, sizeof msg));
    TEST_ASSERT_NULL(stewart_plant_create(NULL, &o, msg, sizeof msg));
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT,
                      plant_step_arrays(NULL, 1e-3, kZero, kZero, NULL, NULL));
}

/* Leaving the stroke is a warning naming the leg; the step itself succeeds. */
static void test_stroke_warning_names_leg(void) {
    stewart_plant_output out;
    int warned = 0;
    for (int i = 0; i < 1000 && !warned; ++i) {
        step_ok(plant, 1e-3, kZero, kZero, NULL, NULL); /* falls under gravity */
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &out));
        warned = out.warnings & STEWART_WARN_STROKE;
    }
    TEST_ASSERT_TRUE(warned);
    /* the legs outside are named in the output (bit k: leg k+1), by their lengths; the message
     * is for errors only */
    TEST_ASSERT_NOT_EQUAL(0, out.stroke_legs);
    for (int k = 0; k < 6; ++k)
        TEST_ASSERT_EQUAL(out.lengths.length[k] < params.stroke_min[k] ||
                              out.lengths.length[k] > params.stroke_max[k],
                          (out.stroke_legs >> k) & 1);
    TEST_ASSERT_EQUAL_STRING("", stewart_plant_message(plant));
}

/* A rolled-back step reproduces its outputs bit for bit; two plants side by side agree. */
static void test_rollback_and_independent_plants(void) {
    stewart_plant *other = test_plant(model, STEWART_FULL, 1e-10, 1e-12);
    const double f[6] = {180, 170, 175, 185, 178, 172};
    double state[32];
    stewart_plant_output a, b, c;
    for (int i = 0; i < 50; ++i) {
        step_ok(plant, 1e-3, f, f, NULL, NULL);
        step_ok(other, 1e-3, f, f, NULL, NULL);
    }
    saved(plant, state);
    step_ok(plant, 2e-3, f, kZero, NULL, NULL);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &a));
    TEST_ASSERT_EQUAL(STEWART_OK, plant_load_doubles(plant, state, plant_state_doubles()));
    step_ok(plant, 2e-3, f, kZero, NULL, NULL);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &b));
    TEST_ASSERT_EQUAL_MEMORY(&a, &b, sizeof a);
    step_ok(other, 2e-3, f, kZero, NULL, NULL);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(other, NULL, &c));
    TEST_ASSERT_EQUAL_MEMORY(&a, &c, sizeof a);
    /* Corrupt states are refused and leave the plant as it was. */
    double now[32];
    saved(plant, now);
    state[3] = NAN;
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT,
                      plant_load_doubles(plant, state, plant_state_doubles()));
    saved(plant, state);
    for (int i = 4; i <= 7; ++i) state[i] = 0; /* no quaternion */
    expect_refused(STEWART_ERR_ARGUMENT, plant_load_doubles(plant, state, plant_state_doubles()),
                   "quaternion norm 0");
    /* Unrotated at z = 0 and shifted so that platform point 1 sits on base point 1. */
    saved(plant, state);
    state[1] = 0.5 - 0.5 * cos(-M_PI / 6), state[2] = -0.5 * sin(-M_PI / 6), state[3] = 0;
    state[4] = 1, state[5] = state[6] = state[7] = 0;
    state[14] = state[15] = state[16] = 0;
    expect_refused(STEWART_ERR_ARGUMENT, plant_load_doubles(plant, state, plant_state_doubles()),
                   "singular pose");
    expect_state(now);
    /* Finite forces whose outputs overflow: no output rather than an infinite one. */
    const double huge[6] = {1e308, 1e308, 1e308, 1e308, 1e308, 1e308};
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, stewart_plant_output_get(plant, huge, &a));
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, plant_load_doubles(plant, state, 3));
    stewart_plant_free(other);
}

/* The grammar's rollback: save bytes and a copy, step, load (or copy back), step again: the same
 * outputs bit for bit; without the rollback the step starts elsewhere; a plant of another model
 * is refused by name. */
static void test_save_copy_step_load_step_again(void) {
    const double f[6] = {180, 170, 175, 185, 178, 172};
    for (int i = 0; i < 20; ++i) step_ok(plant, 1e-3, f, f, NULL, NULL);
    unsigned char bytes[1024];
    const size_t size = stewart_plant_state_size(plant);
    TEST_ASSERT_TRUE(size > 0 && size <= sizeof bytes);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_save(plant, bytes, size));
    stewart_plant *kept = test_plant(model, STEWART_FULL, 1e-10, 1e-12);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_copy(kept, plant));
    stewart_plant_input in;
    memset(&in, 0, sizeof in);
    in.h = 2e-3;
    memcpy(in.force_start, f, sizeof f);
    stewart_plant_output first, moved_on, again, from_copy;
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_step(plant, &in, &first));
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_step(plant, &in, &moved_on));
    TEST_ASSERT_TRUE(memcmp(&first, &moved_on, sizeof first) != 0);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_load(plant, bytes, size));
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_step(plant, &in, &again));
    TEST_ASSERT_EQUAL_MEMORY(&first, &again, sizeof first);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_step(kept, &in, &from_copy));
    TEST_ASSERT_EQUAL_MEMORY(&first, &from_copy, sizeof first);
    /* refused: a short buffer, bytes of another version, a plant of another model */
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, stewart_plant_save(plant, bytes, size - 1));
    TEST_ASSERT_NOT_NULL(strstr(stewart_plant_message(plant), "the state needs"));
    bytes[4] ^= 1;
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, stewart_plant_load(plant, bytes, size));
    TEST_ASSERT_NOT_NULL(strstr(stewart_plant_message(plant), "version"));
    stewart_params other_params = params;
    other_params.base_radius = 0.6;
    stewart_model *other = test_model(&other_params);
    stewart_plant *elsewhere = test_plant(other, STEWART_FULL, 1e-10, 1e-12);
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, stewart_plant_copy(elsewhere, plant));
    TEST_ASSERT_NOT_NULL(strstr(stewart_plant_message(elsewhere), "different models"));
    /* reset: at rest at home at time 0, as made */
    stewart_plant_reset(plant);
    stewart_plant_output home;
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &home));
    TEST_ASSERT_EQUAL_DOUBLE(0.0, home.time);
    TEST_ASSERT_EQUAL_DOUBLE(params.home_height, home.pose.q[2]);
    stewart_plant_free(elsewhere);
    stewart_model_free(other);
    stewart_plant_free(kept);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_non_finite_inputs_refused);
    RUN_TEST(test_bad_start_state_refused);
    RUN_TEST(test_motion_through_zero_length_refused);
    RUN_TEST(test_integrator_failure_refused);
    RUN_TEST(test_options_checked);
    RUN_TEST(test_stroke_warning_names_leg);
    RUN_TEST(test_rollback_and_independent_plants);
    RUN_TEST(test_save_copy_step_load_step_again);
    return UNITY_END();
}
