// The sensor readings at a measured pose and their closed-form derivatives with respect to the
// geometry: joints, length offsets, tool and user frames (kinematic calibration,
// docs/calibration.md §2).
#pragma once

#include <Eigen/Dense>

#include "kinematics/closed_form.hpp"
#include "stewart/stewart.h"

namespace stewart {

using Matrix63 = Eigen::Matrix<double, STEWART_LEGS, 3>;

// Everything a reading depends on besides the pose: joints (a_k base frame, b_k platform frame),
// length offsets o_k (joint-to-joint length = reading + o_k), the tool frame in the platform frame
// and the user frame in the base frame as (x, y, z, roll, pitch, yaw).
struct CalibrationGeometry {
    Matrix36 base_points;
    Matrix36 platform_points;
    Vector6 length_offset;
    Vector6 tool_frame;
    Vector6 user_frame;
    double min_length;  // below it a leg has no direction [m]
};

// Row k of each block is d reading_k / d (that parameter's elements); a leg's reading depends on
// its own joints and offset only, so the joint blocks keep leg k's three columns in row k.
struct GeometryJacobian {
    Vector6 length;           // joint-to-joint |p + R b_k - a_k| [m]
    Vector6 reading;          // length - length_offset: what leg k's sensor reads [m]
    Matrix63 base_joint;      // d reading_k / d a_k (x, y, z)
    Matrix63 platform_joint;  // d reading_k / d b_k (x, y, z)
    Vector6 length_offset;    // d reading_k / d o_k = -1
    Matrix6 tool_frame;       // d reading_k / d tool_frame (x, y, z, roll, pitch, yaw)
    Matrix6 user_frame;       // d reading_k / d user_frame
    Matrix6 pose;             // d reading_k / d pose of the tool frame in the user frame
};

// Readings and derivatives at `pose` (x, y, z, roll, pitch, yaw of the tool frame in the user
// frame). STEWART_ERR_UNREACHABLE (message names the leg) when a leg is shorter than min_length;
// the caller checks that the pose is finite.
stewart_status geometry_jacobian(const CalibrationGeometry &g, const double pose[6],
                                 GeometryJacobian &out, char *msg, size_t size);

}  // namespace stewart
