#include "platform_fixture.h"

#include "test_support.h"
#include "unity.h"

stewart_params params;
stewart_model *model;
stewart_inverse *data;
stewart_forward *forward_solver;

void setUp(void) {
    stewart_params_default(&params);
    model = test_model(&params);
    data = test_inverse(model);
    TEST_ASSERT_NOT_NULL(data);
    stewart_forward_options fo;
    stewart_forward_options_default(&fo);
    char msg[STEWART_MESSAGE_SIZE];
    forward_solver = stewart_forward_create(model, &fo, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(forward_solver, msg);
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
    model = test_model(&params);
    data = test_inverse(model);
    TEST_ASSERT_NOT_NULL(data);
    stewart_forward_options fo;
    stewart_forward_options_default(&fo);
    char msg[STEWART_MESSAGE_SIZE];
    /* NULL for a platform singular at home (it has no forward kinematics) */
    forward_solver = stewart_forward_create(model, &fo, msg, sizeof msg);
}
