#include "kinematics/motion.hpp"

#include <cmath>

#include "util/message.hpp"
#include "util/range.hpp"

namespace stewart {

namespace {

Eigen::Matrix3d rotation_from_trig(double cr, double sr, double cp, double sp, double cy, double sy) {
    Eigen::Matrix3d R;
    R << cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,
         sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,
         -sp,     cp * sr,                cp * cr;
    return R;
}

}  // namespace

const char *const kPoseNames[6] = {"x", "y", "z", "roll", "pitch", "yaw"};

bool angle_rates_of(const double q[6], const Eigen::Vector3d &omega, double out[3],
                    double min_cos_pitch) {
    const double sp = std::sin(q[4]), cp = std::cos(q[4]);
    const double sy = std::sin(q[5]), cy = std::cos(q[5]);
    if (!(std::fabs(cp) > min_cos_pitch)) return false;
    out[0] = (cy * omega.x() + sy * omega.y()) / cp;
    out[1] = -sy * omega.x() + cy * omega.y();
    out[2] = omega.z() + sp * out[0];
    return true;
}

void angles_of_rotation(const Eigen::Matrix3d &R, const double near[3], double angles[3]) {
    const double sp = -R(2, 0);
    angles[1] = std::asin(sp > 1 ? 1 : sp < -1 ? -1 : sp);
    angles[0] = std::atan2(R(2, 1), R(2, 2));
    angles[2] = std::atan2(R(1, 0), R(0, 0));
    for (int i : {0, 2}) {
        const double turns = std::round((near[i] - angles[i]) / (2 * M_PI));
        angles[i] += 2 * M_PI * turns;
    }
}

stewart_status check_pose(const stewart_pose &pose, char *msg, size_t size) {
    const double *rows[3] = {pose.q, pose.q_dot, pose.q_ddot};
    const char *suffix[3] = {"", "_dot", "_ddot"};
    for (int r = 0; r < 3; ++r)
        for (int i = 0; i < 6; ++i)
            if (!std::isfinite(rows[r][i]))
                return set_message(msg, size, STEWART_ERR_ARGUMENT,
                                   "pose input %s%s is %g: it must be finite", kPoseNames[i],
                                   suffix[r], rows[r][i]);
    return STEWART_OK;
}

stewart_status input_out_of_range(const stewart_pose &pose, int first_row, int last_row,
                                  const char *what, char *msg, size_t size) {
    const double *rows[3] = {pose.q, pose.q_dot, pose.q_ddot};
    const char *suffix[3] = {"", "_dot", "_ddot"};
    int row = first_row, index = 0;
    for (int r = first_row; r <= last_row; ++r)
        for (int i = 0; i < 6; ++i)
            if (std::fabs(rows[r][i]) > std::fabs(rows[row][index])) row = r, index = i;
    if (rows[row][index] == 0 && first_row > 0)  // no derivative at all: the position it is
        return input_out_of_range(pose, 0, 0, what, msg, size);
    return set_message(msg, size, STEWART_ERR_ARGUMENT,
                       "pose input %s%s = %s is out of range: it makes the %s overflow",
                       kPoseNames[index], suffix[row], ExactText(rows[row][index]).c_str(), what);
}

Eigen::Matrix3d rotation_from_rpy(double roll, double pitch, double yaw) {
    return rotation_from_trig(std::cos(roll), std::sin(roll), std::cos(pitch), std::sin(pitch),
                              std::cos(yaw), std::sin(yaw));
}

Motion motion_of_pose(const stewart_pose &pose) {
    Motion m;
    m.position = Eigen::Vector3d(pose.q[0], pose.q[1], pose.q[2]);
    m.velocity = Eigen::Vector3d(pose.q_dot[0], pose.q_dot[1], pose.q_dot[2]);
    m.acceleration = Eigen::Vector3d(pose.q_ddot[0], pose.q_ddot[1], pose.q_ddot[2]);
    const double cr = std::cos(pose.q[3]), sr = std::sin(pose.q[3]);
    const double cp = std::cos(pose.q[4]), sp = std::sin(pose.q[4]);
    const double cy = std::cos(pose.q[5]), sy = std::sin(pose.q[5]);
    m.rotation = rotation_from_trig(cr, sr, cp, sp, cy, sy);

    // omega = roll_dot Rz Ry ex + pitch_dot Rz ey + yaw_dot ez.
    const Eigen::Matrix3d E = angle_rate_matrix(cp, sp, cy, sy);
    const Eigen::Vector3d rate(pose.q_dot[3], pose.q_dot[4], pose.q_dot[5]);
    const Eigen::Vector3d accel(pose.q_ddot[3], pose.q_ddot[4], pose.q_ddot[5]);
    const Eigen::Matrix3d E_dot = angle_rate_matrix_dot(cp, sp, cy, sy, rate[1], rate[2]);
    m.omega = E * rate;
    m.alpha = E * accel + E_dot * rate;
    return m;
}

}  // namespace stewart
