// The leg classes of the limit check (stewart/stewart_limits.h): each leg's speed, acceleration
// and jerk from the pose's time derivatives, and its force, against leg_speed_max,
// leg_accel_max, leg_jerk_max and leg_force_max.
#include <algorithm>
#include <cmath>

#include "kinematics/closed_form.hpp"
#include "kinematics/frames.hpp"
#include "kinematics/motion.hpp"
#include "limits/limit_check.hpp"
#include "util/message.hpp"

namespace stewart {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// d^n/dt^n of the elementary rotation exp(theta K) about axis `axis` (0 x, 1 y, 2 z), n = 0..3,
// for theta moving with rates d[0..2] (first to third derivative): exp(theta K) times
// 1, K d1, K^2 d1^2 + K d2, K^3 d1^3 + 3 K^2 d1 d2 + K d3.
void elementary_derivatives(int axis, double theta, const double d[3], Matrix3d out[4]) {
    Matrix3d K = Matrix3d::Zero();
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    K(b, a) = 1.0;
    K(a, b) = -1.0;
    const Matrix3d F = Eigen::AngleAxisd(theta, Vector3d::Unit(axis)).toRotationMatrix();
    const Matrix3d K2 = K * K;
    out[0] = F;
    out[1] = F * K * d[0];
    out[2] = F * (K2 * (d[0] * d[0]) + K * d[1]);
    out[3] = F * (K2 * K * (d[0] * d[0] * d[0]) + K2 * (3.0 * d[0] * d[1]) + K * d[2]);
}

// The rotation of the caller's angles (rotation order `order`) and its first three time
// derivatives: a product of three elementary rotations, differentiated by Leibniz' rule.
void rotation_derivatives(int order, const stewart_limits_input &in, Matrix3d R[4]) {
    // Order 0: Rz(yaw) Ry(pitch) Rx(roll); order 1: Rx(roll) Ry(pitch) Rz(yaw).
    const int angles[3] = {order == kRotationXYZ ? 3 : 5, 4, order == kRotationXYZ ? 5 : 3};
    Matrix3d F[3][4];
    for (int f = 0; f < 3; ++f) {
        const int i = angles[f];
        const double d[3] = {in.q_dot[i], in.q_ddot[i], in.q_dddot[i]};
        elementary_derivatives(i == 3 ? 0 : i == 4 ? 1 : 2, in.q[i], d, F[f]);
    }
    static const int kFactorial[4] = {1, 1, 2, 6};
    for (int n = 0; n < 4; ++n) {
        R[n].setZero();
        for (int a = 0; a <= n; ++a)
            for (int b = 0; a + b <= n; ++b) {
                const int c = n - a - b;
                const double multinomial =
                    double(kFactorial[n]) / (kFactorial[a] * kFactorial[b] * kFactorial[c]);
                R[n] += multinomial * F[0][a] * F[1][b] * F[2][c];
            }
    }
}

// Each leg's third length derivative: with l = p + R (b - tool origin) - a in the base frame
// (the frames' constant turns and offsets applied to the caller's pose) and L = |l|,
// L L''' = 3 (l' . l'' - L' L'') + l . l''' (from differentiating L^2 = l . l three times).
bool leg_jerks(const LimitConstants &c, const stewart_limits_input &in, double jerk[STEWART_LEGS]) {
    const Frames &f = c.frames;
    Matrix3d R[4];
    rotation_derivatives(f.identity ? kRotationZYX : f.rotation_order, in, R);
    const Vector3d p[4] = {Eigen::Map<const Vector3d>(in.q), Eigen::Map<const Vector3d>(in.q_dot),
                           Eigen::Map<const Vector3d>(in.q_ddot),
                           Eigen::Map<const Vector3d>(in.q_dddot)};
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Vector3d arm =
            f.tool_rotation.transpose() * (c.geometry.platform_points.col(k) - f.tool_origin);
        Vector3d l[4];
        for (int n = 0; n < 4; ++n) l[n] = f.user_rotation * (p[n] + R[n] * arm);
        l[0] += f.user_origin - c.geometry.base_points.col(k);
        const double L = l[0].norm();
        if (!(L > c.geometry.min_length)) return false;
        const double rate = l[0].dot(l[1]) / L;
        const double accel = (l[1].squaredNorm() + l[0].dot(l[2]) - rate * rate) / L;
        jerk[k] = (3.0 * (l[1].dot(l[2]) - rate * accel) + l[0].dot(l[3])) / L;
    }
    return true;
}

// One leg class from the legs' values: margin limit - |value| per leg, the smallest and its leg.
void leg_class(const LimitConstants &c, int limit_class, const double value[STEWART_LEGS],
               stewart_limits_output &out) {
    const int index = limit_class - 1;
    const double *limit = c.leg_limit[limit_class - STEWART_LIMIT_LEG_SPEED];
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const double m = std::isinf(limit[k]) ? HUGE_VAL : limit[k] - std::fabs(value[k]);
        out.leg_margin[index][k] = m;
        if (m < out.margin[index]) {
            out.margin[index] = m;
            out.leg[index] = k + 1;
        }
    }
}

}  // namespace

stewart_status check_leg_limits(const LimitConstants &c, const stewart_limits_input &in,
                                stewart_limits_output &out, char *msg, size_t size) {
    for (int i = STEWART_LIMIT_LEG_SPEED - 1; i < STEWART_LIMIT_LEG_FORCE; ++i) {
        out.margin[i] = HUGE_VAL;
        out.leg[i] = out.other_leg[i] = 0;
        std::fill(out.leg_margin[i], out.leg_margin[i] + STEWART_LEGS, HUGE_VAL);
    }
    if (in.derivatives >= 1) {
        // The inverse's own route to the legs' rates and accelerations, so that both agree bit
        // for bit.
        stewart_pose pose{};
        std::copy(in.q, in.q + 6, pose.q);
        std::copy(in.q_dot, in.q_dot + 6, pose.q_dot);
        if (in.derivatives >= 2) std::copy(in.q_ddot, in.q_ddot + 6, pose.q_ddot);
        const Motion motion =
            c.frames.identity ? motion_of_pose(pose) : platform_motion_of_pose(c.frames, pose);
        LegKinematics legs;
        const stewart_status s = leg_kinematics(c.geometry, motion, legs, msg, size);
        if (s != STEWART_OK) return s;
        double jerk[STEWART_LEGS] = {0};
        if (in.derivatives >= 3 && !leg_jerks(c, in, jerk))
            return set_message(msg, size, STEWART_ERR_UNREACHABLE,
                               "a leg has zero length at this pose: its jerk is not defined");
        const bool finite =
            legs.rate.allFinite() && legs.accel.allFinite() &&
            std::all_of(jerk, jerk + STEWART_LEGS, [](double v) { return std::isfinite(v); });
        if (!finite)
            return set_message(msg, size, STEWART_ERR_ARGUMENT,
                               "the legs' rates overflow at these pose derivatives: give "
                               "derivatives of the pose's own scale");
        leg_class(c, STEWART_LIMIT_LEG_SPEED, legs.rate.data(), out);
        if (in.derivatives >= 2) leg_class(c, STEWART_LIMIT_LEG_ACCEL, legs.accel.data(), out);
        if (in.derivatives >= 3) leg_class(c, STEWART_LIMIT_LEG_JERK, jerk, out);
    }
    if (in.has_force) leg_class(c, STEWART_LIMIT_LEG_FORCE, in.force, out);
    classify_margins(c, out);
    return STEWART_OK;
}

}  // namespace stewart
