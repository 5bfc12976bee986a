// The definitions of plant_equations.hpp's templates, for the files that instantiate them:
// plant_equations.cpp (double, the plant) and linearize/plant_dual.cpp (the dual scalar), each
// in its own translation unit so that the plant's double code is compiled as it was alone.
#pragma once

#include "plant/plant_equations.hpp"

namespace stewart {
namespace plant {

namespace {

template <class S>
using Matrix66T = Eigen::Matrix<S, 6, 6>;
template <class S>
using Vector6T = Eigen::Matrix<S, 6, 1>;

template <class S>
Mat3T<S> skew(const Vec3T<S> &v) {
    Mat3T<S> m;
    m << S(0), -v[2], v[1], v[2], S(0), -v[0], -v[1], v[0], S(0);
    return m;
}

template <class S>
Mat3T<S> world_inertia(const Mat3T<S> &A, const Vec3 &principal) {
    return A * principal.template cast<S>().asDiagonal() * A.transpose();
}

// The applied minus inertial force f and torque t (about the centre of mass) of a body of the mass
// and world inertia I moving as b, under gravity.
template <class S>
void body_wrench(double mass, const Vec3 &gravity, const Mat3T<S> &I, const MotionT<S> &b,
                 Vec3T<S> &f, Vec3T<S> &t) {
    f = mass * (gravity.template cast<S>() - b.acceleration);
    t = -(I * b.alpha + b.omega.cross(I * b.omega));
}

// The applied minus inertial forces of leg k's two bodies (force, torque about each centre of
// mass) as generalised forces: f_point on the leg's platform point P_ddot, f_alpha on the
// platform's angular acceleration (the piston's spin about the leg). piston_linear = I - cp N.
template <class S>
void leg_forces(const DynamicsModel &d, const LegConfigurationT<S> &leg,
                const LegAccelerationMapT<S> &map, const Mat3T<S> &piston_linear,
                const MotionT<S> &cyl, const MotionT<S> &pis, const Mat3T<S> &I_cyl,
                const Mat3T<S> &I_pis, Vec3T<S> &f_point, Vec3T<S> &f_alpha) {
    Vec3T<S> f_cyl, t_cyl, f_pis, t_pis;
    body_wrench(d.cylinder_mass, d.gravity, I_cyl, cyl, f_cyl, t_cyl);
    body_wrench(d.piston_mass, d.gravity, I_pis, pis, f_pis, t_pis);
    f_point = d.legs.cylinder_com * (map.N * f_cyl) + map.cylinder_alpha.transpose() * t_cyl +
              piston_linear.transpose() * f_pis + map.piston_alpha.transpose() * t_pis;
    f_alpha = -leg.n.dot(t_pis) * map.piston_spin;
}

// Adds leg k's two bodies. Their accelerations are linear in u = (P_ddot, alpha) (the leg's
// platform point and the platform's angular acceleration) plus the velocity products in the
// biases, so their share is first formed in u (3 x 3 blocks) and then mapped to the twist rate
// by u = S nu_dot, S = [I, K; 0, I], K = -[arm]x.
template <class S>
void add_leg(const DynamicsModel &d, const LegConfigurationT<S> &leg, int k, const MotionT<S> &cyl,
             const MotionT<S> &pis, Matrix66T<S> &M, Vector6T<S> &rhs) {
    LegAccelerationMapT<S> map;
    leg_acceleration_map(d.legs, k, leg, map);
    const Mat3T<S> I_cyl = world_inertia(cyl.rotation, d.cylinder_inertia);
    const Mat3T<S> I_pis = world_inertia(pis.rotation, d.piston_inertia);
    const double cc = d.legs.cylinder_com, cp = d.legs.piston_com;
    const Mat3T<S> piston_linear = Mat3T<S>::Identity() - cp * map.N;
    // u-space mass blocks: A (P_ddot, P_ddot), B (P_ddot, alpha), C (alpha, alpha).
    Mat3T<S> A = (d.cylinder_mass * cc * cc) * (map.N * map.N) +
                 d.piston_mass * piston_linear.transpose() * piston_linear;
    A.noalias() += map.cylinder_alpha.transpose() * I_cyl * map.cylinder_alpha;
    A.noalias() += map.piston_alpha.transpose() * I_pis * map.piston_alpha;
    const Vec3T<S> I_pis_n = I_pis * leg.n;
    const Mat3T<S> B = -(map.piston_alpha.transpose() * I_pis_n) * map.piston_spin.transpose();
    const Mat3T<S> C = leg.n.dot(I_pis_n) * map.piston_spin * map.piston_spin.transpose();
    Vec3T<S> f_point, f_alpha;
    leg_forces(d, leg, map, piston_linear, cyl, pis, I_cyl, I_pis, f_point, f_alpha);

    const Mat3T<S> K = -skew(leg.arm);
    const Mat3T<S> AK_B = A * K + B;
    M.template topLeftCorner<3, 3>() += A;
    M.template topRightCorner<3, 3>() += AK_B;
    M.template bottomLeftCorner<3, 3>() += AK_B.transpose();
    M.template bottomRightCorner<3, 3>().noalias() += K.transpose() * AK_B + B.transpose() * K + C;
    rhs.template head<3>() += f_point;
    rhs.template tail<3>() += leg.arm.cross(f_point) + f_alpha;
}

// Leg k's configuration at m's pose into e.legs[k] (false, fault set, if it is undefined), and
// its force F_k (scalar S or double) added to the generalised forces f: along the leg, power
// F_k L_dot_k with L_dot_k = n . (v + omega x arm).
template <class S, class Force>
[[gnu::always_inline]] inline bool place_leg(const DynamicsModel &d, const MotionT<S> &m, int k,
                                             const Force &force, EvaluationT<S> &e,
                                             Vector6T<S> &f) {
    LegConfigurationT<S> &leg = e.legs[k];
    const LegFault fault = leg_configuration(d.legs, k, m.position, m.rotation, leg, d.with_legs);
    if (fault != LegFault::None) {
        e.fault = fault;
        e.fault_leg = k;
        return false;
    }
    f.template head<3>() += force * leg.n;
    f.template tail<3>() += force * leg.arm.cross(leg.n);
    return true;
}

// reduced_equations' body, and the platform's centre of mass c from its origin (world), inlined
// into twist_rate: as a call, and with c computed twice, it cost the plant's step 1.5 % more
// instructions at the massless fidelity. with_mass false leaves M alone (twist_rate's massless
// solve needs rhs and c only).
template <class S>
[[gnu::always_inline]] inline bool assemble(const DynamicsModel &d, const MotionT<S> &m,
                                            const S force[STEWART_LEGS], EvaluationT<S> &e,
                                            Matrix66T<S> &M, Vector6T<S> &rhs, Vec3T<S> &c,
                                            bool with_mass = true) {
    rhs.setZero();

    // The platform (and payload), centre of mass at c from the platform origin: with
    // a_c = v_dot + alpha x c + omega x (omega x c), Newton-Euler about the origin gives
    // M = [m I, -m [c]x; m [c]x, I_c - m [c]x [c]x] and the velocity-product and gravity terms.
    c = m.rotation * d.platform_com.template cast<S>();
    const Mat3T<S> I_platform =
        m.rotation * d.platform_inertia.template cast<S>() * m.rotation.transpose();
    const double mass = d.platform_mass;
    if (with_mass) {  // the four blocks fill M
        const Mat3T<S> c_cross = skew(c);
        M.template topLeftCorner<3, 3>() = mass * Mat3T<S>::Identity();
        M.template topRightCorner<3, 3>() = -mass * c_cross;
        M.template bottomLeftCorner<3, 3>() = mass * c_cross;
        M.template bottomRightCorner<3, 3>() = I_platform - mass * c_cross * c_cross;
    }
    const Vec3T<S> f_platform =
        mass * (d.gravity.template cast<S>() - m.omega.cross(m.omega.cross(c)));
    rhs.template head<3>() = f_platform;
    rhs.template tail<3>() = c.cross(f_platform) - m.omega.cross(I_platform * m.omega);

    if (!d.with_legs) {
        for (int k = 0; k < STEWART_LEGS; ++k)
            if (!place_leg(d, m, k, force[k], e, rhs)) return false;
        return true;
    }
    MotionT<S> at_rest_rate = m;  // the twist, with zero twist rate: velocity products
    at_rest_rate.acceleration.setZero();
    at_rest_rate.alpha.setZero();
    for (int k = 0; k < STEWART_LEGS; ++k) {
        if (!place_leg(d, m, k, force[k], e, rhs)) return false;
        const LegConfigurationT<S> &leg = e.legs[k];
        MotionT<S> cyl_bias, pis_bias;
        leg_body_motion(d.legs, k, leg, at_rest_rate, cyl_bias, pis_bias);
        add_leg(d, leg, k, cyl_bias, pis_bias, M, rhs);
    }
    return true;
}

}  // namespace

template <class S>
bool reduced_equations(const DynamicsModel &d, const MotionT<S> &m, const S force[STEWART_LEGS],
                       EvaluationT<S> &e, Eigen::Matrix<S, 6, 6> &M, Eigen::Matrix<S, 6, 1> &rhs) {
    Vec3T<S> c;
    return assemble(d, m, force, e, M, rhs, c);
}

template <class S>
bool twist_rate(const DynamicsModel &d, const MotionT<S> &m, const S force[STEWART_LEGS],
                EvaluationT<S> &e) {
    Matrix66T<S> M;
    Vector6T<S> rhs;
    Vec3T<S> c;
    if (!assemble(d, m, force, e, M, rhs, c, d.with_legs)) return false;
    if (!d.with_legs) {
        const double mass = d.platform_mass;
        // One rigid body: I_c alpha = T - c x F (moments about the origin), a = F/m - alpha x c.
        const Vec3T<S> F = rhs.template head<3>();
        const Vec3T<S> alpha =
            m.rotation * (d.platform_inertia_inverse.template cast<S>() *
                          (m.rotation.transpose() * (rhs.template tail<3>() - c.cross(F))));
        e.twist_rate.template head<3>() = F / mass - alpha.cross(c);
        e.twist_rate.template tail<3>() = alpha;
        e.fault = LegFault::None;
        e.fault_leg = -1;
        return true;
    }
    // M is symmetric positive definite (the platform alone has a positive mass and inertia).
    e.twist_rate = M.llt().solve(rhs);
    e.fault = LegFault::None;
    e.fault_leg = -1;
    return true;
}

template <class S>
bool motion_residual(const DynamicsModel &d, const MotionT<S> &m, const double force[STEWART_LEGS],
                     EvaluationT<S> &e, Eigen::Matrix<S, 6, 1> &residual) {
    // The platform: its applied minus inertial force at the centre of mass c, moments about the
    // origin (twist_rate's platform rows with the twist rate moved to the right).
    const Vec3T<S> c = m.rotation * d.platform_com.template cast<S>();
    const Mat3T<S> I_platform =
        m.rotation * d.platform_inertia.template cast<S>() * m.rotation.transpose();
    const Vec3T<S> f_platform =
        d.platform_mass * (d.gravity.template cast<S>() - m.acceleration - m.alpha.cross(c) -
                           m.omega.cross(m.omega.cross(c)));
    residual.template head<3>() = f_platform;
    residual.template tail<3>() =
        c.cross(f_platform) - I_platform * m.alpha - m.omega.cross(I_platform * m.omega);
    for (int k = 0; k < STEWART_LEGS; ++k) {
        if (!place_leg(d, m, k, force[k], e, residual)) return false;
        if (!d.with_legs) continue;
        const LegConfigurationT<S> &leg = e.legs[k];
        MotionT<S> cyl, pis;
        leg_body_motion(d.legs, k, leg, m, cyl, pis);
        Vec3T<S> f_cyl, t_cyl, f_pis, t_pis, f_point, f_alpha;
        body_wrench(d.cylinder_mass, d.gravity, world_inertia(cyl.rotation, d.cylinder_inertia),
                    cyl, f_cyl, t_cyl);
        body_wrench(d.piston_mass, d.gravity, world_inertia(pis.rotation, d.piston_inertia), pis,
                    f_pis, t_pis);
        leg_point_forces(d.legs, k, leg, f_cyl, t_cyl, f_pis, t_pis, f_point, f_alpha);
        residual.template head<3>() += f_point;
        residual.template tail<3>() += leg.arm.cross(f_point) + f_alpha;
    }
    e.fault = LegFault::None;
    e.fault_leg = -1;
    return true;
}

template <class S>
void body_motions(const DynamicsModel &d, const MotionT<S> &m, const EvaluationT<S> &e,
                  MotionT<S> bodies[13]) {
    MotionT<S> &platform = bodies[0];
    const Vec3T<S> c = m.rotation * d.platform_com.template cast<S>();
    platform.position = m.position + c;
    platform.rotation = m.rotation;
    platform.velocity = m.velocity + m.omega.cross(c);
    platform.omega = m.omega;
    platform.acceleration = m.acceleration + m.alpha.cross(c) + m.omega.cross(m.omega.cross(c));
    platform.alpha = m.alpha;
    if (!d.with_legs) return;
    for (int k = 0; k < STEWART_LEGS; ++k)
        leg_body_motion(d.legs, k, e.legs[k], m, bodies[1 + k], bodies[7 + k]);
}

template <class S>
void base_wrench(const DynamicsModel &d, const MotionT<S> bodies[13], Vec3T<S> &force,
                 Vec3T<S> &torque) {
    force.setZero();
    torque.setZero();
    const int count = d.with_legs ? 13 : 1;
    for (int b = 0; b < count; ++b) {
        const MotionT<S> &body = bodies[b];
        double mass;
        Mat3T<S> I;
        if (b == 0) {
            mass = d.platform_mass;
            I = body.rotation * d.platform_inertia.template cast<S>() * body.rotation.transpose();
        } else {
            mass = b <= 6 ? d.cylinder_mass : d.piston_mass;
            I = world_inertia(body.rotation, b <= 6 ? d.cylinder_inertia : d.piston_inertia);
        }
        // What the base must supply to this body beyond gravity, with the sign reversed.
        const Vec3T<S> f = mass * (body.acceleration - d.gravity.template cast<S>());
        force -= f;
        torque -= body.position.cross(f) + I * body.alpha + body.omega.cross(I * body.omega);
    }
}


// Explicit instantiation for the scalar S (inside namespace stewart::plant).
#define STEWART_PLANT_EQUATIONS_INSTANTIATE(S)                                               \
    template bool reduced_equations<S>(const DynamicsModel &, const MotionT<S> &, const S *, \
                                       EvaluationT<S> &, Eigen::Matrix<S, 6, 6> &,           \
                                       Eigen::Matrix<S, 6, 1> &);                            \
    template bool twist_rate<S>(const DynamicsModel &, const MotionT<S> &, const S *,        \
                                EvaluationT<S> &);                                           \
    template void body_motions<S>(const DynamicsModel &, const MotionT<S> &,                 \
                                  const EvaluationT<S> &, MotionT<S>[13]);                   \
    template void base_wrench<S>(const DynamicsModel &, const MotionT<S>[13], Vec3T<S> &,    \
                                 Vec3T<S> &);

// Explicit instantiation of motion_residual for the scalar S (inside namespace stewart::plant).
#define STEWART_PLANT_RESIDUAL_INSTANTIATE(S)                                                   \
    template bool motion_residual<S>(const DynamicsModel &, const MotionT<S> &, const double *, \
                                     EvaluationT<S> &, Eigen::Matrix<S, 6, 1> &);

}  // namespace plant
}  // namespace stewart
