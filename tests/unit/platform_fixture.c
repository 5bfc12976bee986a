#include "platform_fixture.h"

#include "test_support.h"
#include "unity.h"

stewart_params params;
stewart_model *model;
stewart_inverse *data;
stewart_forward *forward_solver;

/* The model of `params`, its inverse solver and its forward solver (NULL for a platform singular
 * at home: it has no forward kinematics). */
static char forward_message[STEWART_MESSAGE_SIZE];
static void make_platform(void) {
    model = test_model(&params);
    data = test_inverse(model);
    TEST_ASSERT_NOT_NULL(data);
    stewart_forward_options fo;
    stewart_forward_options_default(&fo);
    forward_solver = stewart_forward_create(model, &fo, forward_message, sizeof forward_message);
}

void setUp(void) {
    stewart_params_default(&params);
    make_platform();
    TEST_ASSERT_NOT_NULL_MESSAGE(forward_solver, forward_message);
}

void tearDown(void) {
    stewart_forward_free(forward_solver);
    forward_solver = NULL;
    stewart_inverse_free(data);
    stewart_model_free(model);
    data = NULL;
    model = NULL;
}

void rebuild_platform(void) {
    tearDown();
    make_platform();
}
