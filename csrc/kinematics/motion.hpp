// Motion of the platform frame from the pose (x, y, z, roll, pitch, yaw) and its time derivatives,
// with R = Rz(yaw) Ry(pitch) Rx(roll) (docs/model.md).
#pragma once

#include <cmath>

#include <Eigen/Dense>

#include "kinematics/pose_names.hpp"
#include "stewart/stewart.h"

namespace stewart {

// The motion of a rigid body or frame: the platform's, each leg body's (the plant), one struct.
// Templated on the scalar so that linearisation can carry derivatives through the same code.
template <class S>
struct MotionT {
    Eigen::Matrix<S, 3, 1> position, velocity, acceleration;  // of the frame origin, world
    Eigen::Matrix<S, 3, 3> rotation;                          // platform to world
    Eigen::Matrix<S, 3, 1> omega, alpha;  // angular velocity and acceleration, world
};
using Motion = MotionT<double>;

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

// R = Rz(yaw) Ry(pitch) Rx(roll) from the cosines and sines of the three angles.
template <class S>
Eigen::Matrix<S, 3, 3> rotation_from_trig(const S &cr, const S &sr, const S &cp, const S &sp,
                                          const S &cy, const S &sy) {
    Eigen::Matrix<S, 3, 3> R;
    R << cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr, sy * cp, sy * sp * sr + cy * cr,
        sy * sp * cr - cy * sr, -sp, cp * sr, cp * cr;
    return R;
}

// E with omega = E (roll, pitch, yaw)_dot, from cos and sin of pitch and yaw:
// E = [Rz Ry e_x, Rz e_y, e_z].
template <class S>
Eigen::Matrix<S, 3, 3> angle_rate_matrix(const S &cp, const S &sp, const S &cy, const S &sy) {
    Eigen::Matrix<S, 3, 3> E;
    E << cy * cp, -sy, S(0), sy * cp, cy, S(0), -sp, S(0), S(1);
    return E;
}

// dE/dt at pitch and yaw (cos and sin) moving at pitch_rate and yaw_rate: alpha = E angles_ddot +
// E_dot angles_dot.
template <class S>
Eigen::Matrix<S, 3, 3> angle_rate_matrix_dot(const S &cp, const S &sp, const S &cy, const S &sy,
                                             const S &pitch_rate, const S &yaw_rate) {
    const S pd = pitch_rate, yd = yaw_rate;
    Eigen::Matrix<S, 3, 3> E_dot;
    E_dot << -sy * yd * cp - cy * sp * pd, -cy * yd, S(0), cy * yd * cp - sy * sp * pd, -sy * yd,
        S(0), -cp * pd, S(0), S(0);
    return E_dot;
}

// The roll, pitch, yaw of R: pitch in [-pi/2, pi/2], roll and yaw on the branch (2 pi apart)
// nearest to near[0] and near[2].
void angles_of_rotation(const Eigen::Matrix3d &R, const double near[3], double angles[3]);

// Adds to roll and yaw (angles[0], angles[2]) the whole turns that bring each nearest to
// near's: angles_of_rotation's last part, for a caller that has the principal angles already.
inline void nearest_turns(const double near[3], double angles[3]) {
    for (int i : {0, 2}) {
        const double turns = std::round((near[i] - angles[i]) / (2 * M_PI));
        angles[i] += 2 * M_PI * turns;
    }
}

// The inverse: (roll, pitch, yaw) rates from the angular velocity omega (world) at pose angles
// pitch q[4] and yaw q[5]. False at pitch = +-90 deg (|cos pitch| <= min_cos_pitch), where roll
// and yaw rates are not defined.
template <class S>
bool angle_rates_of(const S q[6], const Eigen::Matrix<S, 3, 1> &omega, S out[3],
                    double min_cos_pitch = 1e-12) {
    using std::abs;
    using std::cos;
    using std::sin;
    const S sp = sin(q[4]), cp = cos(q[4]);
    const S sy = sin(q[5]), cy = cos(q[5]);
    if (!(abs(cp) > min_cos_pitch)) return false;
    out[0] = (cy * omega.x() + sy * omega.y()) / cp;
    out[1] = -sy * omega.x() + cy * omega.y();
    out[2] = omega.z() + sp * out[0];
    return true;
}
inline bool angle_rates_of(const double q[6], const Eigen::Vector3d &omega, double out[3],
                           double min_cos_pitch = 1e-12) {
    return angle_rates_of<double>(q, omega, out, min_cos_pitch);
}

// The same rates at the angles of the rotation R (pitch on the principal branch, so cos pitch
// >= 0; roll and yaw on any), read from R instead of the angles' sines and cosines: R's first
// column is (cy cp, sy cp, -sp), so with cp^2 = R00^2 + R10^2
//   roll_dot = (R00 wx + R10 wy) / cp^2,  pitch_dot = (R00 wy - R10 wx) / cp,
//   yaw_dot = wz - R20 roll_dot.
// Equal to the rates from the angles to rounding (tests/unit/test_plant_rhs.cpp); infinite or NaN
// at pitch +-90 degrees.
inline void angle_rates_of_rotation(const Eigen::Matrix3d &R, const Eigen::Vector3d &omega,
                                    double out[3]) {
    const double cos_pitch_squared = R(0, 0) * R(0, 0) + R(1, 0) * R(1, 0);
    out[0] = (R(0, 0) * omega.x() + R(1, 0) * omega.y()) / cos_pitch_squared;
    out[1] = (R(0, 0) * omega.y() - R(1, 0) * omega.x()) / std::sqrt(cos_pitch_squared);
    out[2] = omega.z() - R(2, 0) * out[0];
}

// The cosines and sines of the pose q's three angles (roll, pitch, yaw).
template <class S>
struct AngleTrig {
    S cr, sr, cp, sp, cy, sy;
};
template <class S>
AngleTrig<S> angle_trig(const S q[6]) {
    using std::cos;
    using std::sin;
    return {cos(q[3]), sin(q[3]), cos(q[4]), sin(q[4]), cos(q[5]), sin(q[5])};
}

// The motion of a frame at the pose q with rates q_dot and accelerations q_ddot, from its angles'
// matrices in their rotation order: R, E (omega = E angles_dot) and E_dot at the angle rates;
// omega = E (roll_dot, pitch_dot, yaw_dot), alpha = E angles_ddot + E_dot angles_dot.
template <class S>
MotionT<S> motion_from_matrices(const S q[6], const S q_dot[6], const S q_ddot[6],
                                const Eigen::Matrix<S, 3, 3> &R, const Eigen::Matrix<S, 3, 3> &E,
                                const Eigen::Matrix<S, 3, 3> &E_dot) {
    using Vec = Eigen::Matrix<S, 3, 1>;
    MotionT<S> m;
    m.position = Vec(q[0], q[1], q[2]);
    m.velocity = Vec(q_dot[0], q_dot[1], q_dot[2]);
    m.acceleration = Vec(q_ddot[0], q_ddot[1], q_ddot[2]);
    m.rotation = R;
    const Vec rate(q_dot[3], q_dot[4], q_dot[5]);
    const Vec accel(q_ddot[3], q_ddot[4], q_ddot[5]);
    m.omega = E * rate;
    m.alpha = E * accel + E_dot * rate;
    return m;
}

// The motion of the platform frame at the pose q (the solvers' rotation order, R = Rz Ry Rx;
// rotation_order.hpp has the other).
template <class S>
MotionT<S> motion_of_pose(const S q[6], const S q_dot[6], const S q_ddot[6]) {
    const AngleTrig<S> t = angle_trig(q);
    return motion_from_matrices<S>(q, q_dot, q_ddot,
                                   rotation_from_trig(t.cr, t.sr, t.cp, t.sp, t.cy, t.sy),
                                   angle_rate_matrix(t.cp, t.sp, t.cy, t.sy),
                                   angle_rate_matrix_dot(t.cp, t.sp, t.cy, t.sy, q_dot[4],
                                                         q_dot[5]));
}

// The motion of the platform frame at pose (its q, q_dot, q_ddot).
inline Motion motion_of_pose(const stewart_pose &pose) {
    return motion_of_pose<double>(pose.q, pose.q_dot, pose.q_ddot);
}

}  // namespace stewart
