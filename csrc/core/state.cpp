#include "core/state.hpp"

#include "core/position_solver.hpp"

#include <cstdio>

namespace mbs {

State::State(const Mechanism &m, const SolverOptions &kind)
    : mechanism(m), q(m.coordinates), q_dot(m.coordinates), q_ddot(m.coordinates),
      lambda(m.equations), drive(m.drivers), values(m.values()), rhs(m.equations),
      force(m.coordinates) {
    for (size_t b = 0; b < m.bodies.size(); ++b)
        for (int c = 0; c < 7; ++c) q[7 * b + c] = m.bodies[b].q_reference[c];
    linear = make_linear_solver(m, kind.linear);
    if (!linear) {
        std::snprintf(message, sizeof message, "the requested block linear solver does not fit "
                      "this mechanism's structure");
        return;
    }
    newton_options = kind;
    newton = std::make_unique<PositionSolver>(*this, kind);
    if (!newton->ok()) newton.reset();
}

State::~State() = default;

void copy_state(State &dst, const State &src) {
    dst.q = src.q;
    dst.q_dot = src.q_dot;
    dst.q_ddot = src.q_ddot;
    dst.lambda = src.lambda;
    dst.drive = src.drive;
    dst.time = src.time;
    dst.has_history = src.has_history;
    dst.stats = src.stats;
    std::copy(src.message, src.message + sizeof src.message, dst.message);
    dst.factor_current = false;
    dst.values_current = false;
}

void reset_history(State &s) {
    s.has_history = false;
    s.factor_current = false;
    s.values_current = false;
    s.stats = SolveStats{};
    s.message[0] = '\0';
}

}  // namespace mbs
