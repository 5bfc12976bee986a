/* A long run of the plant at full fidelity: the combined manoeuvre tracked in a closed loop (the
 * inverse side's forces plus PD on the actuator lengths, held over each 1 ms step, as a master
 * with the controller FMU does), and every leg body checked on its joints from the bodies' poses
 * alone (test_plant_support.c: leg_joint_error). The joints are never integrated (the leg bodies
 * follow the platform in closed form), so they must hold to rounding however long the run.
 * Steps: the first argument (ctest passes 1e6, 1e5 under the sanitizers). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "stewart/stewart_plant.h"
#include "test_plant_support.h"
#include "test_support.h"
#include "unity.h"

static long steps = 1000000;

void setUp(void) {}
void tearDown(void) {}

static void test_leg_joints_hold_over_a_long_closed_loop_run(void) {
    stewart_params params;
    stewart_params_default(&params);
    stewart_model *model = test_model(&params);
    stewart_inverse *data = test_inverse(model);
    stewart_plant *plant = test_plant(model, STEWART_FULL, 1e-10, 1e-12);
    const double h = 1e-3, kp = 1e6, kd = 1e4; /* the controller FMU's default gains */
    const stewart_pose start = combined_pose(0);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(plant, 0, start.q, start.q_dot));
    stewart_plant_body bodies[STEWART_PLANT_BODIES];
    double worst_joint = 0, worst_tracking = 0;
    for (long i = 0; i < steps; ++i) {
        const stewart_pose cue = combined_pose(h * (double)i);
        const stewart_inverse_output ff = solve_ok(data, STEWART_FULL, &cue);
        stewart_plant_output now;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, NULL, &now));
        double f[6];
        for (int k = 0; k < 6; ++k)
            f[k] = ff.force[k] + kp * (ff.lengths.length[k] - now.lengths.length[k]) +
                   kd * (ff.lengths.length_rate[k] - now.lengths.length_rate[k]);
        step_ok(plant, h, f, f, NULL, NULL);
        if (i % 1000 != 0 && i != steps - 1) continue; /* sample the checks: the run is long */
        stewart_plant_output out;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, f, &out));
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_bodies(plant, bodies));
        worst_joint = fmax(worst_joint, leg_joint_error(&params, out.pose.q, bodies));
        const stewart_pose next = combined_pose(h * (double)(i + 1));
        for (int c = 0; c < 6; ++c)
            worst_tracking = fmax(worst_tracking, fabs(out.pose.q[c] - next.q[c]));
    }
    printf("%ld closed-loop plant steps of 1 ms: max leg joint error %.3g, max tracking error "
           "%.3g (m, rad)\n",
           steps, worst_joint, worst_tracking);
    TEST_ASSERT_TRUE(worst_joint <= 1e-12);
    TEST_ASSERT_TRUE(worst_tracking <= 1e-3); /* the loop stays closed: the run is meaningful */
    stewart_plant_free(plant);
    stewart_inverse_free(data);
    stewart_model_free(model);
}

int main(int argc, char **argv) {
    if (argc > 1) steps = (long)atof(argv[1]);
    UNITY_BEGIN();
    RUN_TEST(test_leg_joints_hold_over_a_long_closed_loop_run);
    return UNITY_END();
}
