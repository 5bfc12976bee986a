#include "inverse/full_model.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/dynamics.hpp"
#include "core/euler_pairs.hpp"
#include "core/step.hpp"
#include "stewart/stewart_table.h"
#include "util/message.hpp"

namespace stewart {

namespace {

using mbs::Vec3;
using mbs::Vec4;

// The leg body frame: z along the leg, x the Cardan arm perpendicular to the plate's arm s.
Eigen::Matrix3d leg_frame(const Vec3 &n, const Vec3 &s) {
    Eigen::Matrix3d A;
    const Vec3 x = s.cross(n).normalized();
    A.col(0) = x;
    A.col(1) = n.cross(x);
    A.col(2) = n;
    return A;
}

// p and -p are the same rotation: the one on the side of `previous` (Euler parameters).
Vec4 same_side(const Vec4 &p, const double *previous) {
    return p.dot(Eigen::Map<const Vec4>(previous)) < 0 ? Vec4(-p) : p;
}

// A body's 7 coordinates: position r, and the Euler parameters of A.
void store_pose(double q[7], const Vec3 &r, const Vec4 &p) {
    for (int c = 0; c < 3; ++c) q[c] = r[c];
    for (int c = 0; c < 4; ++c) q[3 + c] = p[c];
}

void put_body(mbs::State &s, int body, const Vec3 &r, const Eigen::Matrix3d &A) {
    double *q = mbs::body_r(s.q.data(), body);
    const Vec4 p = mbs::euler_parameters(A);
    // Stay on the side of the previous solution.
    store_pose(q, r, s.has_history ? same_side(p, mbs::body_p(s.q.data(), body)) : p);
}

// q, q_dot, q_ddot of a body: p_dot = E^T w / 2, p_ddot = E^T alpha / 2 - |p_dot|^2 p.
void put_body_motion(mbs::State &s, int body, const Motion &b) {
    put_body(s, body, b.position, b.rotation);
    const double *p = mbs::body_p(s.q.data(), body);
    Vec4 p_dot, p_ddot;
    mbs::E_transpose_times_two(p, b.omega.data(), b.alpha.data(), p_dot.data(), p_ddot.data());
    p_dot *= 0.5;  // a power of two: exact
    p_ddot = 0.5 * p_ddot - p_dot.squaredNorm() * Vec4(p);
    store_pose(mbs::body_r(s.q_dot.data(), body), b.velocity, p_dot);
    store_pose(mbs::body_r(s.q_ddot.data(), body), b.acceleration, p_ddot);
}

// Two 3-vectors side by side: component c of the cylinder's in lane 0 of v[c], the piston's in
// lane 1 (euler_pairs.hpp: each lane does the scalar arithmetic in Eigen's order, so both are the
// scalar results' bits).
struct TwoVec3 {
    mbs::Lanes v[3];
};
TwoVec3 two(const Vec3 &a, const Vec3 &b) {
    return {{mbs::lanes(a[0], b[0]), mbs::lanes(a[1], b[1]), mbs::lanes(a[2], b[2])}};
}
TwoVec3 operator+(const TwoVec3 &a, const TwoVec3 &b) {
    return {{a.v[0] + b.v[0], a.v[1] + b.v[1], a.v[2] + b.v[2]}};
}
TwoVec3 operator-(const TwoVec3 &a, const TwoVec3 &b) {
    return {{a.v[0] - b.v[0], a.v[1] - b.v[1], a.v[2] - b.v[2]}};
}
TwoVec3 operator*(mbs::Lanes k, const TwoVec3 &a) { return {{k * a.v[0], k * a.v[1], k * a.v[2]}}; }
TwoVec3 operator/(const TwoVec3 &a, mbs::Lanes k) { return {{a.v[0] / k, a.v[1] / k, a.v[2] / k}}; }
// Eigen's dot and cross of 3-vectors, term by term in its order.
mbs::Lanes dot(const TwoVec3 &a, const TwoVec3 &b) {
    return a.v[0] * b.v[0] + a.v[1] * b.v[1] + a.v[2] * b.v[2];
}
TwoVec3 cross(const TwoVec3 &a, const TwoVec3 &b) {
    return {{a.v[1] * b.v[2] - a.v[2] * b.v[1], a.v[2] * b.v[0] - a.v[0] * b.v[2],
             a.v[0] * b.v[1] - a.v[1] * b.v[0]}};
}
Vec3 lane(const TwoVec3 &a, int k) { return Vec3(a.v[0][k], a.v[1][k], a.v[2][k]); }

// A leg body's angular velocity and acceleration. Its z axis is the leg axis n (with rates), its
// Cardan partner (angular velocity w_o, acceleration alpha_o) carries the cross arm s (world);
// the body's x axis is the other arm, s x n normalised. The relative rotation is about the two
// arms, w = w_o + a s + b x, and n_dot = w x n fixes a and b; n_ddot = alpha x n + w x n_dot
// fixes their rates the same way.
// Both bodies of a leg at once, in the two lanes: the cylinder (arm s_c, partner the fixed base)
// and the piston (arm s_p, partner the platform: w_p, alpha_p); their frames (leg_frame's) too.
void leg_bodies_rates(const Vec3 &n_, const Vec3 &n_dot_, const Vec3 &n_ddot_, const Vec3 &s_c,
                      const Vec3 &s_p, const Vec3 &w_p, const Vec3 &alpha_p, Motion &cylinder,
                      Motion &piston) {
    const Vec3 zero = Vec3::Zero();
    const TwoVec3 n = two(n_, n_), n_dot = two(n_dot_, n_dot_), n_ddot = two(n_ddot_, n_ddot_);
    const TwoVec3 s = two(s_c, s_p), w_o = two(zero, w_p), alpha_o = two(zero, alpha_p);
    const TwoVec3 c = cross(s, n);
    const mbs::Lanes squared = dot(c, c);
    const mbs::Lanes c_norm = mbs::lanes(std::sqrt(squared[0]), std::sqrt(squared[1]));
    const TwoVec3 x = c / c_norm, y = cross(n, x);
    const TwoVec3 relative = n_dot - cross(w_o, n);
    const mbs::Lanes a = dot(relative, x) / c_norm, bb = -dot(relative, y);
    const TwoVec3 omega = w_o + a * s + bb * x;
    const TwoVec3 known = alpha_o + a * cross(w_o, s) + bb * cross(omega, x);
    const TwoVec3 rest = n_ddot - cross(omega, n_dot) - cross(known, n);
    const TwoVec3 alpha = known + (dot(rest, x) / c_norm) * s - dot(rest, y) * x;
    Motion *bodies[2] = {&cylinder, &piston};
    for (int k = 0; k < 2; ++k) {
        bodies[k]->omega = lane(omega, k);
        bodies[k]->alpha = lane(alpha, k);
        // leg_frame(n, s): its x is s x n normalised, c / |c| (Eigen's normalized() divides).
        bodies[k]->rotation.col(0) = lane(x, k);
        bodies[k]->rotation.col(1) = lane(y, k);
        bodies[k]->rotation.col(2) = n_;
    }
}

struct Placement {
    Vec3 r_cylinder[STEWART_LEGS], r_piston[STEWART_LEGS], r_platform;
    Eigen::Matrix3d A_cylinder[STEWART_LEGS], A_piston[STEWART_LEGS], A_platform;
};

Placement place(const FullLayout &l, const Vec3 &position, const Eigen::Matrix3d &R) {
    Placement pl;
    pl.r_platform = position + R * l.com;
    pl.A_platform = R * l.axes;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Vec3 a = l.geometry.base_points.col(k);
        const Vec3 P = position + R * l.geometry.platform_points.col(k);
        const Vec3 n = (P - a).normalized();
        pl.A_cylinder[k] = leg_frame(n, l.base_arm.col(k));
        pl.A_piston[k] = leg_frame(n, R * l.platform_arm.col(k));
        pl.r_cylinder[k] = a + l.cylinder_com * n;
        pl.r_piston[k] = P - l.piston_com * n;
    }
    return pl;
}

// The parameters with lengths in units of L0 (a power of two: exact), by the table's units.
stewart_params in_length_unit(const stewart_params &si, double L0) {
    stewart_params p = si;
    for (int i = 0; i < stewart_param_count(); ++i) {
        const char *unit = stewart_param(i)->unit;
        const double factor = !std::strcmp(unit, "m") || !std::strcmp(unit, "m/s2") ? 1.0 / L0
                              : !std::strcmp(unit, "kg.m2") ? 1.0 / (L0 * L0)
                                                            : 1.0;
        for (int e = 0; e < stewart_param(i)->count; ++e)
            *stewart_param_element(&p, i, e) *= factor;
    }
    return p;
}

}  // namespace

