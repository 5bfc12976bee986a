#include "platform_fixture.h"

#include "test_support.h"
#include "unity.h"

stewart_params params;
stewart_model *model;
stewart_data *data;

void setUp(void) {
    stewart_params_default(&params);
    model = test_model(&params);
    data = stewart_data_create(model);
    TEST_ASSERT_NOT_NULL(data);
}

void tearDown(void) {
    stewart_data_free(data);
    stewart_model_free(model);
    data = NULL;
    model = NULL;
}

void rebuild_platform(void) {
    tearDown();
    model = test_model(&params);
    data = stewart_data_create(model);
    TEST_ASSERT_NOT_NULL(data);
}
