#include "kinematics/frames.hpp"

#include <cstring>

namespace stewart {

namespace {

// The pose of a frame moving with m, angles in `order`: pitch in [-pi/2, pi/2], roll and yaw
// nearest to near; rates (derivatives >= 1) and accelerations (2) through E^-1, the other rows 0.
// False at pitch +-90 deg when rates are wanted.
bool pose_of_motion(const Motion &m, int order, const double near[3], int derivatives,
                    stewart_pose &pose, double min_cos_pitch) {
    stewart_pose out{};
    for (int i = 0; i < 3; ++i) out.q[i] = m.position[i];
    angles_of_rotation_in_order(order, m.rotation, near, out.q + 3);
    if (derivatives >= 1) {
        if (!angle_rates_in_order(order, out.q, m.omega, out.q_dot + 3, min_cos_pitch))
            return false;
        for (int i = 0; i < 3; ++i) out.q_dot[i] = m.velocity[i];
    }
    if (derivatives >= 2) {
        // alpha = E angles_ddot + E_dot angles_dot.
        const Eigen::Vector3d bias = angle_rate_bias_in_order(order, out.q, out.q_dot + 3);
        angle_rates_in_order(order, out.q, Eigen::Vector3d(m.alpha - bias), out.q_ddot + 3,
                             min_cos_pitch);
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

// The rotation of angles (roll, pitch, yaw) in `order`.
Eigen::Matrix3d rotation_in_order(int order, const double angles[3]) {
    if (order != kRotationXYZ) return rotation_from_rpy(angles[0], angles[1], angles[2]);
    using std::cos;
    using std::sin;
    return rotation_xyz_from_trig(cos(angles[0]), sin(angles[0]), cos(angles[1]), sin(angles[1]),
                                  cos(angles[2]), sin(angles[2]));
}

// (x, y, z) -> (x, -y, -z): the 180 deg turn about x from a z-down frame to its z-up twin.
void turn_about_x(double *v, int vectors) {
    for (int k = 0; k < vectors; ++k) v[3 * k + 1] = -v[3 * k + 1], v[3 * k + 2] = -v[3 * k + 2];
}

}  // namespace

Frames frames_of(const stewart_params &p) {
    Frames f;
    f.rotation_order = p.rotation_order == 1.0 ? kRotationXYZ : kRotationZYX;
    f.z_down = p.frame_convention == 1.0;
    f.identity = f.rotation_order == kRotationZYX && !f.z_down;
    f.turns = !f.identity;
    for (int i = 0; i < 6; ++i) {
        if (p.tool_frame[i] != 0 || p.user_frame[i] != 0) f.identity = false;
        if (i >= 3 && (p.tool_frame[i] != 0 || p.user_frame[i] != 0)) f.turns = true;
    }
    const double *u = p.user_frame, *t = p.tool_frame;
    const Eigen::Matrix3d user_turn = rotation_in_order(f.rotation_order, u + 3);
    const Eigen::Matrix3d tool_turn = rotation_in_order(f.rotation_order, t + 3);
    f.user_origin = Eigen::Vector3d(u[0], u[1], u[2]);
    f.user_rotation = user_turn;
    f.tool_origin = Eigen::Vector3d(t[0], t[1], t[2]);
    f.tool_rotation = tool_turn;
    if (f.z_down) {
        // The base and platform frames are the solvers' turned by 180 deg about x (F = diag(1,
        // -1, -1), its own inverse), and the user and tool frames are given in them: F u, F R_u,
        // F t, F R_t (negations: exact).
        for (Eigen::Vector3d *origin : {&f.user_origin, &f.tool_origin}) origin->tail<2>() *= -1.0;
        for (Eigen::Matrix3d *turn : {&f.user_rotation, &f.tool_rotation})
            turn->bottomRows<2>() *= -1.0;
        f.angle_sign[1] = f.angle_sign[2] = -1;
    }
    // At zero platform rotation the tool turns by user^T tool (F cancels); its angles on the
    // branch of the frames' own (exact for turns about z alone).
    const double near[3] = {t[3] - u[3], t[4] - u[4], t[5] - u[5]};
    angles_of_rotation_in_order(f.rotation_order, user_turn.transpose() * tool_turn, near,
                                f.angle_shift);
    return f;
}

stewart_params params_in_solver_frames(const stewart_params &p) {
    stewart_params s = p;
    if (p.frame_convention != 1.0) return s;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        s.base_angle[k] = -p.base_angle[k];  // (cos b, sin b, 0) -> (cos -b, sin -b, 0)
        s.platform_angle[k] = -p.platform_angle[k];
    }
    for (double *v : {s.base_joint, s.platform_joint, s.base_cardan_axis, s.platform_cardan_axis,
                      s.base_joint_neutral, s.platform_joint_neutral})
        turn_about_x(v, STEWART_LEGS);
    turn_about_x(s.platform_com, 1);
    turn_about_x(s.payload_com, 1);
    return s;
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
    for (int i = 0; i < 3; ++i) near[i] = f.angle_sign[i] * platform.q[3 + i] + f.angle_shift[i];
    return pose_of_motion(m, f.rotation_order, near, derivatives, tool, min_cos_pitch);
}

bool platform_pose(const Frames &f, const double tool_q[6], const double *tool_rate, double q[6],
                   double *rate, double min_cos_pitch) {
    stewart_pose given{};
    std::memcpy(given.q, tool_q, sizeof given.q);
    if (tool_rate) std::memcpy(given.q_dot, tool_rate, sizeof given.q_dot);
    const Motion m = platform_motion_of_pose(f, given);
    const int derivatives = tool_rate ? 1 : 0;
    stewart_pose out;
    if (!f.turns) {
        pose_with_angles(m, given, derivatives, out);
    } else {
        double near[3];
        for (int i = 0; i < 3; ++i) near[i] = f.angle_sign[i] * (tool_q[3 + i] - f.angle_shift[i]);
        if (!pose_of_motion(m, kRotationZYX, near, derivatives, out, min_cos_pitch)) return false;
    }
    std::memcpy(q, out.q, sizeof out.q);
    if (rate) std::memcpy(rate, out.q_dot, sizeof out.q_dot);
    return true;
}

void angles_of_rotation_in_order(int order, const Eigen::Matrix3d &R, const double near[3],
                                 double angles[3]) {
    if (order != kRotationXYZ) return angles_of_rotation(R, near, angles);
    // R = Rx Ry Rz: first row (cp cy, -cp sy, sp), last column (sp, -sr cp, cr cp).
    const double sp = R(0, 2);
    angles[1] = std::asin(sp > 1 ? 1 : sp < -1 ? -1 : sp);
    angles[0] = std::atan2(-R(1, 2), R(2, 2));
    angles[2] = std::atan2(-R(0, 1), R(0, 0));
    nearest_turns(near, angles);
}

Eigen::Vector3d angle_axis_in_order(int order, const double q[6], int axis) {
    if (order != kRotationXYZ) {  // E = [Rz Ry e_x, Rz e_y, e_z]
        if (axis == 5) return Eigen::Vector3d::UnitZ();
        if (axis == 4) return rotation_from_rpy(0.0, 0.0, q[5]).col(1);
        return rotation_from_rpy(0.0, q[4], q[5]).col(0);
    }
    // E = [e_x, Rx e_y, Rx Ry e_z]
    if (axis == 3) return Eigen::Vector3d::UnitX();
    const double cr = std::cos(q[3]), sr = std::sin(q[3]);
    if (axis == 4) return Eigen::Vector3d(0.0, cr, sr);
    const double cp = std::cos(q[4]), sp = std::sin(q[4]);
    return Eigen::Vector3d(sp, -sr * cp, cr * cp);
}

}  // namespace stewart