double length_unit(const stewart_params &p) {
    const JointGeometry joints = joint_geometry(p);
    const double size =
        std::max({joints.base_size, joints.platform_size, std::fabs(p.home_height)});
    int exponent = 0;
    const double mantissa = std::frexp(2.0 * size, &exponent);  // 2 size = mantissa 2^exponent
    return std::ldexp(1.0, mantissa == 0.5 ? exponent - 1 : exponent);
}

std::unique_ptr<mbs_model> build_full_platform(const stewart_params &si, FullDrive drive,
                                               FullLayout &l, char *msg, size_t size) {
    l.length_unit = length_unit(si);
    const stewart_params p = in_length_unit(si, l.length_unit);
    std::unique_ptr<mbs_model> model(new (std::nothrow) mbs_model);
    if (!model) {
        set_message(msg, size, STEWART_ERR_MEMORY, "out of memory building the full model");
        return nullptr;
    }
    l.drive = drive;
    l.geometry = platform_geometry(p);
    l.cylinder_com = p.cylinder_com;
    l.piston_com = p.piston_com;
    const JointGeometry joints = joint_geometry(p);
    l.base_arm = joints.base_arms;
    l.platform_arm = joints.platform_arms;

    // Platform and payload as one body, on its own principal axes at its centre of mass.
    const LumpedBody lumped = lumped_platform(p);
    l.com = lumped.com;
    Eigen::Matrix3d I = lumped.inertia;
    Vec3 principal;
    const double off = std::fabs(I(0, 1)) + std::fabs(I(0, 2)) + std::fabs(I(1, 2));
    if (off <= 1e-15 * I.trace()) {
        l.axes.setIdentity();
        principal = I.diagonal();
    } else {
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I);
        l.axes = eig.eigenvectors();
        if (l.axes.determinant() < 0) l.axes.col(2) = -l.axes.col(2);
        principal = eig.eigenvalues();
    }

    const Placement home = place(l, Vec3(0, 0, p.home_height), Eigen::Matrix3d::Identity());
    mbs::Mechanism &m = model->mechanism;
    m.gravity = Vec3(p.gravity);
    mbs::Builder b{m, msg, size};
    auto reference = [](const Vec3 &r, const Eigen::Matrix3d &A, double q[7]) {
        store_pose(q, r, mbs::euler_parameters(A));
    };
    double q[7];
    reference(Vec3::Zero(), Eigen::Matrix3d::Identity(), q);
    l.base = b.body("base", 0.0, Vec3::Zero(), q);
    for (int k = 0; k < STEWART_LEGS; ++k) {
        reference(home.r_cylinder[k], home.A_cylinder[k], q);
        l.cylinder[k] = b.body("cylinder", p.cylinder_mass, Vec3(p.cylinder_inertia), q);
    }
    for (int k = 0; k < STEWART_LEGS; ++k) {
        reference(home.r_piston[k], home.A_piston[k], q);
        l.piston[k] = b.body("piston", p.piston_mass, Vec3(p.piston_inertia), q);
    }
    reference(home.r_platform, home.A_platform, q);
    l.platform = b.body("platform", lumped.mass, principal, q);
    if (l.platform < 0 || (l.base_fixed = b.fix(l.base)) < 0) return nullptr;

    const Vec3 ez = Vec3::UnitZ(), ex = Vec3::UnitX();
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Vec3 base_point = l.geometry.base_points.col(k);
        const Vec3 plate_point = l.axes.transpose() * (l.geometry.platform_points.col(k) - l.com);
        const Vec3 plate_arm = l.axes.transpose() * l.platform_arm.col(k);
        const Vec3 cyl_end(0, 0, -p.cylinder_com), pis_end(0, 0, p.piston_com);
        l.base_cardan[k] =
            b.cardan(l.base, base_point, l.base_arm.col(k), l.cylinder[k], cyl_end, ex);
        if (b.cardan(l.platform, plate_point, plate_arm, l.piston[k], pis_end, ex) < 0)
            return nullptr;
        l.cylindrical[k] = b.cylindrical(l.cylinder[k], cyl_end, ez, l.piston[k], pis_end, ez);
        if (l.base_cardan[k] < 0 || l.cylindrical[k] < 0) return nullptr;
    }
    if (drive == FullDrive::ActuatorLengths) {
        for (int k = 0; k < STEWART_LEGS; ++k)
            if ((l.driver_joint[k] = b.distance_driver(l.cylindrical[k], nullptr)) < 0)
                return nullptr;
    } else if ((l.pose_joint = b.pose_driver(l.platform, nullptr)) < 0) {
        return nullptr;
    }
    if (!mbs::finalize(m, msg, size)) return nullptr;
    return model;
}

