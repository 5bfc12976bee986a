// White-box test of the full plant's closed-form right-hand side for axisymmetric leg bodies
// (plant::twist_rate for double, csrc/plant/plant_full_rhs.cpp) against the template formulation
// it replaces (plant::twist_rate<double>, plant_equations_impl.hpp: every body's world inertia
// A diag A^T, the u-space mass blocks, the leg bodies' full motions), which stays the
// formulation of the dual scalar (linearisation): on random states (any rotation, fast motion,
// forces to 50 kN) the two twist rates agree within 1e-13 relative (each half, linear and
// angular, against its own size) and agree on the same faults, and so do the base wrench in
// closed form (plant::base_wrench of the motion: its leg terms found anew, and reused from the
// right-hand side's kept terms) and base_wrench of the 13 bodies' motions; one 1 ms plant step
// of each from random states near home within 1e-13 of the state's scale; the plant's step
// outputs (base wrench from the end evaluation's kept terms) against stewart_plant_output_get at
// the same state (found anew); leg bodies that are not axisymmetric take the template itself
// (equal bits). For the thesis platform and for one with a payload off its centre (full
// inertia, centre of mass off the origin).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "plant/plant_integrator.hpp"
#include "plant/plant_object.hpp"
#include "stewart/stewart.h"
#include "test_support.h"
#include "unity.h"

namespace plant = stewart::plant;

namespace {

constexpr double kBound = 1e-13;

double uniform(uint64_t &state, double a, double b) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return a + (b - a) * static_cast<double>(state >> 11) / 9007199254740992.0;
}

// The larger of two differences, infinite if either is NaN (std::max would drop a NaN second
// argument and let a fast path returning NaN pass).
double worse(double a, double b) {
    return std::isnan(a) || std::isnan(b) ? INFINITY : std::max(a, b);
}

// A difference relative to scale (absolute where the scale is zero).
double relative(double difference, double scale) {
    return scale > 0 ? difference / scale : difference;
}

// The larger relative difference of the two halves (linear, angular) of the twist rates.
double relative_difference(const plant::Evaluation &a, const plant::Evaluation &b) {
    double worst = 0;
    for (int half = 0; half < 2; ++half) {
        double scale = 0, difference = 0;
        for (int i = 3 * half; i < 3 * half + 3; ++i) {
            scale = std::max(scale, std::fabs(b.twist_rate[i]));
            difference = worse(difference, std::fabs(a.twist_rate[i] - b.twist_rate[i]));
        }
        worst = worse(worst, relative(difference, scale));
    }
    return worst;
}

// The base wrench in closed form (plant::base_wrench of the motion, with closed's configuration and
// its kept terms if it kept them) against base_wrench of body_motions' 13 bodies, at the
// platform's motion m with the twist rate of e: the larger relative difference of the force
// and the torque.
double base_wrench_difference(const plant::DynamicsModel &d, stewart::Motion m,
                              const plant::Evaluation &e, const plant::Evaluation &closed) {
    m.acceleration = e.twist_rate.head<3>();
    m.alpha = e.twist_rate.tail<3>();
    stewart::Motion bodies[13];
    plant::body_motions(d, m, e, bodies);
    plant::Vec3 force, torque, force_fast, torque_fast;
    plant::base_wrench(d, bodies, force, torque);
    plant::base_wrench(d, m, closed, force_fast, torque_fast);
    if (!force_fast.allFinite() || !torque_fast.allFinite()) return INFINITY;
    return worse(relative((force_fast - force).lpNorm<Eigen::Infinity>(),
                          force.lpNorm<Eigen::Infinity>()),
                 relative((torque_fast - torque).lpNorm<Eigen::Infinity>(),
                          torque.lpNorm<Eigen::Infinity>()));
}

stewart_model *make_model(const stewart_params &params) {
    char message[STEWART_MESSAGE_SIZE];
    stewart_model *model = stewart_model_create(&params, message, sizeof message);
    TEST_ASSERT_NOT_NULL_MESSAGE(model, message);
    return model;
}

