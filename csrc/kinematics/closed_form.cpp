#include "kinematics/closed_form.hpp"

#include <cmath>

#include "kinematics/joints.hpp"
#include "kinematics/lu6.hpp"
#include "util/message.hpp"

namespace stewart {

PlatformGeometry platform_geometry(const stewart_params &p) {
    const JointGeometry joints = joint_geometry(p);
    PlatformGeometry g;
    g.base_points = joints.base_points;
    g.platform_points = joints.platform_points;
    g.min_length = 1e-12 * (joints.base_size + joints.platform_size);
    g.characteristic_length = joints.platform_size;
    return g;
}

namespace {

// Inertia of a body about a point displaced by d from its centre of mass (parallel axes).
Eigen::Matrix3d shifted_inertia(const Eigen::Matrix3d &I, double m, const Eigen::Vector3d &d) {
    return I + m * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
}

}  // namespace

LumpedBody lumped_platform(const stewart_params &p) {
    const Eigen::Vector3d c_plate(p.platform_com), c_load(p.payload_com);
    LumpedBody b;
    b.mass = p.platform_mass + p.payload_mass;
    b.com = (p.platform_mass * c_plate + p.payload_mass * c_load) / b.mass;
    const Eigen::Matrix3d I_plate = Eigen::Vector3d(p.platform_inertia).asDiagonal();
    const Eigen::Matrix3d I_load = Eigen::Vector3d(p.payload_inertia).asDiagonal();
    b.inertia = shifted_inertia(I_plate, p.platform_mass, c_plate - b.com) +
                shifted_inertia(I_load, p.payload_mass, c_load - b.com);
    return b;
}

stewart_status leg_kinematics(const PlatformGeometry &g, const Motion &m, LegKinematics &out,
                              char *msg, size_t size) {
    out.arm.noalias() = m.rotation * g.platform_points;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Eigen::Vector3d r = out.arm.col(k);
        const Eigen::Vector3d d = m.position + r - g.base_points.col(k);
        const double L = d.norm();
        if (!(L > g.min_length)) return check_leg_length(k, L, g.min_length, msg, size);
        const double inv_L = 1.0 / L;  // one division per leg, in the hot path
        const Eigen::Vector3d n = d * inv_L;
        const Eigen::Vector3d v = m.velocity + m.omega.cross(r);
        const Eigen::Vector3d a =
            m.acceleration + m.alpha.cross(r) + m.omega.cross(m.omega.cross(r));
        const double L_dot = n.dot(v);
        out.axis.col(k) = n;
        out.length[k] = L;
        out.rate[k] = L_dot;
        // From d(d.d)/dt twice: L L_ddot = |d_dot|^2 - L_dot^2 + d.d_ddot.
        out.accel[k] = (v.squaredNorm() - L_dot * L_dot) * inv_L + n.dot(a);
    }
    return STEWART_OK;
}

namespace {

// inv = A^-1 from the one small LU (lu6: partial pivoting, a pivot below 1e-14 of the largest
// entry refused, so beyond a condition of about 1e14 there is no inverse). False: none.
bool invert_6x6(const Eigen::Matrix<double, 6, 6> &A, Eigen::Matrix<double, 6, 6> &inv) {
    double a[36];
    int pivot[6], order[6];
    for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 6; ++c) a[6 * r + c] = A(r, c);
    if (!lu6_factor(a, pivot, order, lu6_largest(a))) return false;
    for (int c = 0; c < 6; ++c) {
        double x[6] = {0, 0, 0, 0, 0, 0};
        x[c] = 1.0;
        lu6_solve(a, order, x, x);
        for (int r = 0; r < 6; ++r) inv(r, c) = x[r];
    }
    return true;
}

}  // namespace

void leg_jacobian(const PlatformGeometry &g, const LegKinematics &legs, LegJacobian &out) {
    const double inv_length = 1.0 / g.characteristic_length;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Eigen::Vector3d n = legs.axis.col(k);
        out.transposed.block<3, 1>(0, k) = n;
        out.transposed.block<3, 1>(3, k) = legs.arm.col(k).cross(n) * inv_length;
    }
    // cond_1(J) = ||J^T||_inf ||J^-T||_inf; exact for 6x6, and the inverse serves the solve too.
    out.condition = invert_6x6(out.transposed, out.inverse_transposed)
                        ? out.transposed.cwiseAbs().rowwise().sum().maxCoeff() *
                              out.inverse_transposed.cwiseAbs().rowwise().sum().maxCoeff()
                        : HUGE_VAL;
}

stewart_status check_leg_length(int leg, double length, double min_length, char *msg, size_t size) {
    if (length > min_length) return STEWART_OK;
    return set_message(msg, size, STEWART_ERR_UNREACHABLE,
                       "leg %d has length %g m at this pose: its platform point lies on its base "
                       "point",
                       leg + 1, length);
}

stewart_status check_condition(double condition, double singular_condition, char *msg,
                               size_t size) {
    if (condition <= singular_condition) return STEWART_OK;
    return set_message(msg, size, STEWART_ERR_SINGULAR,
                       "leg Jacobian is singular at this pose: condition number %g exceeds "
                       "singular_condition %g",
                       condition, singular_condition);
}

void base_wrench_from_axial(const PlatformGeometry &g, const LegKinematics &legs,
                            const double force[STEWART_LEGS], stewart_inverse_output &out) {
    Eigen::Vector3d f = Eigen::Vector3d::Zero(), t = Eigen::Vector3d::Zero();
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Eigen::Vector3d on_base = -force[k] * legs.axis.col(k);
        f += on_base;
        t += g.base_points.col(k).cross(on_base);
    }
    for (int i = 0; i < 3; ++i) {
        out.base_force[i] = f[i];
        out.base_torque[i] = t[i];
    }
}

stewart_status massless_forces(const PlatformGeometry &g, const LumpedBody &body,
                               const Eigen::Vector3d &gravity, const Motion &m,
                               const LegKinematics &legs, double singular_condition,
                               stewart_inverse_output &out, char *msg, size_t size) {
    // Newton-Euler for the lumped body; moments taken about the platform origin.
    const Eigen::Vector3d c = m.rotation * body.com;
    const Eigen::Vector3d a_c = m.acceleration + m.alpha.cross(c) + m.omega.cross(m.omega.cross(c));
    const Eigen::Matrix3d I_world = m.rotation * body.inertia * m.rotation.transpose();
    Vector6 wrench;
    wrench.head<3>() = body.mass * (a_c - gravity);
    wrench.tail<3>() =
        I_world * m.alpha + m.omega.cross(I_world * m.omega) + c.cross(wrench.head<3>());

    LegJacobian J;
    leg_jacobian(g, legs, J);
    const stewart_status s = check_condition(J.condition, singular_condition, msg, size);
    if (s != STEWART_OK) return s;
    // J^T F = wrench, with the moment rows scaled as the Jacobian's.
    wrench.tail<3>() /= g.characteristic_length;
    const Vector6 F = J.inverse_transposed * wrench;
    for (int k = 0; k < STEWART_LEGS; ++k) out.force[k] = F[k];
    out.condition = J.condition;
    base_wrench_from_axial(g, legs, out.force, out);
    return STEWART_OK;
}

}  // namespace stewart
