/* Long runs of the full level along the combined manoeuvre at 1 ms. First as stewart_inverse_solve runs
 * it: the Euler parameters of every body stay normalised and the leg lengths stay the closed
 * form |p + R b - a| (computed here from the pose). That level places every body afresh from the
 * pose at each step, so this checks that nothing else accumulates. Then driven by the actuator
 * lengths, with Newton from the predictor and nothing placed in closed form: there drift could
 * build up, and must not. Steps: the first argument (ctest passes 1e6, 1e5 under the
 * sanitizers; 1e7 is the run, about 260 s for both). */
#include <math.h>
#include <stdlib.h>

#include "platform_fixture.h"
#include "stewart/stewart_full.h"
#include "test_support.h"
#include "unity.h"

static long steps = 1000000;

static void test_no_drift_over_a_long_run(void) {
    double worst_norm = 0, worst_length = 0, worst_late_norm = 0;
    for (long i = 0; i < steps; ++i) {
        stewart_pose pose = combined_pose(1e-3 * (double)i);
        stewart_inverse_output out = solve_ok(data, STEWART_FULL, &pose);
        if (i % 1000 != 0 && i != steps - 1) continue; /* sample the checks: the run is long */
        const double *q = mbs_q(stewart_inverse_mechanism(data));
        for (int b = 0; b < 14; ++b) {
            const double *e = q + MBS_BODY_P(b);
            const double err = fabs(e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + e[3] * e[3] - 1);
            worst_norm = fmax(worst_norm, err);
            if (i >= steps / 2) worst_late_norm = fmax(worst_late_norm, err);
        }
        for (int k = 0; k < 6; ++k)
            worst_length = fmax(worst_length, fabs(out.lengths.length[k] -
                                                   closed_form_length(&params, &pose, k)));
    }
    printf(
        "%ld steps: max | |p|^2 - 1 | = %.3g (second half %.3g), max |L - closed form| = %.3g m\n",
        steps, worst_norm, worst_late_norm, worst_length);
    TEST_ASSERT_TRUE(worst_norm <= 1e-12);
    TEST_ASSERT_TRUE(worst_length <= 1e-11);
}

/* The same manoeuvre driven the other way, as forward kinematics: the six actuator lengths, with
 * their rates and accelerations from the kinematic level, drive the platform's mechanism, and
 * Newton finds every body from the predictor q + h q_dot + h^2/2 q_ddot of the step before. No
 * closed-form placement resets anything here, so drift would accumulate if the integration of
 * the positions let it: every body's Euler parameters must stay normalised, and every body must
 * stay where the full level's closed-form placement of the same pose puts it. */
static void test_forward_kinematics_by_newton_over_a_long_run(void) {
    mbs_data *mech = mbs_data_create(stewart_model_mechanism(model), MBS_LINEAR_AUTOMATIC);
    TEST_ASSERT_NOT_NULL(mech);
    mbs_options o;
    mbs_options_default(&o); /* predictor on, tolerance 1e-12 */
    double worst_norm = 0, worst_position = 0, worst_rotation = 0;
    int worst_iterations = 0;
    for (long i = 0; i < steps; ++i) {
        const double t = 1e-3 * (double)i;
        const stewart_pose pose = combined_pose(t);
        const stewart_inverse_output legs = solve_ok(data, STEWART_KINEMATIC, &pose);
        for (int k = 0; k < 6; ++k)
            mbs_set_driver(mech, k, legs.lengths.length[k], legs.lengths.length_rate[k],
                           legs.lengths.length_accel[k]);
        TEST_ASSERT_EQUAL_INT_MESSAGE(MBS_OK, mbs_step(mech, t, &o), mbs_data_message(mech));
        if (i > 0 && mbs_iterations(mech) > worst_iterations)
            worst_iterations = mbs_iterations(mech);
        if (i % 1000 != 0 && i != steps - 1) continue;
        solve_ok(data, STEWART_FULL, &pose);
        const double *q = mbs_q(mech), *ref = mbs_q(stewart_inverse_mechanism(data));
        for (int b = 1; b < 14; ++b) {
            const double *r = q + MBS_BODY_R(b), *r_ref = ref + MBS_BODY_R(b);
            const double *e = q + MBS_BODY_P(b), *e_ref = ref + MBS_BODY_P(b);
            for (int c = 0; c < 3; ++c)
                worst_position = fmax(worst_position, fabs(r[c] - r_ref[c]));
            const double dot =
                e[0] * e_ref[0] + e[1] * e_ref[1] + e[2] * e_ref[2] + e[3] * e_ref[3];
            const double sign = dot < 0 ? -1.0 : 1.0; /* p and -p: the same rotation */
            for (int c = 0; c < 4; ++c)
                worst_rotation = fmax(worst_rotation, fabs(e[c] - sign * e_ref[c]));
            worst_norm =
                fmax(worst_norm, fabs(e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + e[3] * e[3] - 1));
        }
    }
    printf("%ld steps by forward kinematics: max | |p|^2 - 1 | = %.3g, max body position error "
           "%.3g m, max |p -+ p_ref| = %.3g, Newton iterations per step <= %d\n",
           steps, worst_norm, worst_position, worst_rotation, worst_iterations);
    mbs_data_free(mech);
    TEST_ASSERT_TRUE(worst_norm <= 1e-12);
    TEST_ASSERT_TRUE(worst_position <= 1e-11);
    TEST_ASSERT_TRUE(worst_rotation <= 1e-12);
    TEST_ASSERT_TRUE(worst_iterations >= 1 && worst_iterations <= 2); /* Newton did the work */
}

int main(int argc, char **argv) {
    if (argc > 1) steps = (long)atof(argv[1]);
    UNITY_BEGIN();
    RUN_TEST(test_no_drift_over_a_long_run);
    RUN_TEST(test_forward_kinematics_by_newton_over_a_long_run);
    return UNITY_END();
}