void full_motion(const FullLayout &l, const Motion &mo, mbs::State &s) {
    const Eigen::Matrix3d &R = mo.rotation;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        // The leg: d = P - a, its length, axis n and their rates.
        const Vec3 arm = R * l.geometry.platform_points.col(k);
        const Vec3 P = mo.position + arm;
        const Vec3 P_dot = mo.velocity + mo.omega.cross(arm);
        const Vec3 P_ddot =
            mo.acceleration + mo.alpha.cross(arm) + mo.omega.cross(mo.omega.cross(arm));
        const Vec3 d = P - l.geometry.base_points.col(k);
        const double L = d.norm();
        const Vec3 n = d / L;
        const double L_dot = n.dot(P_dot);
        const Vec3 n_dot = (P_dot - L_dot * n) / L;
        const double L_ddot = (P_dot.squaredNorm() + d.dot(P_ddot) - L_dot * L_dot) / L;
        const Vec3 n_ddot = (P_ddot - L_ddot * n - 2.0 * L_dot * n_dot) / L;

        Motion cylinder;
        cylinder.position = l.geometry.base_points.col(k) + l.cylinder_com * n;
        cylinder.velocity = l.cylinder_com * n_dot;
        cylinder.acceleration = l.cylinder_com * n_ddot;
        Motion piston;
        const Vec3 plate_arm = R * l.platform_arm.col(k);
        piston.position = P - l.piston_com * n;
        piston.velocity = P_dot - l.piston_com * n_dot;
        piston.acceleration = P_ddot - l.piston_com * n_ddot;
        leg_bodies_rates(n, n_dot, n_ddot, l.base_arm.col(k), plate_arm, mo.omega, mo.alpha,
                         cylinder, piston);
        put_body_motion(s, l.cylinder[k], cylinder);
        put_body_motion(s, l.piston[k], piston);
    }
    Motion platform;
    const Vec3 c = R * l.com;
    platform.position = mo.position + c;
    platform.velocity = mo.velocity + mo.omega.cross(c);
    platform.acceleration = mo.acceleration + mo.alpha.cross(c) + mo.omega.cross(mo.omega.cross(c));
    platform.rotation = R * l.axes;
    platform.omega = mo.omega;
    platform.alpha = mo.alpha;
    put_body_motion(s, l.platform, platform);
}

