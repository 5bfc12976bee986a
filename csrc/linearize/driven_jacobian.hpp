// The plant driven by its motors' currents or voltages (plant/plant_drive_rhs.cpp) linearised:
// the driven plant is the force-driven plant under the legs' drive forces F_k = phi_k(L_k,
// L_dot_k, L_ddot_k, i_k), one scalar law per leg, so its derivatives are plant_jacobian's (the
// force-driven plant's, at those forces) composed with the law's partial derivatives, L_ddot's
// own by leg_lengths, and the loop closed through L_ddot(q_ddot) by one 6 x 6 solve.
#pragma once

#include "kinematics/frames.hpp"
#include "linearize/plant_derivatives.hpp"

namespace stewart {
namespace lin {

constexpr int kDrivenStates = 18;  // (q, q_dot, i_1 .. i_6) at most

struct DrivenJacobian {
    int states = 12;  // 18 with the windings' currents (voltage input, an inductance)
    double state_rate[kDrivenStates] = {};
    double A[kDrivenStates][kDrivenStates] = {};  // rows and columns beyond states zero
    double B[kDrivenStates][STEWART_LEGS] = {};
    double length[STEWART_LEGS], length_rate[STEWART_LEGS];
    double length_wrt_state[STEWART_LEGS][12], length_rate_wrt_state[STEWART_LEGS][12];
    double leg_force[STEWART_LEGS];
    int not_smooth_legs = 0;  // bit k: leg k's terms at a kink (stewart_linearize_driven)
};

// Fills out at x = (q, q_dot[, current]), u = input. force_model: the plant's dynamics without
// drives (input FORCE); driven: the same with the drives (input CURRENT or VOLTAGE). False (why
// set) for a leg fault, pitch at +-90 deg, or a power flow that does not settle.
bool driven_jacobian(const plant::DynamicsModel &force_model, const plant::DynamicsModel &driven,
                     const Frames &f, const double q[6], const double q_dot[6],
                     const double input[STEWART_LEGS], const double current[STEWART_LEGS],
                     DrivenJacobian &out, Failure &why);

}  // namespace lin
}  // namespace stewart
