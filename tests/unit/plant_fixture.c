#include "plant_fixture.h"

#include "test_plant_support.h"
#include "test_support.h"
#include "unity.h"

stewart_params params;
stewart_model *model;
stewart_plant *plant;
const double kZero[6] = {0};

void setUp(void) {
    stewart_params_default(&params);
    model = test_model(&params);
    plant = test_plant(model, STEWART_FULL, 1e-10, 1e-12);
}

void tearDown(void) {
    stewart_plant_free(plant);
    stewart_model_free(model);
}
