// Inverse dynamics with Haug's Euler-parameter equations (docs/model.md), body frames at the centre
// of mass on principal axes: M q_ddot + Phi_q^T lambda = Q.
#pragma once

#include "core/state.hpp"

namespace mbs {

// out = Q(q, q_dot) - M(q) q_ddot: gravity, and the Euler-parameter velocity term
// 8 G_dot^T J' G_dot p; M = diag(m I, 4 G^T J' G).
void applied_minus_inertial(const Mechanism &m, const double *q, const double *q_dot,
                            const double *q_ddot, double *out);

// The force (world, at the body's reference point) and torque (world, about that point) that
// joint `joint` puts on its body i (side 0) or body j (side 1), from its multipliers.
void joint_reaction(const Mechanism &m, const State &s, int joint, int side, Vec3 &force,
                    Vec3 &torque);

// Kinetic and potential energy of the free bodies.
double mechanical_energy(const Mechanism &m, const double *q, const double *q_dot);

}  // namespace mbs
