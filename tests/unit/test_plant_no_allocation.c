/* No allocation inside a plant step, for every integrator: malloc and friends are interposed
 * (allocation_counter.c) and counted while the plant steps, saves and loads its state along a
 * forced motion. */
#include <stddef.h>

#include "stewart/stewart_plant.h"
#include "test_plant_support.h"
#include "allocation_counter.h"
#include "test_support.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

static void steps_do_not_allocate(int fidelity, int method) {
    stewart_params params;
    stewart_params_default(&params);
    stewart_model *model = test_model(&params);
    stewart_plant_options o = test_plant_options(fidelity);
    o.method = method;
    stewart_plant *plant = test_plant_with(model, &o);
    double state[32], f0[6], f1[6];
    for (int k = 0; k < 6; ++k) f0[k] = 175.0;
    stewart_plant_output out;
    stewart_plant_body bodies[STEWART_PLANT_BODIES];
    stewart_plant_reactions reactions;
    const long before = allocations;
    for (int i = 1; i <= 200; ++i) {
        for (int k = 0; k < 6; ++k) f1[k] = 175.0 + 2.0 * k * (i % 7);
        step_ok(plant, 1e-3, f0, f1, NULL, NULL);
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &out));
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_bodies(plant, bodies));
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_reactions_get(plant, NULL, &reactions));
        plant_save_doubles(plant, state);
        if (i % 10 == 0)
            TEST_ASSERT_EQUAL(STEWART_OK, plant_load_doubles(plant, state, plant_state_doubles()));
        for (int k = 0; k < 6; ++k) f0[k] = f1[k];
    }
    /* A refused step too. */
    const double bad[6] = {0, 0, 0, 0, 0, 1.0 / 0.0};
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, plant_step_arrays(plant, 1e-3, f0, bad, NULL, NULL));
    TEST_ASSERT_EQUAL(0, allocations - before);
    stewart_plant_free(plant);
    stewart_model_free(model);
}

static void test_erk_steps_do_not_allocate(void) {
    steps_do_not_allocate(STEWART_FULL, STEWART_PLANT_ERK);
    steps_do_not_allocate(STEWART_MASSLESS, STEWART_PLANT_ERK);
    steps_do_not_allocate(STEWART_FULL, STEWART_PLANT_ERK5);
}

static void test_adams_steps_do_not_allocate(void) {
    steps_do_not_allocate(STEWART_FULL, STEWART_PLANT_ADAMS);
}

static void test_bdf_steps_do_not_allocate(void) {
    steps_do_not_allocate(STEWART_FULL, STEWART_PLANT_BDF);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_erk_steps_do_not_allocate);
    RUN_TEST(test_adams_steps_do_not_allocate);
    RUN_TEST(test_bdf_steps_do_not_allocate);
    return UNITY_END();
}