void full_set_drivers(const FullLayout &l, const Motion &mo, const LegKinematics &legs,
                      mbs::State &s) {
    const mbs::Mechanism &m = s.mechanism;
    if (l.drive == FullDrive::ActuatorLengths) {
        for (int k = 0; k < STEWART_LEGS; ++k)
            s.drive[m.joints[l.driver_joint[k]].driver] =
                mbs::DriverValue{legs.length[k], legs.rate[k], legs.accel[k]};
        return;
    }
    const Vec3 c = mo.rotation * l.com;
    const Vec3 r = mo.position + c;
    const Vec3 v = mo.velocity + mo.omega.cross(c);
    const Vec3 a = mo.acceleration + mo.alpha.cross(c) + mo.omega.cross(mo.omega.cross(c));
    const Vec4 p =
        same_side(mbs::euler_parameters(mo.rotation * l.axes), mbs::body_p(s.q.data(), l.platform));
    const mbs::Mat34 E = mbs::E_matrix(p.data());
    const Vec4 p_dot = 0.5 * E.transpose() * mo.omega;
    const Vec4 p_ddot = 0.5 * E.transpose() * mo.alpha - p_dot.squaredNorm() * p;
    mbs::DriverValue *d = s.drive.data() + m.joints[l.pose_joint].driver;
    for (int i = 0; i < 3; ++i) d[i] = mbs::DriverValue{r[i], v[i], a[i]};
    for (int i = 0; i < 4; ++i) d[3 + i] = mbs::DriverValue{p[i], p_dot[i], p_ddot[i]};
}

