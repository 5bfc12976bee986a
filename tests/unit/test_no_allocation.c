/* No allocation inside a step: malloc and friends are interposed (allocation_counter.c) and
 * counted while the full level (and the slider-crank on the core) step along a manoeuvre. */
#include <stddef.h>
#include <string.h>

#include "slider_crank.h"
#include "stewart/stewart_forward.h"
#include "stewart/stewart_full.h"
#include "allocation_counter.h"
#include "test_support.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

static void test_full_level_steps_do_not_allocate(void) {
    stewart_params params;
    stewart_params_default(&params);
    stewart_model *model = test_model(&params);
    stewart_inverse_options o = test_options(STEWART_FULL);
    stewart_inverse *exact = stewart_inverse_create(model, &o, NULL, 0);
    o.modified_newton = 1;
    stewart_inverse *modified = stewart_inverse_create(model, &o, NULL, 0);
    stewart_inverse *saved = test_inverse(model);
    TEST_ASSERT_NOT_NULL(exact);
    TEST_ASSERT_NOT_NULL(modified);
    stewart_inverse_output out;
    stewart_inverse_input in = {combined_pose(0)};
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_inverse_solve(exact, &in, &out));
    const long before = allocations;
    for (int i = 1; i < 500; ++i) {
        /* exact and modified Newton in turn, along one history */
        stewart_inverse *now = i % 2 ? modified : exact;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_inverse_copy(now, i % 2 ? exact : modified));
        in.pose = combined_pose(0.01 * i);
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_inverse_solve(now, &in, &out));
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_inverse_copy(saved, now)); /* the FMU rollback */
    }
    TEST_ASSERT_EQUAL(before, allocations);
    /* A step that needs Newton iterations (KINSOL) allocates nothing either; creating the data
     * block does (which shows the counter counts). */
    const mbs_model *mech = stewart_model_mechanism(model);
    mbs_data *d = mbs_data_create(mech, MBS_LINEAR_AUTOMATIC);
    TEST_ASSERT_TRUE(allocations > before);
    mbs_options mo;
    mbs_options_default(&mo);
    const long before_newton = allocations;
    for (int k = 0; k < 6; ++k) mbs_set_driver(d, k, 0.58 + 0.004 * k, 0, 0);
    TEST_ASSERT_EQUAL_MESSAGE(MBS_OK, mbs_step(d, 0, &mo), mbs_data_message(d));
    TEST_ASSERT_TRUE(mbs_iterations(d) > 0);
    TEST_ASSERT_EQUAL(before_newton, allocations);
    mbs_data_free(d);
    stewart_inverse_free(saved);
    stewart_inverse_free(modified);
    stewart_inverse_free(exact);
    stewart_model_free(model);
}

static void test_slider_crank_steps_do_not_allocate(void) {
    slider_crank_params p;
    slider_crank_layout l;
    slider_crank_params_default(&p);
    char msg[STEWART_MESSAGE_SIZE];
    mbs_model *m = slider_crank_create(&p, &l, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(m, msg);
    mbs_data *d = mbs_data_create(m, MBS_LINEAR_AUTOMATIC);
    mbs_options o;
    mbs_options_default(&o);
    const long before = allocations;
    for (int i = 0; i < 600; ++i) {
        const double t = 0.02 * i, w = M_PI / 3;
        mbs_set_driver(d, l.crank_driver, w * t, w, 0);
        TEST_ASSERT_EQUAL(MBS_OK, mbs_step(d, t, &o));
    }
    TEST_ASSERT_EQUAL(before, allocations);
    mbs_data_free(d);
    mbs_model_free(m);
}

/* Forward kinematics: tracking (KINSOL iterations, rates and accelerations) and a cold start. */
static void test_forward_solves_do_not_allocate(void) {
    stewart_params params;
    stewart_params_default(&params);
    stewart_model *model = test_model(&params);
    stewart_inverse *data = test_inverse(model);
    stewart_forward *forward = test_forward(model);
    stewart_forward *saved = test_forward(model);
    stewart_inverse_output legs[200];
    for (int i = 0; i < 200; ++i) {
        const stewart_pose p = combined_pose(1e-3 * i);
        legs[i] = solve_ok(data, STEWART_KINEMATIC, &p);
    }
    stewart_forward_output r;
    stewart_forward_input in = {0, legs[0].lengths, 2, 0, {0}};
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_forward_solve(forward, &in, &r));
    unsigned char state[4096];
    TEST_ASSERT_TRUE(stewart_forward_state_size(forward) <= sizeof state);
    const long before = allocations;
    int iterations = 0;
    for (int i = 1; i < 200; ++i) {
        in.time = 1e-3 * i;
        in.lengths = legs[i].lengths;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_forward_solve(forward, &in, &r));
        iterations += r.iterations;
        /* the rollbacks */
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_forward_copy(saved, forward));
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_forward_save(forward, state, sizeof state));
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_forward_load(saved, state, sizeof state));
    }
    stewart_forward_reset(forward);
    in.lengths = legs[100].lengths;
    in.derivatives = 0;
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_forward_solve(forward, &in, &r));
    TEST_ASSERT_TRUE(iterations > 0 && r.iterations > 0); /* KINSOL did iterate */
    TEST_ASSERT_EQUAL(before, allocations);
    stewart_forward_free(saved);
    stewart_forward_free(forward);
    stewart_inverse_free(data);
    stewart_model_free(model);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_full_level_steps_do_not_allocate);
    RUN_TEST(test_slider_crank_steps_do_not_allocate);
    RUN_TEST(test_forward_solves_do_not_allocate);
    return UNITY_END();
}
