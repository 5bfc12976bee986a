// The plant's joint-limit and interference warnings with the clearance it keeps from step to step
// (limit_check.cpp: platform_limit_failures with a LimitClearance; plant_api.cpp's step) against
// stewart_plant_output_get at the same state, which runs the exact check every time: both
// fidelities, 1 ms steps, narrow joint limits and wide legs, along a path that sets the state to
// poses turning in and out of the limits every few steps and steps under forces between them.
// Every step's warnings must equal output_get's; the path must cross the limits (steps with and
// without each warning) and the clearance must spare the check on some steps (else this tests
// nothing of it). Seen to fail (10 steps differing) with the clearance's allowance divided by 30,
// not by 10: this path's moves stay well inside the bound (test_limit_failures.cpp's
// test_clearance_edge probes the bound itself).
#include <cmath>
#include <cstdio>

#include "plant/plant_object.hpp"
#include "stewart/stewart.h"
#include "test_support.h"
#include "unity.h"

namespace {

constexpr int kLimitWarnings = STEWART_WARN_JOINT_LIMIT | STEWART_WARN_INTERFERENCE;

// The path's pose at time t [s] and its rates: a drift of the position, tilts and a turn whose
// amplitudes take the legs past the joint limits and toward each other.
void path_pose(double t, double home_height, double pose[6], double rate[6]) {
    const double amplitude[6] = {0.03, 0.03, 0.04, 0.15, 0.15, 0.35},
                 frequency[6] = {0.7, 1.1, 0.9, 1.3, 1.7, 0.8};  // [rad/s]
    for (int i = 0; i < 6; ++i) {
        pose[i] = amplitude[i] * std::sin(frequency[i] * t + i);
        rate[i] = amplitude[i] * frequency[i] * std::cos(frequency[i] * t + i);
    }
    pose[2] += home_height;
}

struct Counts {
    int steps = 0, differing = 0, joint = 0, interference = 0, clear = 0, spared = 0, changes = 0;
};

void run_path(int fidelity, Counts &counts) {
    stewart_params params;
    stewart_params_default(&params);
    // legs 1 and 2 (3 and 4, 5 and 6) cross at home: their distance comes and goes with the yaw
    const double crossing[STEWART_LEGS] = {25, 5, 145, 125, 265, 245};  // [deg]
    for (int k = 0; k < STEWART_LEGS; ++k) params.platform_angle[k] = crossing[k] * M_PI / 180;
    params.base_joint_limit = 0.4;
    params.platform_joint_limit = 0.45;
    params.leg_diameter = 0.01;
    stewart_model *model = test_model(&params);
    const stewart_plant_options o = test_plant_options(fidelity);
    stewart_plant *plant = test_plant_with(model, &o);
    int last = 0;  // the last step's exact limit warnings
    for (int n = 0; n < 5000; ++n) {
        if (n % 5 == 0) {  // the path speeds up: 0.5 .. 20 path seconds per second
            const double t = 1e-3 * n, speed = 0.5 + 19.5 * (n % 1000) / 1000.0;
            double pose[6], rate[6];
            path_pose(t * speed, params.home_height, pose, rate);
            for (double &r : rate) r *= speed;
            TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_plant_set_state(plant, t, pose, rate),
                                          stewart_plant_message(plant));
        }
        stewart_plant_input in{};
        in.h = 1e-3;
        for (int k = 0; k < STEWART_LEGS; ++k) {
            in.force_start[k] = 1500 + 300 * std::sin(0.05 * n + k);
            in.force_end[k] = 1500 + 300 * std::sin(0.05 * (n + 1) + k);
        }
        const Eigen::Vector3d kept_at = plant->limit_clearance.position;
        const bool kept = plant->limit_clearance.valid;
        stewart_plant_output stepped, exact;
        TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_plant_step(plant, &in, &stepped),
                                      stewart_plant_message(plant));
        TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_plant_output_get(plant, nullptr, &exact));
        ++counts.steps;
        counts.differing +=
            (stepped.warnings & kLimitWarnings) != (exact.warnings & kLimitWarnings);
        counts.joint += (exact.warnings & STEWART_WARN_JOINT_LIMIT) != 0;
        counts.interference += (exact.warnings & STEWART_WARN_INTERFERENCE) != 0;
        counts.clear += (exact.warnings & kLimitWarnings) == 0;
        counts.changes += (exact.warnings & kLimitWarnings) != last;
        last = exact.warnings & kLimitWarnings;
        counts.spared +=
            kept && plant->limit_clearance.valid && plant->limit_clearance.position == kept_at;
    }
    stewart_plant_free(plant);
    stewart_model_free(model);
}

void test_warnings_along_path(void) {
    for (int fidelity : {STEWART_MASSLESS, STEWART_FULL}) {
        Counts c;
        run_path(fidelity, c);
        std::printf("%s: %d steps, %d with a joint-limit warning, %d with interference, %d with "
                    "neither, %d changes of verdict, %d spared the check, %d differing from "
                    "output_get\n",
                    fidelity == STEWART_MASSLESS ? "massless" : "full", c.steps, c.joint,
                    c.interference, c.clear, c.changes, c.spared, c.differing);
        TEST_ASSERT_EQUAL_INT(0, c.differing);
        TEST_ASSERT_TRUE(c.joint > c.steps / 20);         // the path crosses the joint limits
        TEST_ASSERT_TRUE(c.interference > c.steps / 20);  // and the legs' interference
        TEST_ASSERT_TRUE(c.clear > c.steps / 10);         // and comes back inside them
        TEST_ASSERT_TRUE(c.changes > 20);                 // many times
        TEST_ASSERT_TRUE(c.spared > c.steps / 10);        // where the clearance spares checks
    }
}

}  // namespace

void setUp(void) {}
void tearDown(void) {}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_warnings_along_path);
    return UNITY_END();
}