stewart_status full_solve(const FullLayout &l, mbs::State &s, const stewart_inverse_options &o,
                          const Motion &si_motion, const LegKinematics &si_legs,
                          stewart_inverse_output &out, char *msg, size_t size) {
    const mbs::Mechanism &m = s.mechanism;
    const double L0 = l.length_unit, per_L0 = 1.0 / L0;  // powers of two: exact
    Motion motion = si_motion;
    motion.position *= per_L0, motion.velocity *= per_L0, motion.acceleration *= per_L0;
    LegKinematics legs;
    legs.length = si_legs.length * per_L0, legs.rate = si_legs.rate * per_L0;
    legs.accel = si_legs.accel * per_L0;
    full_motion(l, motion, s);
    full_set_drivers(l, motion, legs, s);
    mbs::SolverOptions so = s.newton_options;
    so.tolerance = o.tolerance;
    so.max_iterations = o.max_iterations;
    so.modified_newton = o.modified_newton != 0;
    const mbs_status st = mbs::solve_step_known_motion(s, 0.0, so);
    if (st != MBS_OK) return set_message(msg, size, from_mbs(st), "full model: %s", s.message);

    // Leg lengths and their rates from the solved bodies: the two Cardan centres. If Newton did
    // not move q, the bodies are the closed-form placement with the closed-form rates, whose
    // Cardan centres are the legs' ends: the lengths are the closed form's (to rounding).
    for (int k = 0; k < STEWART_LEGS; ++k) {
        out.force[k] = 0;
        if (s.stats.iterations == 0) {
            out.lengths.length[k] = si_legs.length[k];
            out.lengths.length_rate[k] = si_legs.rate[k];
            out.lengths.length_accel[k] = si_legs.accel[k];
            continue;
        }
        using mbs::body_r;
        const double *qc = body_r(s.q.data(), l.cylinder[k]), *qp = body_r(s.q.data(), l.piston[k]);
        const double *vc = body_r(s.q_dot.data(), l.cylinder[k]);
        const double *vp = body_r(s.q_dot.data(), l.piston[k]);
        const double *ac = body_r(s.q_ddot.data(), l.cylinder[k]);
        const double *ap = body_r(s.q_ddot.data(), l.piston[k]);
        const Vec3 uc(0, 0, -l.cylinder_com), up(0, 0, l.piston_com);
        auto point = [](const double *q, const Vec3 &u) {
            return Vec3(Eigen::Map<const Vec3>(q) + mbs::rotate(q + 3, u));
        };
        // d(A u)/dt = B(p, u) p_dot = 2 C(p, p_dot) u; d2(A u)/dt2 adds 2 A(p_dot) u.
        auto rate = [](const double *q, const double *v, const Vec3 &u) {
            return Vec3(Eigen::Map<const Vec3>(v) + 2.0 * mbs::bilinear(q + 3, v + 3, u));
        };
        auto accel = [](const double *q, const double *v, const double *a, const Vec3 &u) {
            return Vec3(Eigen::Map<const Vec3>(a) + 2.0 * mbs::bilinear(q + 3, a + 3, u) +
                        2.0 * mbs::rotate(v + 3, u));
        };
        const Vec3 d = point(qp, up) - point(qc, uc);
        const Vec3 d_dot = rate(qp, vp, up) - rate(qc, vc, uc);
        const Vec3 d_ddot = accel(qp, vp, ap, up) - accel(qc, vc, ac, uc);
        const double L = d.norm(), L_dot = d.dot(d_dot) / L;
        out.lengths.length[k] = L * L0;
        out.lengths.length_rate[k] = L_dot * L0;
        out.lengths.length_accel[k] =
            (d_dot.squaredNorm() + d.dot(d_ddot) - L_dot * L_dot) / L * L0;
    }
    if (l.drive == FullDrive::ActuatorLengths)
        for (int k = 0; k < STEWART_LEGS; ++k)
            out.force[k] = -s.lambda[m.first_row[l.driver_joint[k]]] * L0;
    else thesis_forces(l, s, out.force);  // in units of L0 N, scaled below

    // The wrench of the base Cardans on the base, about the world origin. The base is massless
    // and joined by them alone, so it is the ground's on the base reversed: the reaction of the
    // joint that fixes it, whose multipliers the transposed solve forms anyway (one reaction
    // where the six Cardans' took 1.8 k instructions; the same sums in another order).
    Vec3 ground_force, ground_torque;
    mbs::joint_reaction(m, s, l.base_fixed, 0, ground_force, ground_torque);
    const Vec3 f = -ground_force;
    const Vec3 t = -ground_torque + Vec3(mbs::body_r(s.q.data(), l.base)).cross(f);
    if (l.drive == FullDrive::PlatformPose)
        for (int k = 0; k < STEWART_LEGS; ++k) out.force[k] *= L0;
    for (int i = 0; i < 3; ++i) out.base_force[i] = f[i] * L0, out.base_torque[i] = t[i] * L0 * L0;
    out.iterations = s.stats.iterations;
    out.residual = s.stats.residual * L0;
    return STEWART_OK;
}

