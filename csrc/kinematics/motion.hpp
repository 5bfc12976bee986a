// Motion of the platform frame from the pose (x, y, z, roll, pitch, yaw) and its time derivatives,
// with R = Rz(yaw) Ry(pitch) Rx(roll) (docs/model.md).
#pragma once

#include <Eigen/Dense>

#include "kinematics/pose_names.hpp"
#include "stewart/stewart.h"

namespace stewart {

// The motion of a rigid body or frame: the platform's, each leg body's (the plant), one struct.
struct Motion {
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

// R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Matrix3d rotation_from_rpy(double roll, double pitch, double yaw);

// E with omega = E (roll, pitch, yaw)_dot, from cos and sin of pitch and yaw:
// E = [Rz Ry e_x, Rz e_y, e_z].
inline Eigen::Matrix3d angle_rate_matrix(double cp, double sp, double cy, double sy) {
    Eigen::Matrix3d E;
    E << cy * cp, -sy, 0,
         sy * cp,  cy, 0,
         -sp,      0,  1;
    return E;
}

// dE/dt at pitch and yaw (cos and sin) moving at pitch_rate and yaw_rate: alpha = E angles_ddot +
// E_dot angles_dot.
inline Eigen::Matrix3d angle_rate_matrix_dot(double cp, double sp, double cy, double sy,
                                             double pitch_rate, double yaw_rate) {
    const double pd = pitch_rate, yd = yaw_rate;
    Eigen::Matrix3d E_dot;
    E_dot << -sy * yd * cp - cy * sp * pd, -cy * yd, 0,
              cy * yd * cp - sy * sp * pd, -sy * yd, 0,
             -cp * pd,                      0,       0;
    return E_dot;
}

// The roll, pitch, yaw of R: pitch in [-pi/2, pi/2], roll and yaw on the branch (2 pi apart)
// nearest to near[0] and near[2].
void angles_of_rotation(const Eigen::Matrix3d &R, const double near[3], double angles[3]);

// The inverse: (roll, pitch, yaw) rates from the angular velocity omega (world) at pose angles
// pitch q[4] and yaw q[5]. False at pitch = +-90 deg (|cos pitch| <= min_cos_pitch), where roll
// and yaw rates are not defined.
bool angle_rates_of(const double q[6], const Eigen::Vector3d &omega, double out[3],
                    double min_cos_pitch = 1e-12);

// The motion of the platform frame at pose; omega = E (roll_dot, pitch_dot, yaw_dot),
// alpha = E angles_ddot + E_dot angles_dot.
Motion motion_of_pose(const stewart_pose &pose);

}  // namespace stewart
