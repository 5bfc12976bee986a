// The definitions of plant_bodies.hpp's templates, for the files that instantiate them:
// plant_bodies.cpp (double, the plant) and linearize/plant_dual.cpp (the dual scalar), each in
// its own translation unit so that the plant's double code is compiled as it was alone.
#pragma once

#include "plant/plant_bodies.hpp"

namespace stewart {
namespace plant {

namespace {

// Motion of a unit axis n = d / |d| from d and its first two rates.
template <class S>
struct AxisRates {
    Vec3T<S> n_dot, n_ddot;
};

template <class S>
AxisRates<S> axis_rates(const LegConfigurationT<S> &c, const Vec3T<S> &d_dot,
                        const Vec3T<S> &d_ddot) {
    AxisRates<S> r;
    const Vec3T<S> &n = c.n;
    const S L_dot = n.dot(d_dot);
    r.n_dot = (d_dot - L_dot * n) * c.inverse_length;
    // L n = d twice differentiated, with L_ddot = n.d_ddot + L |n_dot|^2.
    const S L_ddot = n.dot(d_ddot) + c.length * r.n_dot.squaredNorm();
    r.n_ddot = (d_ddot - L_ddot * n - 2.0 * L_dot * r.n_dot) * c.inverse_length;
    return r;
}

// Angular velocity and acceleration of the frame (x, y = n x x, z = n), x = (s x n)/|s x n|, from
// the rates of n and s. With z = n, omega = n x n_dot + w n, where the spin rate w = x_dot.y
// = (-x.s_dot + (y x s).n_dot) / |s x n|; alpha = n x n_ddot + w_dot n + w n_dot.
template <class S>
void frame_rates(const Vec3T<S> &n, const AxisRates<S> &nr, const Vec3T<S> &s,
                 const Vec3T<S> &s_dot, const Vec3T<S> &s_ddot, const Vec3T<S> &x, S mu,
                 Vec3T<S> &omega, Vec3T<S> &alpha) {
    const S inv_mu = 1.0 / mu;
    const Vec3T<S> y = n.cross(x);
    const Vec3T<S> u_dot = s_dot.cross(n) + s.cross(nr.n_dot);
    const S mu_dot = x.dot(u_dot);
    const Vec3T<S> x_dot = (u_dot - mu_dot * x) * inv_mu;
    const Vec3T<S> y_dot = nr.n_dot.cross(x) + n.cross(x_dot);
    const Vec3T<S> y_cross_s = y.cross(s);
    const S w = (-x.dot(s_dot) + y_cross_s.dot(nr.n_dot)) * inv_mu;
    const S numerator_dot = -x_dot.dot(s_dot) - x.dot(s_ddot) +
                            (y_dot.cross(s) + y.cross(s_dot)).dot(nr.n_dot) +
                            y_cross_s.dot(nr.n_ddot);
    const S w_dot = (numerator_dot - w * mu_dot) * inv_mu;
    omega = n.cross(nr.n_dot) + w * n;
    alpha = n.cross(nr.n_ddot) + w_dot * n + w * nr.n_dot;
}

// R b for a column b of the model's 3 x 6 point sets, written out: the sums of Eigen's 3 x 3
// product in its order (so the same bits), without the call and loop of its product kernel for
// a block operand (1 k instructions per massless plant step).
template <class S, class Column>
[[gnu::always_inline]] inline Vec3T<S> rotate(const Mat3T<S> &R, const Column &b) {
    const Vec3T<S> v = b.template cast<S>();
    Vec3T<S> r;
    for (int i = 0; i < 3; ++i) r[i] = R(i, 0) * v[0] + R(i, 1) * v[1] + R(i, 2) * v[2];
    return r;
}

template <class S>
Mat3T<S> leg_axes(const Vec3T<S> &x, const Vec3T<S> &n) {
    Mat3T<S> A;
    A.col(0) = x;
    A.col(1) = n.cross(x);
    A.col(2) = n;
    return A;
}

}  // namespace

template <class S>
LegFault leg_configuration(const LegParameters &p, int k, const Vec3T<S> &position,
                           const Mat3T<S> &rotation, LegConfigurationT<S> &c, bool frames) {
    c.arm = rotate(rotation, p.platform_points.col(k));
    const Vec3T<S> d = position + c.arm - p.base_points.col(k).template cast<S>();
    c.length = d.norm();
    if (!(c.length > p.min_length)) return LegFault::ZeroLength;
    c.inverse_length = 1.0 / c.length;
    c.n = d * c.inverse_length;
    if (!frames) return LegFault::None;
    c.piston_arm = rotate(rotation, p.platform_arm.col(k));
    const Vec3T<S> uc = p.base_arm.col(k).template cast<S>().cross(c.n),
                   up = c.piston_arm.cross(c.n);
    c.cylinder_sin = uc.norm();
    c.piston_sin = up.norm();
    if (!(c.cylinder_sin > p.min_cardan_sin)) return LegFault::LockedBaseCardan;
    if (!(c.piston_sin > p.min_cardan_sin)) return LegFault::LockedPlatformCardan;
    c.cylinder_x = uc / c.cylinder_sin;
    c.piston_x = up / c.piston_sin;
    return LegFault::None;
}

template <class S>
void leg_body_motion(const LegParameters &p, int k, const LegConfigurationT<S> &c,
                     const MotionT<S> &m, MotionT<S> &cyl, MotionT<S> &pis) {
    const Vec3T<S> P = m.position + c.arm;
    const Vec3T<S> P_dot = m.velocity + m.omega.cross(c.arm);
    const Vec3T<S> P_ddot =
        m.acceleration + m.alpha.cross(c.arm) + m.omega.cross(m.omega.cross(c.arm));
    const AxisRates<S> nr = axis_rates(c, P_dot, P_ddot);

    cyl.position = p.base_points.col(k).template cast<S>() + p.cylinder_com * c.n;
    cyl.velocity = p.cylinder_com * nr.n_dot;
    cyl.acceleration = p.cylinder_com * nr.n_ddot;
    cyl.rotation = leg_axes(c.cylinder_x, c.n);
    const Vec3T<S> zero = Vec3T<S>::Zero();
    frame_rates<S>(c.n, nr, p.base_arm.col(k).template cast<S>(), zero, zero, c.cylinder_x,
                   c.cylinder_sin, cyl.omega, cyl.alpha);

    pis.position = P - p.piston_com * c.n;
    pis.velocity = P_dot - p.piston_com * nr.n_dot;
    pis.acceleration = P_ddot - p.piston_com * nr.n_ddot;
    pis.rotation = leg_axes(c.piston_x, c.n);
    const Vec3T<S> &s = c.piston_arm;
    const Vec3T<S> s_dot = m.omega.cross(s);
    const Vec3T<S> s_ddot = m.alpha.cross(s) + m.omega.cross(s_dot);
    frame_rates(c.n, nr, s, s_dot, s_ddot, c.piston_x, c.piston_sin, pis.omega, pis.alpha);
}

template <class S>
void leg_acceleration_map(const LegParameters &p, int k, const LegConfigurationT<S> &c,
                          LegAccelerationMapT<S> &map) {
    map.N = (Mat3T<S>::Identity() - c.n * c.n.transpose()) * c.inverse_length;
    Mat3T<S> n_cross;
    n_cross << S(0), -c.n[2], c.n[1], c.n[2], S(0), -c.n[0], -c.n[1], c.n[0], S(0);
    const Mat3T<S> turn = n_cross * map.N;  // n x n_ddot per unit P_ddot
    // A leg body's frame has z = n: omega = n x n_dot + w n with the spin rate
    // w = (-x.s_dot + (y x s).n_dot) / |s x n| (Cardan arm s), so the part of alpha linear in the
    // accelerations is n x n_ddot + w_dot n, w_dot = (-x.s_ddot + (y x s).n_ddot) / |s x n|.
    const Vec3T<S> g_cyl =
        c.n.cross(c.cylinder_x).cross(p.base_arm.col(k).template cast<S>()) / c.cylinder_sin;
    map.cylinder_alpha = turn + c.n * (map.N * g_cyl).transpose();
    // The platform arm turns with the platform: s_ddot = alpha x s, x.s_ddot = alpha.(s x x).
    const Vec3T<S> g_pis = c.n.cross(c.piston_x).cross(c.piston_arm) / c.piston_sin;
    map.piston_alpha = turn + c.n * (map.N * g_pis).transpose();
    map.piston_spin = c.piston_arm.cross(c.piston_x) / c.piston_sin;
}

template <class S>
void leg_point_forces(const LegParameters &p, int k, const LegConfigurationT<S> &c,
                      const Vec3T<S> &f_cyl, const Vec3T<S> &t_cyl, const Vec3T<S> &f_pis,
                      const Vec3T<S> &t_pis, Vec3T<S> &f_point, Vec3T<S> &f_alpha) {
    // With N v = (v - n (n.v)) / L (symmetric) and a body's alpha map turn + n (N g)^T,
    // turn = [n]x N: its transpose takes t to N (t x n + (n.t) g). The cylinder's point map is
    // cylinder_com N, the piston's I - piston_com N.
    const Vec3T<S> &n = c.n;
    const Vec3T<S> g_cyl =
        n.cross(c.cylinder_x).cross(p.base_arm.col(k).template cast<S>()) / c.cylinder_sin;
    const Vec3T<S> g_pis = n.cross(c.piston_x).cross(c.piston_arm) / c.piston_sin;
    const S n_t_cyl = n.dot(t_cyl), n_t_pis = n.dot(t_pis);
    const Vec3T<S> v = p.cylinder_com * f_cyl - p.piston_com * f_pis + (t_cyl + t_pis).cross(n) +
                       n_t_cyl * g_cyl + n_t_pis * g_pis;
    f_point = f_pis + (v - n.dot(v) * n) * c.inverse_length;
    f_alpha = (-n_t_pis / c.piston_sin) * c.piston_arm.cross(c.piston_x);
}

// Explicit instantiation for the scalar S (inside namespace stewart::plant).
#define STEWART_PLANT_BODIES_INSTANTIATE(S)                                                    \
    template LegFault leg_configuration<S>(const LegParameters &, int, const Vec3T<S> &,       \
                                           const Mat3T<S> &, LegConfigurationT<S> &, bool);    \
    template void leg_body_motion<S>(const LegParameters &, int, const LegConfigurationT<S> &, \
                                     const MotionT<S> &, MotionT<S> &, MotionT<S> &);          \
    template void leg_acceleration_map<S>(const LegParameters &, int,                          \
                                          const LegConfigurationT<S> &, LegAccelerationMapT<S> &);

}  // namespace plant
}  // namespace stewart
