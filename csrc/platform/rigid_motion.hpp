// Motion of the platform frame from the pose (x, y, z, roll, pitch, yaw) and its time derivatives,
// with R = Rz(yaw) Ry(pitch) Rx(roll) (model.md §3).
#pragma once

#include <Eigen/Dense>

#include "stewart/stewart.h"

namespace stewart {

struct RigidMotion {
    Eigen::Vector3d position, velocity, acceleration;  // of the platform frame origin, world
    Eigen::Matrix3d rotation;                          // platform to world
    Eigen::Vector3d omega, alpha;                      // angular velocity and acceleration, world
};

// STEWART_ERR_ARGUMENT (message names the component, e.g. "roll_dot", and its value) unless
// every pose component and derivative is finite.
stewart_status check_pose(const stewart_pose &pose, char *msg, size_t size);

Eigen::Matrix3d rotation_from_rpy(double roll, double pitch, double yaw);

// omega = E(pitch, yaw) * (roll_dot, pitch_dot, yaw_dot); alpha = E * angles_ddot + E_dot * angles_dot.
RigidMotion rigid_motion(const stewart_pose &pose);

}  // namespace stewart