void thesis_forces(const FullLayout &l, const mbs::State &s, double force[STEWART_LEGS]) {
    const mbs::Mechanism &m = s.mechanism;
    // The pose drivers' reaction on the platform: force, and torque about its origin.
    const double *lambda = s.lambda.data() + m.first_row[l.pose_joint];
    const double *q = mbs::body_r(s.q.data(), l.platform);
    Matrix6 Jt;
    Vector6 wrench;
    wrench.head<3>() = -Vec3(lambda);
    wrench.tail<3>() = mbs::rotate(q + 3, -0.5 * mbs::G_matrix(q + 3) * Vec4(lambda + 3));
    // Virtual power: sum F_k dL_k = wrench . twist, dL_k = n_k . (v + w x (P_k - r)).
    const Vec3 r(q);
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const Vec3 P = r + mbs::rotate(q + 3, l.axes.transpose() *
                                                  (l.geometry.platform_points.col(k) - l.com));
        const Vec3 n = (P - l.geometry.base_points.col(k)).normalized();
        Jt.block<3, 1>(0, k) = n;
        Jt.block<3, 1>(3, k) = (P - r).cross(n);
    }
    const Vector6 F = Jt.partialPivLu().solve(wrench);
    for (int k = 0; k < STEWART_LEGS; ++k) force[k] = F[k];
}

}  // namespace stewart