// Both formulations on 20,000 random states: the worst relative difference (bound checked by the
// caller) and the number of disagreements on whether (and where) a state is defined.
double compare_twist_rates(const plant::DynamicsModel &d, bool same_bits_expected) {
    uint64_t rng = 424242;
    double worst = 0, worst_wrench = 0, worst_kept = 0;
    int disagreements = 0, defined = 0;
    for (int n = 0; n < 20000; ++n) {
        double y[plant::kStates], force[STEWART_LEGS];
        y[0] = uniform(rng, -0.2, 0.2);
        y[1] = uniform(rng, -0.2, 0.2);
        y[2] = 1.0 + uniform(rng, -0.3, 0.3);
        for (int i = 3; i < 7; ++i) y[i] = uniform(rng, -1.5, 1.5);
        for (int i = 7; i < 13; ++i) y[i] = uniform(rng, -20, 20);
        for (double &f : force) f = uniform(rng, -5e4, 5e4);
        const stewart::Motion m = plant::motion_of_state(y);
        plant::Evaluation fast, reference;
        fast.keep_terms = true;
        const bool a = plant::twist_rate(d, m, force, fast);
        const bool b = plant::twist_rate<double>(d, m, force, reference);
        if (a != b || fast.fault != reference.fault || fast.fault_leg != reference.fault_leg) {
            ++disagreements;
            continue;
        }
        if (!a) continue;
        ++defined;
        if (same_bits_expected)
            disagreements += std::memcmp(fast.twist_rate.data(), reference.twist_rate.data(),
                                         6 * sizeof(double)) != 0;
        // the closed form keeps its terms when asked; the template never does
        disagreements += fast.terms_kept == same_bits_expected;
        worst = worse(worst, relative_difference(fast, reference));
        worst_wrench = worse(worst_wrench, base_wrench_difference(d, m, reference, reference));
        worst_kept = worse(worst_kept, base_wrench_difference(d, m, reference, fast));
    }
    std::printf("%d defined states, worst relative difference %.3g (twist rate), %.3g (base "
                "wrench), %.3g (base wrench from the kept terms)\n",
                defined, worst, worst_wrench, worst_kept);
    worst = worse(worst, worse(worst_wrench, worst_kept));
    TEST_ASSERT_EQUAL_INT(0, disagreements);
    TEST_ASSERT_TRUE(defined > 10000);
    return worst;
}

// One 1 ms step of the plant's integrator with each formulation from random states near home
// under random forces around the static ones: the worst difference relative to max(1, |y_i|).
double compare_steps(const plant::DynamicsModel &d) {
    plant::DynamicsModel reference_model = d;
    reference_model.reference_equations = true;
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    o.fidelity = STEWART_FULL;
    char message[STEWART_MESSAGE_SIZE];
    plant::Integrator fast, reference;
    TEST_ASSERT_TRUE_MESSAGE(fast.init(&d, o, message, sizeof message), message);
    TEST_ASSERT_TRUE_MESSAGE(reference.init(&reference_model, o, message, sizeof message), message);
    uint64_t rng = 2024;
    double worst = 0;
    for (int n = 0; n < 500; ++n) {
        double y[plant::kStates] = {0}, y_ref[plant::kStates];
        y[0] = uniform(rng, -0.05, 0.05);
        y[1] = uniform(rng, -0.05, 0.05);
        y[2] = 1.0 + uniform(rng, -0.1, 0.1);
        const double half = 0.5 * uniform(rng, 0, 0.3);
        double axis[3], norm = 0;
        for (double &a : axis) a = uniform(rng, -1, 1), norm += a * a;
        y[3] = std::cos(half);
        for (int i = 0; i < 3; ++i) y[4 + i] = std::sin(half) * axis[i] / std::sqrt(norm);
        for (int i = 7; i < 13; ++i) y[i] = uniform(rng, -0.5, 0.5);
        std::memcpy(y_ref, y, sizeof y);
        plant::ForceProfile p;
        p.h = 1e-3;
        for (int k = 0; k < STEWART_LEGS; ++k) {
            p.start[k] = uniform(rng, 0, 3000);
            p.end[k] = p.start[k] + uniform(rng, -400, 400);
        }
        double hint = 0, hint_ref = 0;
        char m_a[STEWART_MESSAGE_SIZE] = "", m_b[STEWART_MESSAGE_SIZE] = "";
        const stewart_status a = fast.advance(y, p, hint, m_a, sizeof m_a);
        const stewart_status b = reference.advance(y_ref, p, hint_ref, m_b, sizeof m_b);
        TEST_ASSERT_EQUAL_INT_MESSAGE(b, a, m_a);
        if (a != STEWART_OK) continue;
        for (int i = 0; i < plant::kStates; ++i)
            worst = worse(worst, std::fabs(y[i] - y_ref[i]) / std::max(1.0, std::fabs(y_ref[i])));
    }
    std::printf("500 steps of 1 ms, worst difference %.3g of the state's scale\n", worst);
    return worst;
}

// The full inverse solve's forces holding the platform at rest at home.
void static_forces(const stewart_model *model, double force[STEWART_LEGS]) {
    const stewart_inverse_options o = test_options(STEWART_FULL);
    stewart_inverse *inverse = test_inverse_with(model, &o);
    stewart_inverse_input in{};
    in.pose.q[2] = stewart_model_params(model)->home_height;
    stewart_inverse_output out;
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_inverse_solve(inverse, &in, &out),
                                  stewart_inverse_message(inverse));
    for (int k = 0; k < STEWART_LEGS; ++k) force[k] = out.force[k];
    stewart_inverse_free(inverse);
}

