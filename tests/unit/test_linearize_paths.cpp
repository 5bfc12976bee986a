// White-box test of the linearisation's fast path (linearize/plant_jacobian.*: the mass matrix in
// plain numbers, the state derivatives by the 12-direction dual through the residual of the
// equations of motion, the force derivatives analytic) against the path it replaced
// (plant_derivatives.*'s plant_point: the 18-direction dual through the plant's own solve). Two
// formulations of the same derivatives: equal to rounding (1e-12 of each block's largest value),
// block by block, at random operating points of both fidelities. tests/unit/test_linearize.c
// checks both against finite differences through the C API.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "linearize/plant_jacobian.hpp"
#include "model.hpp"
#include "test_support.h"
#include "unity.h"

namespace plant = stewart::plant;
namespace lin = stewart::lin;

namespace {

constexpr double kRelative = 1e-12;

stewart_params params;
stewart_model *model = nullptr;

double uniform(uint64_t &state, double a, double b) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return a + (b - a) * static_cast<double>(state >> 11) / 9007199254740992.0;
}

// Largest |fast - reference| of a block over its largest |reference|.
struct Block {
    double error = 0, scale = 0;
    void add(double fast, double reference) {
        error = std::max(error, std::fabs(fast - reference));
        scale = std::max(scale, std::fabs(reference));
    }
    double relative() const { return error / (scale > 0 ? scale : 1); }
};

void paths_agree(int fidelity) {
    const plant::DynamicsModel d = plant::dynamics_model(*model, fidelity);
    uint64_t rng = 0x9a7b5u + static_cast<uint64_t>(fidelity);
    // q_ddot, A's q and q_dot blocks, B, C's L and L_dot rows.
    Block blocks[6];
    const char *names[6] = {"q_ddot",     "dq_ddot/dq", "dq_ddot/dq_dot",
                            "dq_ddot/dF", "dL/dx",      "dL_dot/dx"};
    for (int n = 0; n < 50; ++n) {
        const double q_half[6] = {0.08, 0.08, 0.05, 0.12, 0.12, 0.2};
        double q[6], q_dot[6], force[STEWART_LEGS];
        for (int i = 0; i < 6; ++i) {
            q[i] = uniform(rng, -q_half[i], q_half[i]);
            q_dot[i] = uniform(rng, -0.5, 0.5);
        }
        q[2] += params.home_height;
        for (double &f : force) f = uniform(rng, 200, 1500);
        lin::PlantJacobian fast;
        lin::PlantPoint reference;
        lin::Failure why;
        TEST_ASSERT_TRUE(lin::plant_jacobian(d, stewart::Frames{}, q, q_dot, force, fast, why));
        TEST_ASSERT_TRUE(lin::plant_point(d, q, q_dot, force, reference, why));
        for (int i = 0; i < 6; ++i) {
            const stewart::Dual &r = reference.q_ddot[i];
            blocks[0].add(fast.q_ddot[i], r.value());
            for (int j = 0; j < 12; ++j)
                blocks[j < 6 ? 1 : 2].add(fast.q_ddot_wrt_state[i][j], r.derivatives()[j]);
            for (int k = 0; k < STEWART_LEGS; ++k)
                blocks[3].add(fast.q_ddot_wrt_force[i][k], r.derivatives()[12 + k]);
        }
        for (int k = 0; k < STEWART_LEGS; ++k) {
            TEST_ASSERT_EQUAL_DOUBLE(reference.length[k].value(), fast.length[k]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-15, reference.length_rate[k].value(), fast.length_rate[k]);
            for (int j = 0; j < 12; ++j) {
                blocks[4].add(fast.length_wrt_state[k][j], reference.length[k].derivatives()[j]);
                blocks[5].add(fast.length_rate_wrt_state[k][j],
                              reference.length_rate[k].derivatives()[j]);
            }
            // The outputs do not depend on the forces: the reference's D is zero.
            for (int j = 12; j < 18; ++j) {
                TEST_ASSERT_EQUAL_DOUBLE(0.0, reference.length[k].derivatives()[j]);
                TEST_ASSERT_EQUAL_DOUBLE(0.0, reference.length_rate[k].derivatives()[j]);
            }
        }
    }
    for (int b = 0; b < 6; ++b) {
        std::printf("fidelity %d: %-15s fast against reference %.1e relative\n", fidelity, names[b],
                    blocks[b].relative());
        TEST_ASSERT_LESS_THAN_DOUBLE_MESSAGE(kRelative, blocks[b].relative(), names[b]);
    }
}

void test_massless_paths_agree() { paths_agree(STEWART_MASSLESS); }
void test_full_paths_agree() { paths_agree(STEWART_FULL); }

}  // namespace

void setUp(void) {
    stewart_params_default(&params);
    model = test_model(&params);
}

void tearDown(void) {
    stewart_model_free(model);
    model = nullptr;
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_massless_paths_agree);
    RUN_TEST(test_full_paths_agree);
    return UNITY_END();
}
