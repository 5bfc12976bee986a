// One step of kinematics and inverse dynamics on a State: position (KINSOL), velocity,
// acceleration, multipliers, all on one factorisation of Phi_q at the solution.
#pragma once

#include "core/state.hpp"

namespace mbs {

// Newton from state.q; with use_predictor and a known previous step, first moves q by
// h q_dot + h^2/2 q_ddot (h = t - previous time).
mbs_status solve_position(State &s, double t, const SolverOptions &o, bool use_predictor);
// Phi_q q_dot = -Phi_t.
mbs_status solve_velocity(State &s);
// Phi_q q_ddot = gamma.
mbs_status solve_acceleration(State &s);
// Phi_q^T lambda = Q - M q_ddot.
mbs_status solve_multipliers(State &s);
// All four; marks the state as history for the next predictor.
mbs_status solve_step(State &s, double t, const SolverOptions &o, bool use_predictor);
// The same step when the caller knows the motion: q holds the guess and q_dot, q_ddot the
// velocities and accelerations of every body at it, consistent with the constraints (a closed
// form: Phi_q q_dot = -Phi_t, Phi_q q_ddot = gamma, to rounding). If the guess passes with no
// Newton iteration they stand and only the multipliers are solved (one factorisation, one
// transposed solve); if Newton moved q they are solved as in solve_step.
mbs_status solve_step_known_motion(State &s, double t, const SolverOptions &o);

}  // namespace mbs
