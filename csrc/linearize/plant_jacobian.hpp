// The plant's state rate and outputs with their first derivatives, the fast way the
// linearisation uses: the mass matrix in plain numbers (it depends on the pose alone), the
// derivatives with respect to the state by the 12-direction dual through the residual of the
// equations of motion (implicit function theorem: d nu_dot = M^-1 d residual), those with
// respect to the forces analytically (they enter linearly: d nu_dot / dF = M^-1 J^T).
// The state is the tool's pose and rates in the user frame (kinematics/frames.hpp; the platform's
// in the base frame when the frames are identity): the frame transforms and the angles' rates are
// differentiated through the same dual.
// plant_derivatives.hpp's plant_point is the same by 18-direction dual through the solve (without
// frames), kept as the reference the tests compare this with.
#pragma once

#include <Eigen/Cholesky>

#include "kinematics/frames.hpp"
#include "linearize/plant_derivatives.hpp"

namespace stewart {
namespace lin {

// The plant's pose accelerations at x = (q, q_dot) in plain numbers, affine in the forces: the
// first stage of plant_jacobian, and all the inverse side needs to find the forces.
struct PlantRate {
    Motion platform;                               // base frame; accelerations not used
    Eigen::Vector3d angle_bias;                    // E_dot angles_dot of the tool's angles
    Eigen::LLT<Eigen::Matrix<double, 6, 6>> mass;  // M factored
    Eigen::Matrix<double, 6, 1> twist_rate;        // the platform's (v_dot, omega_dot), base frame
    Eigen::Matrix<double, 6, 6> twist_rate_wrt_force;  // M^-1 J^T
    double q_ddot[6];
    double q_ddot_wrt_force[6][STEWART_LEGS];
};

// Fills r at the forces; false (why set) for a leg fault or pitch at +-90 deg (the tool's or,
// through the frames, the platform's).
bool plant_rate(const plant::DynamicsModel &d, const Frames &f, const double q[6],
                const double q_dot[6], const double force[STEWART_LEGS], PlantRate &r,
                Failure &why);

// r moved from the forces it was made at to those plus change (q_ddot and the twist rate).
void plant_rate_add_force(PlantRate &r, const double change[STEWART_LEGS]);

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
bool plant_jacobian(const plant::DynamicsModel &d, const Frames &f, const double q[6],
                    const double q_dot[6], const double force[STEWART_LEGS], PlantJacobian &out,
                    Failure &why);

// The same from r = plant_rate(d, f, q, q_dot, force) (the second stage alone).
bool plant_jacobian(const plant::DynamicsModel &d, const Frames &f, const double q[6],
                    const double q_dot[6], const double force[STEWART_LEGS], const PlantRate &r,
                    PlantJacobian &out, Failure &why);

}  // namespace lin
}  // namespace stewart
