// The rotation order of the angles a caller gives and gets (the platform parameter rotation_order,
// docs/geometry.md "Rotation order and frames"): 0 R = Rz(yaw) Ry(pitch) Rx(roll), the solvers'
// own (motion.hpp); 1 R = Rx(roll) Ry(pitch) Rz(yaw), rotations about the moving x, then y, then z
// (PI's U -> V -> W). Rates and accelerations are the time derivatives of the angles of either.
// Order 0 calls motion.hpp's functions themselves, so that its results are theirs bit for bit.
#pragma once

#include <cmath>

#include <Eigen/Dense>

#include "kinematics/motion.hpp"

namespace stewart {

constexpr int kRotationZYX = 0;  // Rz Ry Rx
constexpr int kRotationXYZ = 1;  // Rx Ry Rz

// R = Rx(roll) Ry(pitch) Rz(yaw) from the cosines and sines of the three angles.
template <class S>
Eigen::Matrix<S, 3, 3> rotation_xyz_from_trig(const S &cr, const S &sr, const S &cp, const S &sp,
                                              const S &cy, const S &sy) {
    Eigen::Matrix<S, 3, 3> R;
    R << cp * cy, -cp * sy, sp, cr * sy + sr * sp * cy, cr * cy - sr * sp * sy, -sr * cp,
        sr * sy - cr * sp * cy, sr * cy + cr * sp * sy, cr * cp;
    return R;
}

// E with omega = E (roll, pitch, yaw)_dot for R = Rx Ry Rz: E = [e_x, Rx e_y, Rx Ry e_z].
template <class S>
Eigen::Matrix<S, 3, 3> angle_rate_matrix_xyz(const S &cr, const S &sr, const S &cp, const S &sp) {
    Eigen::Matrix<S, 3, 3> E;
    E << S(1), S(0), sp, S(0), cr, -sr * cp, S(0), sr, cr * cp;
    return E;
}

// dE/dt for R = Rx Ry Rz at roll and pitch moving at roll_rate and pitch_rate.
template <class S>
Eigen::Matrix<S, 3, 3> angle_rate_matrix_xyz_dot(const S &cr, const S &sr, const S &cp, const S &sp,
                                                 const S &roll_rate, const S &pitch_rate) {
    const S rd = roll_rate, pd = pitch_rate;
    Eigen::Matrix<S, 3, 3> E_dot;
    E_dot << S(0), S(0), cp * pd, S(0), -sr * rd, -cr * cp * rd + sr * sp * pd, S(0), cr * rd,
        -sr * cp * rd - cr * sp * pd;
    return E_dot;
}

// The motion of a frame at the pose q (angles in `order`) with rates q_dot and accelerations
// q_ddot.
template <class S>
MotionT<S> motion_of_pose_in_order(int order, const S q[6], const S q_dot[6], const S q_ddot[6]) {
    if (order != kRotationXYZ) return motion_of_pose<S>(q, q_dot, q_ddot);
    const AngleTrig<S> t = angle_trig(q);
    return motion_from_matrices<S>(q, q_dot, q_ddot,
                                   rotation_xyz_from_trig(t.cr, t.sr, t.cp, t.sp, t.cy, t.sy),
                                   angle_rate_matrix_xyz(t.cr, t.sr, t.cp, t.sp),
                                   angle_rate_matrix_xyz_dot(t.cr, t.sr, t.cp, t.sp, q_dot[3],
                                                             q_dot[4]));
}

inline Motion motion_of_pose_in_order(int order, const stewart_pose &pose) {
    return motion_of_pose_in_order<double>(order, pose.q, pose.q_dot, pose.q_ddot);
}

// (roll, pitch, yaw) rates (in `order`) from the angular velocity omega at the pose angles of q.
// False at pitch +-90 deg (|cos pitch| <= min_cos_pitch), where roll and yaw rates are not
// defined, in either order.
template <class S>
bool angle_rates_in_order(int order, const S q[6], const Eigen::Matrix<S, 3, 1> &omega, S out[3],
                          double min_cos_pitch = 1e-12) {
    if (order != kRotationXYZ) return angle_rates_of<S>(q, omega, out, min_cos_pitch);
    using std::abs;
    using std::cos;
    using std::sin;
    const S sr = sin(q[3]), cr = cos(q[3]);
    const S sp = sin(q[4]), cp = cos(q[4]);
    if (!(abs(cp) > min_cos_pitch)) return false;
    // Rows of E^-1 (E = [e_x, Rx e_y, Rx Ry e_z], det E = cos pitch).
    out[1] = cr * omega.y() + sr * omega.z();
    out[2] = (cr * omega.z() - sr * omega.y()) / cp;
    out[0] = omega.x() - sp * out[2];
    return true;
}

// The part of alpha that the angle rates give with zero angle accelerations: E_dot angles_dot.
template <class S>
Eigen::Matrix<S, 3, 1> angle_rate_bias_in_order(int order, const S q[6], const S rate[3]) {
    using std::cos;
    using std::sin;
    const Eigen::Matrix<S, 3, 1> r(rate[0], rate[1], rate[2]);
    if (order != kRotationXYZ)
        return angle_rate_matrix_dot<S>(cos(q[4]), sin(q[4]), cos(q[5]), sin(q[5]), rate[1],
                                        rate[2]) *
               r;
    return angle_rate_matrix_xyz_dot<S>(cos(q[3]), sin(q[3]), cos(q[4]), sin(q[4]), rate[0],
                                        rate[1]) *
           r;
}

// The angles (in `order`) of R: pitch in [-pi/2, pi/2], roll and yaw on the branch nearest to
// near[0] and near[2].
void angles_of_rotation_in_order(int order, const Eigen::Matrix3d &R, const double near[3],
                                 double angles[3]);

// The direction (unit, in the pose's frame) about which the frame turns when angle `axis` (3 roll,
// 4 pitch, 5 yaw) of the pose q moves alone: E's column.
Eigen::Vector3d angle_axis_in_order(int order, const double q[6], int axis);

}  // namespace stewart