// The full plant's step outputs (their base wrench from the end evaluation's kept terms) against
// stewart_plant_output_get at the state the step reached (the terms found anew), along 300
// steps of 1 ms under forces around the static ones: the worst relative difference of the base
// force and torque. The written-out ERK 4(3) ends on an evaluation at the step's end, and most
// of its steps must reuse it (counted, so that a change that stops keeping the terms fails
// here); ARKODE's Dormand-Prince (0 of 300 steps: its last evaluation is not at the state it
// returns) and CVODE BDF (the last evaluation is an iterate) check the fallback.
double compare_step_outputs(const stewart_model *model) {
    double worst = 0;
    const int methods[] = {STEWART_PLANT_ERK, STEWART_PLANT_ERK5, STEWART_PLANT_BDF};
    for (int method : methods) {
        stewart_plant_options o = test_plant_options(STEWART_FULL);
        o.method = method;
        stewart_plant *plant = test_plant_with(model, &o);
        stewart_plant_input in{};
        in.h = 1e-3;
        uint64_t rng = 77;
        double static_force[STEWART_LEGS];
        static_forces(model, static_force);
        for (int k = 0; k < STEWART_LEGS; ++k) in.force_end[k] = static_force[k];
        int reused = 0;
        for (int n = 0; n < 300; ++n) {
            for (int k = 0; k < STEWART_LEGS; ++k) {
                in.force_start[k] = in.force_end[k];
                in.force_end[k] = static_force[k] * (1 + 0.05 * std::sin(0.01 * n * (k + 1))) +
                                  uniform(rng, -20, 20);
            }
            stewart_plant_output out, again;
            TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_plant_step(plant, &in, &out),
                                          stewart_plant_message(plant));
            const plant::Evaluation *end = plant->integrator.end_evaluation();
            if (end && end->terms_kept) ++reused;
            TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_plant_output_get(plant, nullptr, &again));
            double force_scale = 0, torque_scale = 0, force_error = 0, torque_error = 0;
            for (int i = 0; i < 3; ++i) {
                force_scale = std::max(force_scale, std::fabs(again.base_force[i]));
                torque_scale = std::max(torque_scale, std::fabs(again.base_torque[i]));
                force_error =
                    worse(force_error, std::fabs(out.base_force[i] - again.base_force[i]));
                torque_error =
                    worse(torque_error, std::fabs(out.base_torque[i] - again.base_torque[i]));
            }
            worst = worse(worst, worse(relative(force_error, force_scale),
                                       relative(torque_error, torque_scale)));
        }
        std::printf("method %d: %d of 300 steps' outputs from the kept terms\n", method, reused);
        if (method == STEWART_PLANT_ERK) TEST_ASSERT_GREATER_THAN_INT(250, reused);
        stewart_plant_free(plant);
    }
    std::printf("900 plant steps, outputs' base wrench against output_get's: worst %.3g\n", worst);
    return worst;
}

void check_platform(const stewart_params &params) {
    stewart_model *model = make_model(params);
    const plant::DynamicsModel d = plant::dynamics_model(*model, STEWART_FULL);
    TEST_ASSERT_TRUE(d.cylinder_inertia[0] == d.cylinder_inertia[1]);  // the fast path's case
    TEST_ASSERT_TRUE(compare_twist_rates(d, false) <= kBound);
    TEST_ASSERT_TRUE(compare_steps(d) <= kBound);
    TEST_ASSERT_TRUE(compare_step_outputs(model) <= kBound);
    stewart_model_free(model);
}

void test_thesis_platform(void) {
    stewart_params params;
    stewart_params_default(&params);
    check_platform(params);
}

void payload_off_centre(stewart_params &params) {
    params.payload_mass = 37.5;
    const double com[3] = {0.07, -0.04, 0.12}, inertia[3] = {1.3, 0.9, 2.1};
    for (int i = 0; i < 3; ++i)
        params.payload_com[i] = com[i], params.payload_inertia[i] = inertia[i];
}

void test_payload_off_centre(void) {
    stewart_params params;
    stewart_params_default(&params);
    payload_off_centre(params);
    // heavier, longer-spinning leg bodies than the thesis's (c > a: a disc-like spin inertia)
    params.cylinder_inertia[0] = params.cylinder_inertia[1] = 0.004;
    params.cylinder_inertia[2] = 0.006;
    params.piston_inertia[2] = 1.8 * params.piston_inertia[0];
    check_platform(params);
}

// Leg bodies that are not axisymmetric take the template formulation: equal bits.
void test_not_axisymmetric(void) {
    stewart_params params;
    stewart_params_default(&params);
    payload_off_centre(params);
    params.piston_inertia[1] = params.piston_inertia[0] + 0.5 * params.piston_inertia[2];
    stewart_model *model = make_model(params);
    const plant::DynamicsModel d = plant::dynamics_model(*model, STEWART_FULL);
    compare_twist_rates(d, true);
    stewart_model_free(model);
}

}  // namespace

void setUp(void) {}
void tearDown(void) {}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_thesis_platform);
    RUN_TEST(test_payload_off_centre);
    RUN_TEST(test_not_axisymmetric);
    return UNITY_END();
}
