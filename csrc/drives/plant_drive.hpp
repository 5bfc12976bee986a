// The plant's form of a leg's drive law (leg_drive.hpp): friction and the screw's efficiency
// regularised near rest with a smoothing speed v_s, so that the plant's right-hand side is
// continuous in the leg speed, and the current that law needs for a given leg force and motion
// (what a test or a feed-forward feeds the current-driven plant to reproduce a trajectory).
#pragma once

#include "drives/leg_drive.hpp"

namespace stewart {

// s(v) = v / sqrt(v^2 + v_s^2): sign(v) away from rest, 0 at rest (v_s > 0).
double smooth_sign(double v, double smoothing_speed);

// The factor e of the nut's force F_nut = e F_i, F_i the screw's torque from the motor side as a
// force (2 pi N / lead) tau, for x = sign(F_i) s(L_dot) in (-1, 1): forward (x > 0, the motor
// drives the load) 1 + (eta - 1) x, backward 1 - (1 / eta_back - 1) x. It is eta and 1 / eta_back
// away from rest and 1 (lossless) at rest: the screw's loss (1 - e) F_i L_dot is never negative.
inline double screw_force_factor(const LegDrive &d, double x) {
    return x >= 0 ? 1.0 + (d.efficiency - 1.0) * x : 1.0 - (1.0 / d.back_efficiency - 1.0) * x;
}

// The motor current that makes the plant's leg push the mechanism with leg_force [N] at leg
// speed L_dot and acceleration L_ddot, with no end stop engaged: the nut pushes leg_force plus
// friction, the motor adds the reflected inertia: i = (F_nut / e + m_r L_ddot) / (c k_t).
double drive_current(const LegDrive &d, double leg_force, double L_dot, double L_ddot,
                     double smoothing_speed);

}  // namespace stewart
