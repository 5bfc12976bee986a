#include "platform/forward_dynamics_bodies.hpp"

namespace stewart {
namespace fd {

namespace {

// Motion of a unit axis n = d / |d| from d and its first two rates.
struct AxisRates {
    Vec3 n_dot, n_ddot;
};

AxisRates axis_rates(const LegConfiguration &c, const Vec3 &d_dot, const Vec3 &d_ddot) {
    AxisRates r;
    const Vec3 &n = c.n;
    const double L_dot = n.dot(d_dot);
    r.n_dot = (d_dot - L_dot * n) * c.inverse_length;
    // L n = d twice differentiated, with L_ddot = n.d_ddot + L |n_dot|^2.
    const double L_ddot = n.dot(d_ddot) + c.length * r.n_dot.squaredNorm();
    r.n_ddot = (d_ddot - L_ddot * n - 2.0 * L_dot * r.n_dot) * c.inverse_length;
    return r;
}

// Angular velocity and acceleration of the frame (x, y = n x x, z = n), x = (s x n)/|s x n|, from
// the rates of n and s: omega = 1/2 sum a_i x a_i_dot, alpha = 1/2 sum a_i x a_i_ddot for the
// columns a_i of any orthonormal frame.
void frame_rates(const Vec3 &n, const AxisRates &nr, const Vec3 &s, const Vec3 &s_dot,
                 const Vec3 &s_ddot, const Vec3 &x, double mu, Vec3 &omega, Vec3 &alpha) {
    const double inv_mu = 1.0 / mu;
    const Vec3 u_dot = s_dot.cross(n) + s.cross(nr.n_dot);
    const Vec3 u_ddot = s_ddot.cross(n) + 2.0 * s_dot.cross(nr.n_dot) + s.cross(nr.n_ddot);
    const double mu_dot = x.dot(u_dot);
    const Vec3 x_dot = (u_dot - mu_dot * x) * inv_mu;
    const double mu_ddot = x.dot(u_ddot) + mu * x_dot.squaredNorm();
    const Vec3 x_ddot = (u_ddot - mu_ddot * x - 2.0 * mu_dot * x_dot) * inv_mu;
    const Vec3 y = n.cross(x);
    const Vec3 y_dot = nr.n_dot.cross(x) + n.cross(x_dot);
    const Vec3 y_ddot = nr.n_ddot.cross(x) + 2.0 * nr.n_dot.cross(x_dot) + n.cross(x_ddot);
    omega = 0.5 * (x.cross(x_dot) + y.cross(y_dot) + n.cross(nr.n_dot));
    alpha = 0.5 * (x.cross(x_ddot) + y.cross(y_ddot) + n.cross(nr.n_ddot));
}

Mat3 leg_axes(const Vec3 &x, const Vec3 &n) {
    Mat3 A;
    A.col(0) = x;
    A.col(1) = n.cross(x);
    A.col(2) = n;
    return A;
}

}  // namespace

LegFault leg_configuration(const LegParameters &p, int k, const Vec3 &position,
                           const Mat3 &rotation, LegConfiguration &c) {
    c.arm.noalias() = rotation * p.platform_points.col(k);
    const Vec3 d = position + c.arm - p.base_points.col(k);
    c.length = d.norm();
    if (!(c.length > p.min_length)) return LegFault::ZeroLength;
    c.inverse_length = 1.0 / c.length;
    c.n = d * c.inverse_length;
    c.piston_arm.noalias() = rotation * p.platform_arm.col(k);
    const Vec3 uc = p.base_arm.col(k).cross(c.n), up = c.piston_arm.cross(c.n);
    c.cylinder_sin = uc.norm();
    c.piston_sin = up.norm();
    if (!(c.cylinder_sin > p.min_cardan_sin)) return LegFault::LockedBaseCardan;
    if (!(c.piston_sin > p.min_cardan_sin)) return LegFault::LockedPlatformCardan;
    c.cylinder_x = uc / c.cylinder_sin;
    c.piston_x = up / c.piston_sin;
    return LegFault::None;
}

void leg_body_motion(const LegParameters &p, int k, const LegConfiguration &c,
                     const PlatformMotion &m, BodyMotion &cyl, BodyMotion &pis) {
    const Vec3 P = m.position + c.arm;
    const Vec3 P_dot = m.velocity + m.omega.cross(c.arm);
    const Vec3 P_ddot = m.acceleration + m.alpha.cross(c.arm) + m.omega.cross(m.omega.cross(c.arm));
    const AxisRates nr = axis_rates(c, P_dot, P_ddot);

    cyl.position = p.base_points.col(k) + p.cylinder_com * c.n;
    cyl.velocity = p.cylinder_com * nr.n_dot;
    cyl.acceleration = p.cylinder_com * nr.n_ddot;
    cyl.rotation = leg_axes(c.cylinder_x, c.n);
    const Vec3 zero = Vec3::Zero();
    frame_rates(c.n, nr, p.base_arm.col(k), zero, zero, c.cylinder_x, c.cylinder_sin, cyl.omega,
                cyl.alpha);

    pis.position = P - p.piston_com * c.n;
    pis.velocity = P_dot - p.piston_com * nr.n_dot;
    pis.acceleration = P_ddot - p.piston_com * nr.n_ddot;
    pis.rotation = leg_axes(c.piston_x, c.n);
    const Vec3 &s = c.piston_arm;
    const Vec3 s_dot = m.omega.cross(s);
    const Vec3 s_ddot = m.alpha.cross(s) + m.omega.cross(s_dot);
    frame_rates(c.n, nr, s, s_dot, s_ddot, c.piston_x, c.piston_sin, pis.omega, pis.alpha);
}

void leg_acceleration_jacobians(const LegParameters &p, int k, const LegConfiguration &c,
                                Matrix66 &cylinder, Matrix66 &piston) {
    // P_ddot = v_dot + omega_dot x arm = T nu_dot; n_ddot = N P_ddot, N = (I - n n^T) / L.
    Eigen::Matrix<double, 3, 6> T;
    T.leftCols<3>().setIdentity();
    T.rightCols<3>() << 0, c.arm[2], -c.arm[1], -c.arm[2], 0, c.arm[0], c.arm[1], -c.arm[0], 0;
    const Mat3 N = (Mat3::Identity() - c.n * c.n.transpose()) * c.inverse_length;
    const Eigen::Matrix<double, 3, 6> NT = N * T;
    Mat3 n_cross;
    n_cross << 0, -c.n[2], c.n[1], c.n[2], 0, -c.n[0], -c.n[1], c.n[0], 0;
    const Eigen::Matrix<double, 3, 6> turn = n_cross * NT;  // n x n_ddot
    // A leg body's frame has z = n: omega = n x n_dot + w n with the spin rate
    // w = (-x.s_dot + (y x s).n_dot) / |s x n| (Cardan arm s), so the part of alpha linear in the
    // twist rate is n x n_ddot + w_dot n, w_dot = (-x.s_ddot + (y x s).n_ddot) / |s x n|.
    const Vec3 base_arm = p.base_arm.col(k);
    const Vec3 g_cyl = c.n.cross(c.cylinder_x).cross(base_arm) / c.cylinder_sin;
    cylinder.topRows<3>() = p.cylinder_com * NT;
    cylinder.bottomRows<3>() = turn + c.n * (g_cyl.transpose() * NT);
    // The platform arm turns with the platform: s_ddot = omega_dot x s, x.s_ddot = omega_dot.(s x x).
    const Vec3 g_pis = c.n.cross(c.piston_x).cross(c.piston_arm) / c.piston_sin;
    const Vec3 h_pis = c.piston_arm.cross(c.piston_x) / c.piston_sin;
    Eigen::Matrix<double, 1, 6> spin = g_pis.transpose() * NT;
    spin.tail<3>() -= h_pis.transpose();
    piston.topRows<3>() = T - p.piston_com * NT;
    piston.bottomRows<3>() = turn + c.n * spin;
}

}  // namespace fd
}  // namespace stewart
