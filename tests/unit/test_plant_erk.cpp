// White-box test of the plant's written-out ERK 4(3) (csrc/plant/plant_erk.*: ARKODE's ERKStep
// copied step for step) against ARKODE itself: two integrators on the same equations, one with
// the written-out steps and one with ARKODE alone (Integrator::init's written_out = false), run
// side by side over runs of 1 ms communication steps from random states under forces that swing
// and jump (so that the adaptive runs take two-step calls and reject steps), at both fidelities,
// adaptive and with 1, 2 and 3 fixed steps. After every step the two must agree bit for bit: the
// state, the next first step, the counters (steps, right-hand sides, rejected steps, last step
// size) and the end-of-step evaluation the outputs reuse. The plant's own mode (Integrator::init's
// carry_end: the quaternion normalised before the end evaluation, which the next step's start
// takes over) is held against ARKODE the same way: the same state, next first step and counters
// bit for bit, the start's right-hand side carried on every call that starts where the last one
// ended (and only there: not after other start forces or a state moved), and an end evaluation
// equal to a fresh one at the state returned.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "plant/plant_integrator.hpp"
#include "stewart/stewart.h"
#include "test_support.h"
#include "unity.h"

namespace plant = stewart::plant;

namespace {

stewart_params params;
stewart_model *model = nullptr;
double static_force[STEWART_LEGS];

double uniform(uint64_t &state, double a, double b) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return a + (b - a) * static_cast<double>(state >> 11) / 9007199254740992.0;
}

// A state near home: position within 3 cm, a rotation of up to 0.1 rad about a random axis,
// velocity up to 0.02 m/s, angular velocity up to 0.05 rad/s.
void random_state(uint64_t &rng, double y[plant::kStates]) {
    y[0] = uniform(rng, -0.03, 0.03);
    y[1] = uniform(rng, -0.03, 0.03);
    y[2] = params.home_height + uniform(rng, -0.03, 0.03);
    double axis[3], norm = 0;
    for (double &a : axis) norm += (a = uniform(rng, -1, 1)) * a;
    norm = std::sqrt(norm);
    const double half = 0.5 * uniform(rng, 0, 0.1);
    y[3] = std::cos(half);
    for (int i = 0; i < 3; ++i) y[4 + i] = std::sin(half) * axis[i] / norm;
    for (int i = 0; i < 3; ++i) y[7 + i] = uniform(rng, -0.02, 0.02);
    for (int i = 0; i < 3; ++i) y[10 + i] = uniform(rng, -0.05, 0.05);
}

// Forces at step n of a run: static ones plus a swing of 40 N, a jump of up to 400 N every 40
// steps (the steps the adaptive control splits or rejects), linear or Hermite by the step's
// parity.
void forces_at(int n, double phase, plant::ForceProfile &p) {
    auto force = [&](int step, int k) {
        const double jump = (step / 40) % 2 ? 400.0 * std::sin(phase + k) : 0.0;
        return static_force[k] + 40.0 * std::sin(0.05 * step + phase + k) + jump;
    };
    p.h = 1e-3;
    p.hermite = n % 2 == 1;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        p.start[k] = force(n, k);
        p.end[k] = force(n + 1, k);
        p.start_rate[k] = 40.0 * 50.0 * std::cos(0.05 * n + phase + k);
        p.end_rate[k] = 40.0 * 50.0 * std::cos(0.05 * (n + 1) + phase + k);
    }
}

void same_bits(const char *what, const void *a, const void *b, size_t size, int run, int n) {
    if (std::memcmp(a, b, size) == 0) return;
    char message[160];
    std::snprintf(message, sizeof message, "%s differs at run %d, step %d", what, run, n);
    TEST_FAIL_MESSAGE(message);
}

