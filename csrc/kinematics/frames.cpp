#include "kinematics/frames.hpp"

#include <cstring>

namespace stewart {

namespace {

// The pose of a frame moving with m: pitch in [-pi/2, pi/2], roll and yaw nearest to near; rates
// (derivatives >= 1) and accelerations (2) through E^-1, the other rows 0. False at pitch +-90
// deg when rates are wanted.
bool pose_of_motion(const Motion &m, const double near[3], int derivatives, stewart_pose &pose,
                    double min_cos_pitch) {
    stewart_pose out{};
    for (int i = 0; i < 3; ++i) out.q[i] = m.position[i];
    angles_of_rotation(m.rotation, near, out.q + 3);
    if (derivatives >= 1) {
        if (!angle_rates_of(out.q, m.omega, out.q_dot + 3, min_cos_pitch)) return false;
        for (int i = 0; i < 3; ++i) out.q_dot[i] = m.velocity[i];
    }
    if (derivatives >= 2) {
        // alpha = E angles_ddot + E_dot angles_dot.
        const Eigen::Matrix3d E_dot = angle_rate_matrix_dot(
            std::cos(out.q[4]), std::sin(out.q[4]), std::cos(out.q[5]), std::sin(out.q[5]),
            out.q_dot[4], out.q_dot[5]);
        const Eigen::Vector3d rates(out.q_dot[3], out.q_dot[4], out.q_dot[5]);
        angle_rates_of(out.q, m.alpha - E_dot * rates, out.q_ddot + 3, min_cos_pitch);
        for (int i = 0; i < 3; ++i) out.q_ddot[i] = m.acceleration[i];
    }
    pose = out;
    return true;
}

// The pose of a frame that moves with m and turns as `angles` (a pose whose angles and their
// derivatives are the frame's already: no frame is rotated).
void pose_with_angles(const Motion &m, const stewart_pose &angles, int derivatives,
                      stewart_pose &pose) {
    stewart_pose out{};
    for (int i = 0; i < 3; ++i) {
        out.q[i] = m.position[i];
        out.q[3 + i] = angles.q[3 + i];
        if (derivatives >= 1) out.q_dot[i] = m.velocity[i], out.q_dot[3 + i] = angles.q_dot[3 + i];
        if (derivatives >= 2)
            out.q_ddot[i] = m.acceleration[i], out.q_ddot[3 + i] = angles.q_ddot[3 + i];
    }
    pose = out;
}

}  // namespace

Frames frames_of(const stewart_params &p) {
    Frames f;
    f.identity = true;
    f.turns = false;
    for (int i = 0; i < 6; ++i) {
        if (p.tool_frame[i] != 0 || p.user_frame[i] != 0) f.identity = false;
        if (i >= 3 && (p.tool_frame[i] != 0 || p.user_frame[i] != 0)) f.turns = true;
    }
    const double *u = p.user_frame, *t = p.tool_frame;
    f.user_origin = Eigen::Vector3d(u[0], u[1], u[2]);
    f.user_rotation = rotation_from_rpy(u[3], u[4], u[5]);
    f.tool_origin = Eigen::Vector3d(t[0], t[1], t[2]);
    f.tool_rotation = rotation_from_rpy(t[3], t[4], t[5]);
    // At zero platform rotation the tool turns by user^T tool; its angles on the branch of the
    // frames' own (exact for turns about z alone).
    const double near[3] = {t[3] - u[3], t[4] - u[4], t[5] - u[5]};
    angles_of_rotation(f.user_rotation.transpose() * f.tool_rotation, near, f.angle_shift);
    return f;
}

template Motion platform_motion<double>(const Frames &f, const Motion &tool);
template Motion tool_motion<double>(const Frames &f, const Motion &platform);

bool motion_finite(const Motion &m) {
    return m.position.allFinite() && m.velocity.allFinite() && m.acceleration.allFinite() &&
           m.rotation.allFinite() && m.omega.allFinite() && m.alpha.allFinite();
}

bool tool_pose(const Frames &f, const stewart_pose &platform, int derivatives, stewart_pose &tool,
               double min_cos_pitch) {
    const Motion m = tool_motion(f, motion_of_pose(platform));
    if (!f.turns) {
        pose_with_angles(m, platform, derivatives, tool);
        return true;
    }
    double near[3];
    for (int i = 0; i < 3; ++i) near[i] = platform.q[3 + i] + f.angle_shift[i];
    return pose_of_motion(m, near, derivatives, tool, min_cos_pitch);
}

bool platform_pose(const Frames &f, const double tool_q[6], const double *tool_rate, double q[6],
                   double *rate, double min_cos_pitch) {
    stewart_pose given{};
    std::memcpy(given.q, tool_q, sizeof given.q);
    if (tool_rate) std::memcpy(given.q_dot, tool_rate, sizeof given.q_dot);
    const Motion m = platform_motion(f, motion_of_pose(given));
    const int derivatives = tool_rate ? 1 : 0;
    stewart_pose out;
    if (!f.turns) {
        pose_with_angles(m, given, derivatives, out);
    } else {
        double near[3];
        for (int i = 0; i < 3; ++i) near[i] = tool_q[3 + i] - f.angle_shift[i];
        if (!pose_of_motion(m, near, derivatives, out, min_cos_pitch)) return false;
    }
    std::memcpy(q, out.q, sizeof out.q);
    if (rate) std::memcpy(rate, out.q_dot, sizeof out.q_dot);
    return true;
}

}  // namespace stewart
