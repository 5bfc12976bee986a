// The classical washout with tilt coordination (classical.hpp).
#include "cueing/classical.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "kinematics/motion.hpp"

namespace stewart {
namespace cueing {

namespace {

FilterDesign second_order(double w, double zeta, int m) {
    FilterDesign d;
    d.n = 2;
    d.m = m;
    d.a[0] = w * w;
    d.a[1] = 2.0 * zeta * w;
    return d;
}

// x = k s^(order - 2) / (D2(s) (s + w_b)^(order - 2)) (f - f_rest): the high-passed specific
// force integrated twice.
FilterDesign translation_design(const stewart_cueing_options &o) {
    const double w = o.translation_frequency, z = o.translation_damping;
    if (o.translation_order == 2) return second_order(w, z, 0);
    const double wb = o.translation_washout_frequency;
    FilterDesign d;
    d.n = 3;
    d.m = 1;
    d.a[0] = w * w * wb;
    d.a[1] = w * w + 2.0 * z * w * wb;
    d.a[2] = 2.0 * z * w + wb;
    return d;
}

// angle = k H_r(s) / s w: k s / D2(s) (order 2) or k / (s + w_r) (order 1).
FilterDesign rotation_design(const stewart_cueing_options &o) {
    if (o.rotation_filter_order == 2)
        return second_order(o.rotation_frequency, o.rotation_damping, 1);
    FilterDesign d;
    d.n = 1;
    d.m = 0;
    d.a[0] = o.rotation_frequency;
    return d;
}

// asin(c) and its first two time derivatives from c, c', c''; at most `max` in magnitude (then
// held there, derivatives 0). True when held; max 0 (no tilt) holds nothing.
bool asin_motion(double c, double c_dot, double c_ddot, double max, double out[3]) {
    if (max == 0.0) {  // no tilt coordination: nothing is held back
        out[0] = out[1] = out[2] = 0.0;
        return false;
    }
    if (std::fabs(c) >= std::sin(max)) {
        out[0] = std::copysign(max, c);
        out[1] = out[2] = 0.0;
        return true;
    }
    const double k = 1.0 / std::sqrt(1.0 - c * c);
    out[0] = std::asin(c);
    out[1] = c_dot * k;
    out[2] = c_ddot * k + c * c_dot * c_dot * k * k * k;
    return false;
}

// The tilt angles the low-passed specific force asks for: R^T (0, 0, g) = (-sin p g,
// sin r cos p g, ...) for R = Rz Ry Rx, so pitch = -asin(f_x / g), roll = asin(f_y / (g cos p)).
// target[0] roll, target[1] pitch, each (angle, rate, acceleration). True if one is at tilt_max.
bool tilt_targets(const ClassicalDesign &d, const double fx[3], const double fy[3],
                  double target[2][3]) {
    const double g = d.gravity;
    double pitch[3];
    bool held = asin_motion(fx[0] / g, fx[1] / g, fx[2] / g, d.tilt_max, pitch);
    for (double &v : pitch) v = -v;
    const double th = pitch[0], th_d = pitch[1], th_dd = pitch[2];
    const double sec = 1.0 / std::cos(th), tan = std::tan(th);
    const double sec_d = sec * tan * th_d;
    const double sec_dd = sec * (tan * tan + sec * sec) * th_d * th_d + sec * tan * th_dd;
    const double c = fy[0] / g * sec;
    const double c_d = fy[1] / g * sec + fy[0] / g * sec_d;
    const double c_dd = fy[2] / g * sec + 2.0 * fy[1] / g * sec_d + fy[0] / g * sec_dd;
    held = asin_motion(c, c_d, c_dd, d.tilt_max, target[0]) || held;
    for (int k = 0; k < 3; ++k) target[1][k] = pitch[k];
    return held;
}

// The angle after the rate limit: the target (with its derivatives) while it moves no faster
// than rate_max, else a slew from the last angle at that rate (linear over the step). True when
// slewing.
bool rate_limited(double last, const double target[3], double rate_max, double dt, double out[3]) {
    const double delta = target[0] - last, reach = rate_max * dt;
    if (std::fabs(delta) <= reach && std::fabs(target[1]) <= rate_max) {
        for (int k = 0; k < 3; ++k) out[k] = target[k];
        return false;
    }
    const double step = std::clamp(delta, -reach, reach);
    out[0] = last + step;
    out[1] = dt > 0.0 ? step / dt : 0.0;
    out[2] = 0.0;
    return true;
}

// The platform turns about the head: its origin moves by (I - R) head, with the derivatives of
// -R head (omega and alpha from the angle rates, kinematics/motion.hpp).
void turn_about_head(const ClassicalDesign &d, Excursion &e) {
    const double r = e.q[3], p = e.q[4], y = e.q[5];
    const double cp = std::cos(p), sp = std::sin(p), cy = std::cos(y), sy = std::sin(y);
    const Eigen::Vector3d head(d.head[0], d.head[1], d.head[2]);
    const Eigen::Vector3d rate(e.q_dot[3], e.q_dot[4], e.q_dot[5]);
    const Eigen::Vector3d accel(e.q_ddot[3], e.q_ddot[4], e.q_ddot[5]);
    const Eigen::Matrix3d E = angle_rate_matrix(cp, sp, cy, sy);
    const Eigen::Vector3d omega = E * rate;
    const Eigen::Vector3d alpha =
        E * accel + angle_rate_matrix_dot(cp, sp, cy, sy, rate[1], rate[2]) * rate;
    const Eigen::Vector3d arm = rotation_from_rpy(r, p, y) * head;
    const Eigen::Vector3d shift = head - arm;
    const Eigen::Vector3d shift_dot = -omega.cross(arm);
    const Eigen::Vector3d shift_ddot = -(alpha.cross(arm) + omega.cross(omega.cross(arm)));
    for (int i = 0; i < 3; ++i) {
        e.q[i] += shift[i];
        e.q_dot[i] += shift_dot[i];
        e.q_ddot[i] += shift_ddot[i];
    }
}

}  // namespace

ClassicalDesign classical_design(const stewart_cueing_options &o, double gravity, bool z_down) {
    ClassicalDesign d;
    d.translation = translation_design(o);
    d.tilt = second_order(o.tilt_frequency, o.tilt_damping, 0);
    d.rotation = rotation_design(o);
    const double wl2 = o.tilt_frequency * o.tilt_frequency;
    const double kt[3] = {o.surge_scale, o.sway_scale, o.heave_scale};
    const double kr[3] = {o.roll_scale, o.pitch_scale, o.yaw_scale};
    for (int i = 0; i < 3; ++i) {
        d.translation_gain[i] = kt[i];
        d.rotation_gain[i] = kr[i];
    }
    d.tilt_gain[0] = kt[0] * wl2;
    d.tilt_gain[1] = kt[1] * wl2;
    d.gravity = gravity;
    d.tilt_max = o.tilt_max;
    d.tilt_rate_max = o.tilt_rate_max;
    // The head is given in the machine's platform frame; a z-down one is the solvers' z-up frame
    // turned by 180 deg about x.
    const double turn = z_down ? -1.0 : 1.0;
    d.head[0] = o.head_x;
    d.head[1] = turn * o.head_y;
    d.head[2] = turn * o.head_z;
    return d;
}

void classical_step(const ClassicalDesign &d, ClassicalSteps &steps, ClassicalState &s,
                    const stewart_cueing_input &in, Excursion &e) {
    const double dt = in.dt;
    if (dt > 0.0 && dt != steps.dt) {
        discretise(d.translation, dt, steps.translation);
        discretise(d.tilt, dt, steps.tilt);
        discretise(d.rotation, dt, steps.rotation);
        steps.dt = dt;
    }
    const double rest[3] = {0.0, 0.0, d.gravity};
    double y[3];
    for (int i = 0; i < 3; ++i) {
        const double u = d.translation_gain[i] * (in.specific_force[i] - rest[i]);
        if (dt > 0.0) advance(d.translation, steps.translation, u, s.translation[i]);
        output(d.translation, s.translation[i], u, y);
        e.q[i] = y[0], e.q_dot[i] = y[1], e.q_ddot[i] = y[2];
        const double w = d.rotation_gain[i] * in.angular_velocity[i];
        if (dt > 0.0) advance(d.rotation, steps.rotation, w, s.rotation[i]);
        output(d.rotation, s.rotation[i], w, y);
        e.q[3 + i] = y[0], e.q_dot[3 + i] = y[1], e.q_ddot[3 + i] = y[2];
    }
    double low[2][3];
    for (int i = 0; i < 2; ++i) {
        const double u = d.tilt_gain[i] * in.specific_force[i];
        if (dt > 0.0) advance(d.tilt, steps.tilt, u, s.tilt[i]);
        output(d.tilt, s.tilt[i], u, low[i]);
    }
    double target[2][3];
    e.tilt_limited = tilt_targets(d, low[0], low[1], target);
    for (int i = 0; i < 2; ++i) {  // roll, pitch
        double tilt[3];
        e.tilt_limited =
            rate_limited(s.tilt_angle[i], target[i], d.tilt_rate_max, dt, tilt) || e.tilt_limited;
        s.tilt_angle[i] = tilt[0];
        e.q[3 + i] += tilt[0], e.q_dot[3 + i] += tilt[1], e.q_ddot[3 + i] += tilt[2];
    }
    turn_about_head(d, e);
}

}  // namespace cueing
}  // namespace stewart
