/* A long run of the full level along the combined manoeuvre at 1 ms: the Euler parameters of
 * every body stay normalised and the leg lengths stay the closed form |p + R b - a| (computed
 * here from the pose), with no drift as the steps add up. Steps: the first argument (ctest
 * passes 1e6, 1e5 under the sanitizers; 1e7 is the run, about 100 s). */
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
        stewart_output out = solve_ok(model, data, STEWART_FULL, &pose);
        if (i % 1000 != 0 && i != steps - 1) continue; /* sample the checks: the run is long */
        const double *q = mbs_q(stewart_data_mechanism(data));
        for (int b = 0; b < 14; ++b) {
            const double *e = q + 7 * b + 3;
            const double err = fabs(e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + e[3] * e[3] - 1);
            worst_norm = fmax(worst_norm, err);
            if (i >= steps / 2) worst_late_norm = fmax(worst_late_norm, err);
        }
        for (int k = 0; k < 6; ++k)
            worst_length = fmax(worst_length, fabs(out.length[k] - closed_form_length(&params, &pose, k)));
    }
    printf("%ld steps: max | |p|^2 - 1 | = %.3g (second half %.3g), max |L - closed form| = %.3g m\n",
           steps, worst_norm, worst_late_norm, worst_length);
    TEST_ASSERT_TRUE(worst_norm <= 1e-12);
    TEST_ASSERT_TRUE(worst_length <= 1e-11);
}

int main(int argc, char **argv) {
    if (argc > 1) steps = (long)atof(argv[1]);
    UNITY_BEGIN();
    RUN_TEST(test_no_drift_over_a_long_run);
    return UNITY_END();
}
