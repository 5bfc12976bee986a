#include "core/step.hpp"

#include <cmath>
#include <cstring>

#include "core/assembly.hpp"
#include "core/dynamics.hpp"
#include "core/position_solver.hpp"
#include "core/message.hpp"

using mbs::set_message;

namespace mbs {

namespace {

mbs_status ensure_factor(State &s) {
    if (s.factor_current) return MBS_OK;
    if (!s.values_current)
        assemble_jacobian(s.mechanism, s.q.data(), s.drive.data(), s.values.data());
    s.values_current = true;
    if (!s.linear->factor(s.values.data()))
        return set_message(s.message, sizeof s.message, MBS_ERR_SINGULAR,
                           "the constraint Jacobian Phi_q is singular at this configuration");
    s.factor_current = true;
    return MBS_OK;
}

// Largest magnitude of a right-hand side; infinite if any entry is not finite.
double largest_magnitude(const std::vector<double> &v) {
    double m = 0.0;
    for (double x : v) m = std::isfinite(x) ? std::fmax(m, std::fabs(x)) : INFINITY;
    return m;
}

// True if every entry is finite: x * 0 is 0 for a finite x and NaN otherwise, and a NaN stays in
// the sum. Two entries at a time (no entry changes; the scan below finds the culprit).
bool all_finite(const std::vector<double> &v) {
    typedef double Two __attribute__((vector_size(16)));
    Two sum = {0.0, 0.0};
    const Two zero = {0.0, 0.0};
    size_t i = 0;
    for (; i + 2 <= v.size(); i += 2) {
        Two x;
        std::memcpy(&x, v.data() + i, sizeof x);
        sum += x * zero;
    }
    double total = sum[0] + sum[1];
    if (i < v.size()) total += v[i] * 0.0;
    return total == 0.0;
}

// A solution that is not finite comes from a right-hand side too large to solve with (inputs out
// of range: an argument error, as at the closed-form levels) or from a (nearly) singular Phi_q.
// Only then is the right-hand side assembled again (into v, whose values are lost anyway) to
// tell which: the common, finite case costs one sweep.
template <class AssembleRhs>
mbs_status check_finite(State &s, std::vector<double> &v, const char *what,
                        AssembleRhs assemble_rhs) {
    if (all_finite(v)) return MBS_OK;
    const double kOutOfRange = 1e150;  // within 1e4 of where squares overflow (1.3e154)
    for (size_t i = 0; i < v.size(); ++i) {
        if (std::isfinite(v[i])) continue;
        const double bad = v[i];
        assemble_rhs();
        const double rhs_max = largest_magnitude(v);
        if (!(rhs_max <= kOutOfRange))
            return set_message(s.message, sizeof s.message, MBS_ERR_ARGUMENT,
                               "%s[%zu] is %g: its right-hand side reaches %g: the inputs (driver "
                               "values, rates, accelerations or forces) are out of range",
                               what, i, bad, rhs_max);
        return set_message(s.message, sizeof s.message, MBS_ERR_SINGULAR,
                           "%s[%zu] is %g: the constraint Jacobian is (nearly) singular", what, i,
                           bad);
    }
    return MBS_OK;
}

// One of a step's linear solves on the shared factor of Phi_q: assemble_rhs puts the right-hand
// side into x, solved in place (with the transpose for the multipliers), then checked finite.
template <bool kTransposed, class AssembleRhs>
mbs_status solve_linear(State &s, std::vector<double> &x, const char *what,
                        AssembleRhs assemble_rhs) {
    const mbs_status st = ensure_factor(s);
    if (st != MBS_OK) return st;
    assemble_rhs();
    if (kTransposed) s.linear->solve_transposed(x.data());
    else s.linear->solve(x.data());
    return check_finite(s, x, what, assemble_rhs);
}

}  // namespace

mbs_status solve_position(State &s, double t, const SolverOptions &o, bool use_predictor) {
    if (!s.ok())
        return set_message(s.message, sizeof s.message, MBS_ERR_MEMORY, "solver not created");
    if (use_predictor && s.has_history) {
        const double h = t - s.time;
        for (size_t i = 0; i < s.q.size(); ++i)
            s.q[i] += h * s.q_dot[i] + 0.5 * h * h * s.q_ddot[i];
    }
    s.factor_current = false;
    s.values_current = false;
    s.time = t;
    return s.newton->solve(o);
}

mbs_status solve_velocity(State &s) {
    return solve_linear<false>(s, s.q_dot, "q_dot", [&s] {
        assemble_phi_t(s.mechanism, s.q.data(), s.drive.data(), s.q_dot.data());
        for (double &v : s.q_dot) v = -v;
    });
}

mbs_status solve_acceleration(State &s) {
    return solve_linear<false>(s, s.q_ddot, "q_ddot", [&s] {
        assemble_gamma(s.mechanism, s.q.data(), s.q_dot.data(), s.drive.data(), s.q_ddot.data());
    });
}

mbs_status solve_multipliers(State &s) {
    return solve_linear<true>(s, s.lambda, "lambda", [&s] {
        applied_minus_inertial(s.mechanism, s.q.data(), s.q_dot.data(), s.q_ddot.data(),
                               s.lambda.data());
    });
}

mbs_status solve_step(State &s, double t, const SolverOptions &o, bool use_predictor) {
    s.message[0] = '\0';
    mbs_status st = solve_position(s, t, o, use_predictor);
    if (st == MBS_OK) st = solve_velocity(s);
    if (st == MBS_OK) st = solve_acceleration(s);
    if (st == MBS_OK) st = solve_multipliers(s);
    s.has_history = (st == MBS_OK);
    return st;
}

mbs_status solve_step_known_motion(State &s, double t, const SolverOptions &o) {
    s.message[0] = '\0';
    mbs_status st = solve_position(s, t, o, false);
    if (st == MBS_OK && s.stats.iterations > 0) {  // q moved: the given motion is not at it
        st = solve_velocity(s);
        if (st == MBS_OK) st = solve_acceleration(s);
    }
    if (st == MBS_OK) st = solve_multipliers(s);
    s.has_history = (st == MBS_OK);
    return st;
}

}  // namespace mbs
