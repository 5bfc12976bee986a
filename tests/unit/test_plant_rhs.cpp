// White-box test of the massless plant's written-out right-hand side (fd::massless_twist_rate,
// csrc/plant/plant_massless.cpp) against the generic equations it copies (fd::twist_rate on the
// same massless model: plant_equations_impl.hpp's assemble and one-body solve): bit for bit, on
// random states far from home (any rotation, fast motion), random forces, with and without a
// payload off the platform's centre (a centre of mass off the origin and a full inertia), and
// the same fault for a leg of zero length; and the state's rotation (fd::motion_of_state, written
// out) against Eigen's quaternion.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "plant/plant_integrator.hpp"
#include "stewart/stewart.h"
#include "unity.h"

namespace fd = stewart::fd;

namespace {

double uniform(uint64_t &state, double a, double b) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return a + (b - a) * static_cast<double>(state >> 11) / 9007199254740992.0;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Both evaluations of one state, compared bit for bit; the number of differing values.
int differences(const fd::DynamicsModel &d, const double y[fd::kStates], const double force[6]) {
    const stewart::Motion m = fd::motion_of_state(y);
    fd::Evaluation generic, written;
    const bool a = fd::twist_rate(d, m, force, generic);
    const bool b = fd::massless_twist_rate(d, m, force, written);
    if (a != b) return 1;
    if (!a) return generic.fault == written.fault && generic.fault_leg == written.fault_leg ? 0 : 1;
    int count = 0;
    for (int i = 0; i < 6; ++i) count += !same_bits(generic.twist_rate[i], written.twist_rate[i]);
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const fd::LegConfiguration &g = generic.legs[k], &w = written.legs[k];
        for (int i = 0; i < 3; ++i)
            count += !same_bits(g.arm[i], w.arm[i]) + !same_bits(g.n[i], w.n[i]);
        count += !same_bits(g.length, w.length) + !same_bits(g.inverse_length, w.inverse_length);
    }
    return count;
}

void check_model(const stewart_params &params) {
    char message[STEWART_MESSAGE_SIZE];
    stewart_model *model = stewart_model_create(&params, message, sizeof message);
    TEST_ASSERT_NOT_NULL_MESSAGE(model, message);
    const fd::DynamicsModel d = fd::dynamics_model(*model, STEWART_MASSLESS);
    uint64_t rng = 12345;
    int differing = 0;
    for (int n = 0; n < 20000; ++n) {
        double y[fd::kStates], force[STEWART_LEGS];
        y[0] = uniform(rng, -0.2, 0.2);
        y[1] = uniform(rng, -0.2, 0.2);
        y[2] = params.home_height + uniform(rng, -0.2, 0.2);
        // an unnormalised quaternion of any rotation (motion_of_state normalises it)
        for (int i = 3; i < 7; ++i) y[i] = uniform(rng, -1.5, 1.5);
        for (int i = 7; i < 13; ++i) y[i] = uniform(rng, -20, 20);
        for (double &f : force) f = uniform(rng, -5e4, 5e4);
        differing += differences(d, y, force);
    }
    // A leg of zero length: the platform point of leg 1 on its base point.
    double y[fd::kStates] = {0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    const fd::Vec3 gap = d.legs.base_points.col(0) - d.legs.platform_points.col(0);
    for (int i = 0; i < 3; ++i) y[i] = gap[i];
    const double zero[STEWART_LEGS] = {0};
    differing += differences(d, y, zero);
    stewart::Motion m = fd::motion_of_state(y);
    fd::Evaluation e;
    TEST_ASSERT_FALSE(fd::massless_twist_rate(d, m, zero, e));
    TEST_ASSERT_EQUAL_INT(0, e.fault_leg);
    stewart_model_free(model);
    TEST_ASSERT_EQUAL_INT(0, differing);
}

// fd::motion_of_state's rotation, written out, against Eigen's quaternion (which it copies), bit
// for bit, on unnormalised quaternions of any rotation and scale.
void test_rotation_of_state(void) {
    uint64_t rng = 777;
    int differing = 0;
    for (int n = 0; n < 100000; ++n) {
        double y[fd::kStates] = {0};
        const double scale = std::pow(10.0, uniform(rng, -3, 3));
        for (int i = 3; i < 7; ++i) y[i] = scale * uniform(rng, -1, 1);
        Eigen::Quaterniond q(y[3], y[4], y[5], y[6]);
        q.normalize();
        const fd::Mat3 expected = q.toRotationMatrix(), R = fd::motion_of_state(y).rotation;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) differing += !same_bits(expected(i, j), R(i, j));
    }
    TEST_ASSERT_EQUAL_INT(0, differing);
}

void test_default_platform(void) {
    stewart_params params;
    stewart_params_default(&params);
    check_model(params);
}

void test_payload_off_centre(void) {
    stewart_params params;
    stewart_params_default(&params);
    params.payload_mass = 37.5;
    const double com[3] = {0.07, -0.04, 0.12}, inertia[3] = {1.3, 0.9, 2.1};
    for (int i = 0; i < 3; ++i) params.payload_com[i] = com[i], params.payload_inertia[i] = inertia[i];
    check_model(params);
}

}  // namespace

void setUp(void) {}
void tearDown(void) {}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_rotation_of_state);
    RUN_TEST(test_default_platform);
    RUN_TEST(test_payload_off_centre);
    return UNITY_END();
}
