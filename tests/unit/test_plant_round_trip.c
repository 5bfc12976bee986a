/* Round trip: the actuator forces the inverse side computes along the combined cue (the formula
 * of scenes/combined.json), fed to the plant with their first time derivatives at 0.1 ms steps,
 * must reproduce the cue's pose. Both fidelities, each against its own inverse level. */
#include <math.h>
#include <stdio.h>

#include "platform_fixture.h"
#include "stewart/stewart_plant.h"
#include "test_plant_support.h"
#include "test_support.h"
#include "unity.h"

/* Forces at t and their time derivative by a central difference of the inverse solve. */
static void inverse_forces(int fidelity, double t, double force[6], double rate[6]) {
    const double delta = 1e-4;
    stewart_pose pose = combined_pose(t);
    const stewart_inverse_output now = solve_ok(data, fidelity, &pose);
    pose = combined_pose(t + delta);
    const stewart_inverse_output ahead = solve_ok(data, fidelity, &pose);
    pose = combined_pose(t - delta);
    const stewart_inverse_output behind = solve_ok(data, fidelity, &pose);
    for (int k = 0; k < 6; ++k) {
        force[k] = now.force[k];
        rate[k] = (ahead.force[k] - behind.force[k]) / (2 * delta);
    }
}

static void round_trip(int fidelity, double seconds, double bound) {
    stewart_plant *plant = test_plant(model, fidelity, 1e-13, 1e-15);
    const stewart_pose start = combined_pose(0);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(plant, 0, start.q, start.q_dot));
    const double h = 1e-4;
    const int steps = (int)(seconds / h + 0.5);
    double f0[6], r0[6], f1[6], r1[6], worst = 0, worst_rate = 0, worst_t = 0;
    double worst_wrench = 0, worst_length = 0;
    inverse_forces(fidelity, 0, f0, r0);
    for (int i = 1; i <= steps; ++i) {
        const double t = i * h;
        inverse_forces(fidelity, t, f1, r1);
        step_ok(plant, h, f0, f1, r0, r1);
        stewart_plant_output out;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_output_get(plant, f1, &out));
        const stewart_pose cue = combined_pose(t);
        /* The base wrench, lengths and rates against the inverse side's at the cue. */
        if (i % 100 == 0) {
            stewart_pose pose = cue;
            const stewart_inverse_output inverse = solve_ok(data, fidelity, &pose);
            for (int a = 0; a < 3; ++a) {
                const double df = fabs(out.base_force[a] - inverse.base_force[a]);
                const double dt = fabs(out.base_torque[a] - inverse.base_torque[a]);
                if (df > worst_wrench) worst_wrench = df;
                if (dt > worst_wrench) worst_wrench = dt;
            }
            for (int k = 0; k < 6; ++k) {
                if (fabs(out.lengths.length[k] - closed_form_length(&params, &pose, k)) >
                    worst_length)
                    worst_length =
                        fabs(out.lengths.length[k] - closed_form_length(&params, &pose, k));
                if (fabs(out.lengths.length_rate[k] - inverse.lengths.length_rate[k]) >
                    worst_length)
                    worst_length =
                        fabs(out.lengths.length_rate[k] - inverse.lengths.length_rate[k]);
            }
        }
        for (int c = 0; c < 6; ++c) {
            const double e = fabs(out.pose.q[c] - cue.q[c]);
            if (e > worst) worst = e, worst_t = t;
            if (fabs(out.pose.q_dot[c] - cue.q_dot[c]) > worst_rate)
                worst_rate = fabs(out.pose.q_dot[c] - cue.q_dot[c]);
        }
        for (int k = 0; k < 6; ++k) f0[k] = f1[k], r0[k] = r1[k];
    }
    stewart_plant_statistics st;
    stewart_plant_statistics_get(plant, &st);
    printf("round trip, fidelity %d: max pose error %.3g (at t = %.4g s), max rate error %.3g, "
           "base wrench against the inverse side's %.3g N or N m, lengths and rates %.3g, "
           "over %g s (%ld internal steps, %ld rhs)\n",
           fidelity, worst, worst_t, worst_rate, worst_wrench, worst_length, seconds,
           st.total_steps, st.total_rhs_evaluations);
    TEST_ASSERT_TRUE(worst <= bound);
    TEST_ASSERT_TRUE(worst_rate <= 10 * bound);
    TEST_ASSERT_TRUE(worst_length <= 10 * bound);
    /* The full inverse side takes its base wrench from the 14-body model's joint reactions. */
    TEST_ASSERT_TRUE(worst_wrench <= 1e-6);
    stewart_plant_free(plant);
}

static void test_round_trip_full(void) { round_trip(STEWART_FULL, 2.0, 1e-6); }
static void test_round_trip_massless(void) { round_trip(STEWART_MASSLESS, 2.0, 1e-6); }

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_round_trip_full);
    RUN_TEST(test_round_trip_massless);
    return UNITY_END();
}