// carry_end: the written-out integrator in the plant's mode (see the header).
void written_out_equals_arkode(int fidelity, int fixed_steps, bool carry_end) {
    const plant::DynamicsModel d = plant::dynamics_model(*model, fidelity);
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    o.fidelity = fidelity;
    o.fixed_steps = fixed_steps;
    char message[STEWART_MESSAGE_SIZE];
    plant::Integrator written_out, arkode;
    TEST_ASSERT_TRUE_MESSAGE(written_out.init(&d, o, message, sizeof message, true, carry_end),
                             message);
    TEST_ASSERT_TRUE_MESSAGE(arkode.init(&d, o, message, sizeof message, false), message);
    uint64_t rng = 0x22b + 10 * static_cast<uint64_t>(fidelity) + fixed_steps;
    long calls = 0, multi_step_calls = 0, rejections = 0, carried = 0;
    for (int run = 0; run < 4; ++run) {
        double y_a[plant::kStates], y_b[plant::kStates];
        random_state(rng, y_a);
        std::memcpy(y_b, y_a, sizeof y_a);
        double hint_a = 0, hint_b = 0;
        const double phase = uniform(rng, 0, 6.283);
        for (int n = 0; n < 250; ++n, ++calls) {
            plant::ForceProfile p;
            forces_at(n, phase, p);
            // now and then a start that is not the last call's end: other start forces, or a
            // state moved (the carried end evaluation must not be taken then)
            const bool moved_force = n % 50 == 25, moved_state = n % 50 == 40;
            if (moved_force) p.start[n % STEWART_LEGS] += 1.0;
            if (moved_state) y_a[7] += 1e-3, y_b[7] += 1e-3;
            char msg_a[STEWART_MESSAGE_SIZE] = "", msg_b[STEWART_MESSAGE_SIZE] = "";
            const stewart_status s_a = written_out.advance(y_a, p, hint_a, msg_a, sizeof msg_a);
            const stewart_status s_b = arkode.advance(y_b, p, hint_b, msg_b, sizeof msg_b);
            TEST_ASSERT_EQUAL_INT_MESSAGE(s_b, s_a, msg_a);
            TEST_ASSERT_EQUAL_STRING(msg_b, msg_a);
            if (s_a != STEWART_OK) break;
            same_bits("the state", y_a, y_b, sizeof y_a, run, n);
            same_bits("the step hint", &hint_a, &hint_b, sizeof hint_a, run, n);
            const stewart_plant_statistics &a = written_out.statistics(), &b = arkode.statistics();
            TEST_ASSERT_EQUAL_INT(b.steps, a.steps);
            // carried: the start's right-hand side is the last call's end evaluation (a call
            // after the first that starts at the state and forces the last one ended with)
            const bool carries = carry_end && n > 0 && !moved_force && !moved_state;
            TEST_ASSERT_EQUAL_INT(b.rhs_evaluations, a.rhs_evaluations);
            TEST_ASSERT_EQUAL_INT(carries, written_out.start_carried());
            carried += carries;
            TEST_ASSERT_EQUAL_INT(b.error_test_failures, a.error_test_failures);
            TEST_ASSERT_EQUAL_INT(b.last_order, a.last_order);
            same_bits("the last step size", &a.last_step_size, &b.last_step_size,
                      sizeof a.last_step_size, run, n);
            const plant::Evaluation *e_a = written_out.end_evaluation(),
                                    *e_b = arkode.end_evaluation();
            TEST_ASSERT_EQUAL_INT(e_b != nullptr, e_a != nullptr);
            if (e_a && !carry_end)
                same_bits("the end evaluation", e_a->twist_rate.data(), e_b->twist_rate.data(),
                          6 * sizeof(double), run, n);
            if (e_a && carry_end) {  // at the state returned, as a fresh evaluation there
                TEST_ASSERT_NOT_NULL(e_b);
                plant::Evaluation fresh;
                TEST_ASSERT_TRUE(plant::twist_rate(d, plant::motion_of_state(y_a), p.end, fresh));
                same_bits("the end evaluation (carry_end)", e_a->twist_rate.data(),
                          fresh.twist_rate.data(), 6 * sizeof(double), run, n);
            }
            multi_step_calls += a.steps > 1;
            rejections += a.error_test_failures;
        }
    }
    std::printf("fidelity %d, fixed steps %d%s: %ld calls equal bit for bit (%ld of more than one "
                "step, %ld rejected steps, %ld starts carried)\n",
                fidelity, fixed_steps, carry_end ? ", carry_end" : "", calls, multi_step_calls,
                rejections, carried);
    TEST_ASSERT_TRUE(calls == 1000);
    if (fixed_steps == 0) TEST_ASSERT_TRUE(multi_step_calls > 0 && rejections > 0);
}

void test_massless_adaptive(void) {
    for (bool carry : {false, true}) written_out_equals_arkode(STEWART_MASSLESS, 0, carry);
}
void test_full_adaptive(void) {
    for (bool carry : {false, true}) written_out_equals_arkode(STEWART_FULL, 0, carry);
}
void test_massless_fixed_steps(void) {
    for (bool carry : {false, true})
        for (int n = 1; n <= 3; ++n) written_out_equals_arkode(STEWART_MASSLESS, n, carry);
}
void test_full_fixed_steps(void) {
    for (bool carry : {false, true})
        for (int n = 1; n <= 3; ++n) written_out_equals_arkode(STEWART_FULL, n, carry);
}

}  // namespace

// The thesis platform, and the legs' forces that hold it at home (the forces swing about them).
void setUp(void) {
    stewart_params_default(&params);
    model = test_model(&params);
    const stewart_inverse_options full = test_options(STEWART_FULL);
    stewart_inverse *inverse = test_inverse_with(model, &full);
    stewart_inverse_input home{};
    home.pose.q[2] = params.home_height;
    stewart_inverse_output out;
    const stewart_status s = stewart_inverse_solve(inverse, &home, &out);
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, s, stewart_inverse_message(inverse));
    std::memcpy(static_force, out.force, sizeof static_force);
    stewart_inverse_free(inverse);
}

void tearDown(void) {
    stewart_model_free(model);
    model = nullptr;
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_massless_adaptive);
    RUN_TEST(test_full_adaptive);
    RUN_TEST(test_massless_fixed_steps);
    RUN_TEST(test_full_fixed_steps);
    return UNITY_END();
}
