#include "platform/forward_dynamics_equations.hpp"

#include "model.hpp"

namespace stewart {
namespace fd {

namespace {

Mat3 skew(const Vec3 &v) {
    Mat3 S;
    S << 0, -v[2], v[1], v[2], 0, -v[0], -v[1], v[0], 0;
    return S;
}

// Adds body b's share: J^T diag(m, I) J to the mass matrix, J^T (f - M bias - gyroscopic) to the
// right-hand side. J rows: acceleration (3) and angular acceleration (3) of the body per unit
// platform twist rate; bias: the body's accelerations at zero twist rate.
void add_body(double mass, const Mat3 &inertia_world, const Eigen::Matrix<double, 6, 6> &J,
              const BodyMotion &bias, const Vec3 &gravity, Matrix66 &M, Vector6 &rhs) {
    Eigen::Matrix<double, 6, 6> MJ;
    MJ.topRows<3>() = mass * J.topRows<3>();
    MJ.bottomRows<3>().noalias() = inertia_world * J.bottomRows<3>();
    M.noalias() += J.transpose() * MJ;
    Vector6 f;
    f.head<3>() = mass * (gravity - bias.acceleration);
    f.tail<3>() = -(inertia_world * bias.alpha + bias.omega.cross(inertia_world * bias.omega));
    rhs.noalias() += J.transpose() * f;
}

Mat3 world_inertia(const Mat3 &A, const Vec3 &principal) {
    return A * principal.asDiagonal() * A.transpose();
}

}  // namespace

DynamicsModel dynamics_model(const stewart_model &model, int fidelity) {
    DynamicsModel d;
    const stewart_params &p = model.params;
    const FullLayout &l = model.full_layout;
    d.legs.base_points = model.geometry.base_points;
    d.legs.platform_points = model.geometry.platform_points;
    d.legs.base_arm = l.base_arm;
    d.legs.platform_arm = l.platform_arm;
    d.legs.cylinder_com = p.cylinder_com;
    d.legs.piston_com = p.piston_com;
    d.legs.min_length = model.geometry.min_length;
    d.legs.min_cardan_sin = 1e-9;
    d.with_legs = fidelity == STEWART_FULL;
    d.platform_mass = model.platform.mass;
    d.platform_com = model.platform.com;
    d.platform_inertia = model.platform.inertia;
    d.cylinder_mass = p.cylinder_mass;
    d.piston_mass = p.piston_mass;
    d.cylinder_inertia = Vec3(p.cylinder_inertia);
    d.piston_inertia = Vec3(p.piston_inertia);
    d.gravity = model.gravity;
    return d;
}

bool twist_rate(const DynamicsModel &d, const PlatformMotion &m, const double force[STEWART_LEGS],
                Evaluation &e) {
    Matrix66 M = Matrix66::Zero();
    Vector6 rhs = Vector6::Zero();

    // The platform (and payload): its centre of mass sits at c from the platform origin.
    const Vec3 c = m.rotation * d.platform_com;
    const Mat3 I_platform = m.rotation * d.platform_inertia * m.rotation.transpose();
    Matrix66 J = Matrix66::Identity();
    J.topRightCorner<3, 3>() = -skew(c);
    BodyMotion bias;
    bias.acceleration = m.omega.cross(m.omega.cross(c));
    bias.alpha.setZero();
    bias.omega = m.omega;
    add_body(d.platform_mass, I_platform, J, bias, d.gravity, M, rhs);

    PlatformMotion at_rest_rate = m;  // the twist, with zero twist rate: velocity products
    at_rest_rate.acceleration.setZero();
    at_rest_rate.alpha.setZero();
    for (int k = 0; k < STEWART_LEGS; ++k) {
        LegConfiguration &leg = e.legs[k];
        const LegFault fault = leg_configuration(d.legs, k, m.position, m.rotation, leg);
        // Massless legs have no bodies: only a zero length matters.
        if (fault != LegFault::None && (d.with_legs || fault == LegFault::ZeroLength)) {
            e.fault = fault;
            e.fault_leg = k;
            return false;
        }
        // F_k along the leg: power F_k L_dot_k, L_dot_k = n . (v + omega x arm).
        rhs.head<3>() += force[k] * leg.n;
        rhs.tail<3>() += force[k] * leg.arm.cross(leg.n);
        if (!d.with_legs) continue;

        BodyMotion cyl_bias, pis_bias;
        leg_body_motion(d.legs, k, leg, at_rest_rate, cyl_bias, pis_bias);
        Matrix66 J_cyl, J_pis;
        leg_acceleration_jacobians(d.legs, k, leg, J_cyl, J_pis);
        add_body(d.cylinder_mass, world_inertia(cyl_bias.rotation, d.cylinder_inertia), J_cyl,
                 cyl_bias, d.gravity, M, rhs);
        add_body(d.piston_mass, world_inertia(pis_bias.rotation, d.piston_inertia), J_pis,
                 pis_bias, d.gravity, M, rhs);
    }
    // M is symmetric positive definite (the platform alone has a positive mass and inertia).
    e.twist_rate = M.llt().solve(rhs);
    e.fault = LegFault::None;
    e.fault_leg = -1;
    return true;
}

void body_motions(const DynamicsModel &d, const PlatformMotion &m, const Evaluation &e,
                  BodyMotion bodies[13]) {
    BodyMotion &platform = bodies[0];
    const Vec3 c = m.rotation * d.platform_com;
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

void base_wrench(const DynamicsModel &d, const BodyMotion bodies[13], Vec3 &force, Vec3 &torque) {
    force.setZero();
    torque.setZero();
    const int count = d.with_legs ? 13 : 1;
    for (int b = 0; b < count; ++b) {
        const BodyMotion &body = bodies[b];
        double mass;
        Mat3 I;
        if (b == 0) {
            mass = d.platform_mass;
            I = body.rotation * d.platform_inertia * body.rotation.transpose();
        } else {
            mass = b <= 6 ? d.cylinder_mass : d.piston_mass;
            I = world_inertia(body.rotation, b <= 6 ? d.cylinder_inertia : d.piston_inertia);
        }
        // What the base must supply to this body beyond gravity, with the sign reversed.
        const Vec3 f = mass * (body.acceleration - d.gravity);
        force -= f;
        torque -= body.position.cross(f) + I * body.alpha + body.omega.cross(I * body.omega);
    }
}

}  // namespace fd
}  // namespace stewart
