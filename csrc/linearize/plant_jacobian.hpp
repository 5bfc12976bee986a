// The plant's state rate and outputs with their first derivatives, the fast way the
// linearisation uses: the mass matrix in plain numbers (it depends on the pose alone), the
// derivatives with respect to the state by the 12-direction dual through the residual of the
// equations of motion (implicit function theorem: d nu_dot = M^-1 d residual), those with
// respect to the forces analytically (they enter linearly: d nu_dot / dF = M^-1 J^T).
// plant_derivatives.hpp's plant_point is the same by 18-direction dual through the solve, kept as
// the reference the tests compare this with.
#pragma once

#include "linearize/plant_derivatives.hpp"

namespace stewart {
namespace lin {

// The plant at x = (q, q_dot), u = F: q_ddot and the outputs L, L_dot with their derivatives,
// columns in the order of x (0-5 q, 6-11 q_dot) and of F (the outputs do not depend on F).
struct PlantJacobian {
    double q_ddot[6];
    double q_ddot_wrt_state[6][12];
    double q_ddot_wrt_force[6][STEWART_LEGS];
    double length[STEWART_LEGS], length_rate[STEWART_LEGS];
    double length_wrt_state[STEWART_LEGS][12], length_rate_wrt_state[STEWART_LEGS][12];
};

// Fills out; false (why set) for a leg fault or pitch at +-90 deg. Inputs beyond the plant's
// range give non-finite values (the caller checks them), as plant_point.
bool plant_jacobian(const fd::DynamicsModel &d, const double q[6], const double q_dot[6],
                    const double force[STEWART_LEGS], PlantJacobian &out, Failure &why);

}  // namespace lin
}  // namespace stewart
