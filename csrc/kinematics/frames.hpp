// Tool and user frames (docs/api.md, "Tool and user frames"): the poses a caller gives and gets
// are the tool frame's (fixed on the platform) in the user frame (fixed on the base); the solvers
// work on the platform frame in the base frame. The frames' constants (made once with the model)
// and the transforms each direction calls at its boundary, on entry and on exit only.
#pragma once

#include <Eigen/Dense>

#include "kinematics/motion.hpp"
#include "stewart/stewart.h"

namespace stewart {

struct Frames {
    bool identity = true;           // both frames identity: no transform at all (bit for bit)
    bool turns = false;             // a frame is rotated (else the angles pass through as they are)
    Eigen::Vector3d user_origin = Eigen::Vector3d::Zero();  // base frame
    Eigen::Matrix3d user_rotation = Eigen::Matrix3d::Identity();  // user axes to base axes
    Eigen::Vector3d tool_origin = Eigen::Vector3d::Zero();  // platform frame
    Eigen::Matrix3d tool_rotation = Eigen::Matrix3d::Identity();  // tool axes to platform axes
    // Roll and yaw of the tool minus the platform's at zero platform rotation: the tool's roll and
    // yaw are taken on the branch nearest to the platform's (continuous) angles plus these.
    double angle_shift[3] = {0, 0, 0};
};

// The frames of parameters p (tool_frame, user_frame; checked finite by the table).
Frames frames_of(const stewart_params &p);

// The platform's motion in the base frame from the tool's in the user frame.
Motion platform_motion(const Frames &f, const Motion &tool);

// Every value of m finite (a transformed motion can overflow where the given one did not).
bool motion_finite(const Motion &m);

// The tool's pose in the user frame from the platform's pose in the base frame, with rates if
// derivatives >= 1 and accelerations if 2 (else those rows are 0). Pitch in [-pi/2, pi/2], roll
// and yaw continuous with the platform's. False (tool unchanged) when rates are wanted and the
// tool's pitch is at +-90 deg (|cos pitch| <= min_cos_pitch), where its roll and yaw rates are
// not defined.
bool tool_pose(const Frames &f, const stewart_pose &platform, int derivatives, stewart_pose &tool,
               double min_cos_pitch = 1e-12);

// The inverse: the platform's pose q (and its rates if tool_rate is not NULL) in the base frame
// from the tool's tool_q (and tool_rate) in the user frame. False (q, rate unchanged) when the
// platform's pitch is at +-90 deg (|cos pitch| <= min_cos_pitch) and rates are wanted.
bool platform_pose(const Frames &f, const double tool_q[6], const double *tool_rate, double q[6],
                   double *rate, double min_cos_pitch = 1e-12);

}  // namespace stewart
