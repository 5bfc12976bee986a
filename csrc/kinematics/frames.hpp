// Tool and user frames (docs/api.md, "Tool and user frames"): the poses a caller gives and gets
// are the tool frame's (fixed on the platform) in the user frame (fixed on the base), with angles
// in the platform's rotation_order and both frames turned by 180 deg about x when
// frame_convention is 1 (z down; docs/geometry.md, "Rotation order and frames"); the solvers work
// on the platform frame in the z-up base frame with R = Rz Ry Rx. The frames' constants (made once
// with the model) and the transforms each direction calls at its boundary, on entry and on exit
// only.
#pragma once

#include <Eigen/Dense>

#include "kinematics/motion.hpp"
#include "kinematics/rotation_order.hpp"
#include "stewart/stewart.h"

namespace stewart {

struct Frames {
    bool identity = true;  // frames identity, order 0, z up: no transform at all (bit for bit)
    bool turns = false;    // a frame turned or the angles converted (else they pass through)
    int rotation_order = kRotationZYX;  // of the caller's angles (the frames' own included)
    bool z_down = false;  // frame_convention 1: base and platform frames z down (user_rotation
                          // and tool_rotation hold the 180 deg turn about x)
    Eigen::Vector3d user_origin = Eigen::Vector3d::Zero();        // base frame
    Eigen::Matrix3d user_rotation = Eigen::Matrix3d::Identity();  // user axes to base axes
    Eigen::Vector3d tool_origin = Eigen::Vector3d::Zero();        // platform frame
    Eigen::Matrix3d tool_rotation = Eigen::Matrix3d::Identity();  // tool axes to platform axes
    // Roll and yaw of the tool minus the platform's at zero platform rotation: the tool's roll and
    // yaw are taken on the branch nearest to the platform's (continuous) angles plus these.
    double angle_shift[3] = {0, 0, 0};
    // The caller's roll, pitch and yaw move as these signs times the platform's (z down: a turn
    // about x maps Rz Ry Rx angles (r, p, y) to (r, -p, -y)): for the branch of roll and yaw.
    double angle_sign[3] = {1, 1, 1};
};

// The frames of parameters p (tool_frame, user_frame, rotation_order, frame_convention; checked
// by the table).
Frames frames_of(const stewart_params &p);

// The parameters the solvers use: p itself for frame_convention 0; for 1 (z down) every vector
// given in the base or platform frame (joints, Cardan axes, joint neutral axes, centres of mass;
// geometry 0's azimuths) turned by 180 deg about x into the z-up frames. Gravity is in the z-up
// world in both, home_height the height of the platform frame above the base frame in both, and
// the tool and user frames stay as given (frames_of composes the turn).
stewart_params params_in_solver_frames(const stewart_params &p);

// The platform's motion in the base frame from the tool's in the user frame. Templated on the
// scalar so that the linearisation carries derivatives through it (double instantiated once, in
// frames.cpp).
template <class S>
MotionT<S> platform_motion(const Frames &f, const MotionT<S> &tool) {
    const Eigen::Matrix<S, 3, 3> U = f.user_rotation.template cast<S>();
    MotionT<S> m;
    m.rotation = U * tool.rotation * f.tool_rotation.transpose().template cast<S>();
    m.omega = U * tool.omega;
    m.alpha = U * tool.alpha;
    // platform origin to tool origin
    const Eigen::Matrix<S, 3, 1> arm = m.rotation * f.tool_origin.template cast<S>();
    m.position = f.user_origin.template cast<S>() + U * tool.position - arm;
    m.velocity = U * tool.velocity - m.omega.cross(arm);
    m.acceleration = U * tool.acceleration - m.alpha.cross(arm) - m.omega.cross(m.omega.cross(arm));
    return m;
}
extern template Motion platform_motion<double>(const Frames &f, const Motion &tool);

// The tool's motion in the user frame from the platform's in the base frame (the inverse of
// platform_motion; any scalar, double instantiated in frames.cpp).
template <class S>
MotionT<S> tool_motion(const Frames &f, const MotionT<S> &platform) {
    const Eigen::Matrix<S, 3, 3> Ut = f.user_rotation.transpose().template cast<S>();
    const Eigen::Matrix<S, 3, 1> arm = platform.rotation * f.tool_origin.template cast<S>();
    MotionT<S> m;
    m.rotation = Ut * platform.rotation * f.tool_rotation.template cast<S>();
    m.omega = Ut * platform.omega;
    m.alpha = Ut * platform.alpha;
    m.position = Ut * (platform.position + arm - f.user_origin.template cast<S>());
    m.velocity = Ut * (platform.velocity + platform.omega.cross(arm));
    m.acceleration = Ut * (platform.acceleration + platform.alpha.cross(arm) +
                           platform.omega.cross(platform.omega.cross(arm)));
    return m;
}
extern template Motion tool_motion<double>(const Frames &f, const Motion &platform);

// The motion of the platform frame (base frame) at the caller's pose (the tool's in the user
// frame, angles in the frames' rotation order), for frames that are not identity.
inline Motion platform_motion_of_pose(const Frames &f, const stewart_pose &tool) {
    return platform_motion(f, motion_of_pose_in_order(f.rotation_order, tool));
}

// The base wrench (force, torque about the base origin) from the solvers' z-up base frame into the
// base frame of the parameters: turned back by 180 deg about x when z is down (user frames do not
// move it).
template <class S>
void base_wrench_to_given_frame(const Frames &f, S force[3], S torque[3]) {
    if (!f.z_down) return;
    for (int i = 1; i < 3; ++i) force[i] = -force[i], torque[i] = -torque[i];
}

// Every value of m finite (a transformed motion can overflow where the given one did not).
bool motion_finite(const Motion &m);

// The tool's pose in the user frame (angles in the frames' rotation order) from the platform's
// pose in the base frame, with rates if derivatives >= 1 and accelerations if 2 (else those rows
// are 0). Pitch in [-pi/2, pi/2], roll and yaw continuous with the platform's. False (tool
// unchanged) when rates are wanted and the tool's pitch is at +-90 deg (|cos pitch| <=
// min_cos_pitch), where its roll and yaw rates are not defined.
bool tool_pose(const Frames &f, const stewart_pose &platform, int derivatives, stewart_pose &tool,
               double min_cos_pitch = 1e-12);

// The inverse: the platform's pose q (and its rates if tool_rate is not NULL) in the base frame
// from the tool's tool_q (and tool_rate) in the user frame (angles in the rotation order). False
// (q, rate unchanged) when the platform's pitch is at +-90 deg (|cos pitch| <= min_cos_pitch) and
// rates are wanted.
bool platform_pose(const Frames &f, const double tool_q[6], const double *tool_rate, double q[6],
                   double *rate, double min_cos_pitch = 1e-12);

}  // namespace stewart
