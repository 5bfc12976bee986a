#include "kinematics/geometry_jacobian.hpp"

#include <cmath>

#include "kinematics/motion.hpp"
#include "util/message.hpp"

namespace stewart {

namespace {

// A frame given as (x, y, z, roll, pitch, yaw): its origin, rotation R = Rz Ry Rx and the matrix
// E that maps its angle rates to the angular velocity in the parent frame (motion.hpp).
struct Frame {
    Eigen::Vector3d origin;
    Eigen::Matrix3d rotation, rate;
};

Frame frame_of(const double q[6]) {
    Frame f;
    f.origin = Eigen::Vector3d(q[0], q[1], q[2]);
    f.rotation = rotation_from_rpy(q[3], q[4], q[5]);
    f.rate = angle_rate_matrix(std::cos(q[4]), std::sin(q[4]), std::cos(q[5]), std::sin(q[5]));
    return f;
}

}  // namespace

stewart_status geometry_jacobian(const CalibrationGeometry &g, const double pose[6],
                                 GeometryJacobian &out, char *msg, size_t size) {
    const Frame tool = frame_of(g.tool_frame.data()), user = frame_of(g.user_frame.data());
    const Frame measured = frame_of(pose);
    // The platform in the base frame: T_base_platform = T_user · T_measured · T_tool⁻¹.
    const Eigen::Matrix3d tool_to_user = measured.rotation * tool.rotation.transpose();
    const Eigen::Matrix3d platform_to_base = user.rotation * tool_to_user;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Eigen::Vector3d from_tool = g.platform_points.col(k) - tool.origin;  // platform
        const Eigen::Vector3d arm = tool_to_user * from_tool;  // tool origin to joint, user
        const Eigen::Vector3d in_user = measured.origin + arm;
        const Eigen::Vector3d from_user = user.rotation * in_user;  // user origin to joint, base
        const Eigen::Vector3d d = user.origin + from_user - g.base_points.col(k);
        const double L = d.norm();
        if (!(L > g.min_length)) return check_leg_length(k, L, g.min_length, msg, size);
        const Eigen::Vector3d n = d / L;  // base frame
        const Eigen::Vector3d n_platform = platform_to_base.transpose() * n;
        const Eigen::Vector3d n_user = user.rotation.transpose() * n;
        out.length[k] = L;
        out.reading[k] = L - g.length_offset[k];
        out.base_joint.row(k) = -n.transpose();
        out.platform_joint.row(k) = n_platform.transpose();
        out.length_offset[k] = -1.0;
        // A small rotation w (parent frame) of a frame moves a point r of it by w x r, so
        // dL = n . (w x r) = w . (r x n), with w = E d(angles).
        out.tool_frame.block<1, 3>(k, 0) = -n_platform.transpose();
        out.tool_frame.block<1, 3>(k, 3) = n_platform.cross(from_tool).transpose() * tool.rate;
        out.user_frame.block<1, 3>(k, 0) = n.transpose();
        out.user_frame.block<1, 3>(k, 3) = from_user.cross(n).transpose() * user.rate;
        out.pose.block<1, 3>(k, 0) = n_user.transpose();
        out.pose.block<1, 3>(k, 3) = arm.cross(n_user).transpose() * measured.rate;
    }
    return STEWART_OK;
}

}  // namespace stewart
