// Motion of the platform frame from the pose (x, y, z, roll, pitch, yaw) and its time derivatives,
// with R = Rz(yaw) Ry(pitch) Rx(roll) (docs/model.md).
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

// STEWART_ERR_ARGUMENT naming the pose input of largest magnitude in rows first_row..last_row
// (0 pose, 1 rates, 2 accelerations; the position if every derivative there is 0) and its value:
// the input that made `what` overflow.
stewart_status input_out_of_range(const stewart_pose &pose, int first_row, int last_row,
                                  const char *what, char *msg, size_t size);

Eigen::Matrix3d rotation_from_rpy(double roll, double pitch, double yaw);

// omega = E(pitch, yaw) * (roll_dot, pitch_dot, yaw_dot); alpha = E * angles_ddot + E_dot * angles_dot.
RigidMotion rigid_motion(const stewart_pose &pose);

}  // namespace stewart
