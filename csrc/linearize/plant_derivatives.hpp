// The plant's right-hand side and outputs, and the legs' lengths, with their derivatives: the
// plant's own equations (plant/plant_equations.*) evaluated in the dual scalar (util/dual.hpp).
#pragma once

#include "kinematics/frames.hpp"
#include "plant/plant_equations.hpp"
#include "util/dual.hpp"

namespace stewart {
namespace lin {

// Below it roll and yaw rates are undefined (pitch = +-90 deg); the plant's own bound.
constexpr double kMinCosPitch = 1e-9;

// Why an evaluation failed: a leg fault (plant::LegFault, 0-based leg) or pitch at +-90 deg.
struct Failure {
    plant::LegFault fault = plant::LegFault::None;
    int leg = -1;
    bool pitch = false;
    int unsettled_leg = -1;  // the driven plant's power flow did not settle on this leg (0-based)
};

// The plant at x = (q, q_dot), u = F: q_ddot and the outputs L, L_dot, each with its derivatives
// along directions 0-5 q, 6-11 q_dot, 12-17 F.
struct PlantPoint {
    Dual q_ddot[6];
    Dual length[STEWART_LEGS], length_rate[STEWART_LEGS];
};
bool plant_point(const plant::DynamicsModel &d, const double q[6], const double q_dot[6],
                 const double force[STEWART_LEGS], PlantPoint &out, Failure &why);

// The legs' lengths and their first two rates at the pose (q, q_dot, q_ddot: the tool's in the
// user frame, frames f), each with its derivatives along directions 0-5 q, 6-11 q_dot, 12-17
// q_ddot.
bool leg_lengths(const plant::LegParameters &p, const Frames &f, const double q[6],
                 const double q_dot[6], const double q_ddot[6], Dual length[STEWART_LEGS],
                 Dual rate[STEWART_LEGS], Dual accel[STEWART_LEGS], Failure &why);

// The wrench the moving bodies put on the base (plant/plant_equations.hpp: base_wrench; base
// frame) when the tool moves with the pose (q, q_dot, q_ddot), with its derivatives along the
// directions of leg_lengths.
bool pose_base_wrench(const plant::DynamicsModel &d, const Frames &f, const double q[6],
                      const double q_dot[6], const double q_ddot[6], Dual force[3], Dual torque[3],
                      Failure &why);

}  // namespace lin
}  // namespace stewart
