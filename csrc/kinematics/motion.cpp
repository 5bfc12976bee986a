#include "kinematics/motion.hpp"

#include <cmath>

#include "util/message.hpp"
#include "util/range.hpp"

namespace stewart {

const char *const kPoseNames[6] = {"x", "y", "z", "roll", "pitch", "yaw"};

void angles_of_rotation(const Eigen::Matrix3d &R, const double near[3], double angles[3]) {
    const double sp = -R(2, 0);
    angles[1] = std::asin(sp > 1 ? 1 : sp < -1 ? -1 : sp);
    angles[0] = std::atan2(R(2, 1), R(2, 2));
    angles[2] = std::atan2(R(1, 0), R(0, 0));
    nearest_turns(near, angles);
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

}  // namespace stewart
