// The two closed-form fidelity levels: leg kinematics, and forces with massless legs.
#pragma once

#include <Eigen/Dense>

#include "kinematics/joints.hpp"
#include "kinematics/motion.hpp"
#include "stewart/stewart.h"

namespace stewart {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

// Attachment points from the parameters (kinematics/joints.hpp: circles or the 36 coordinates):
// a_k in the world, b_k in the platform frame.
struct PlatformGeometry {
    Matrix36 base_points;
    Matrix36 platform_points;
    double min_length;  // below it a leg has no direction: the pose is unreachable [m]
    // The platform's size (its radius, or its farthest joint from the platform origin): scales
    // the angular part of the Jacobian.
    double characteristic_length;
};
PlatformGeometry platform_geometry(const stewart_params &p);

// Platform and payload lumped into one rigid body, in the platform frame.
struct LumpedBody {
    double mass;
    Eigen::Vector3d com;
    Eigen::Matrix3d inertia;  // about com
};
LumpedBody lumped_platform(const stewart_params &p);

// Per-leg kinematics along a pose.
struct LegKinematics {
    Matrix36 arm;   // R b_k: platform point relative to the platform origin, world
    Matrix36 axis;  // unit vector n_k from base point toward platform point
    Vector6 length, rate, accel;
};

// Fails with STEWART_ERR_UNREACHABLE (message names the leg) when a leg has zero length.
stewart_status leg_kinematics(const PlatformGeometry &g, const Motion &m, LegKinematics &out,
                              char *msg, size_t size);

// STEWART_ERR_UNREACHABLE (message names the leg and its length) unless length > min_length: a
// leg of (nearly) zero length has no direction, so no force or rate can be defined.
stewart_status check_leg_length(int leg, double length, double min_length, char *msg, size_t size);

// The leg Jacobian J maps the platform twist (v, omega) at its origin to the leg rates L_dot.
// Its angular columns are divided by the characteristic length (the platform radius), so that
// the condition number is dimensionless and the same for a platform of any size.
struct LegJacobian {
    Matrix6 transposed;  // column k = (n_k, (R b_k) x n_k / length)
    Matrix6 inverse_transposed;
    double condition;  // 1-norm condition number; +inf if singular
};
void leg_jacobian(const PlatformGeometry &g, const LegKinematics &legs, LegJacobian &out);

// STEWART_ERR_SINGULAR (message names both numbers) unless condition <= singular_condition: the
// pose check of the force levels, shared so that every caller gives the same verdict.
stewart_status check_condition(double condition, double singular_condition, char *msg, size_t size);

// Massless legs: solves J^T F = wrench needed by Newton-Euler for the lumped body, fills
// force, condition and the base wrench. STEWART_ERR_SINGULAR if the condition number is above
// singular_condition (or not finite).
stewart_status massless_forces(const PlatformGeometry &g, const LumpedBody &body,
                               const Eigen::Vector3d &gravity, const Motion &m,
                               const LegKinematics &legs, double singular_condition,
                               stewart_inverse_output &out, char *msg, size_t size);

// The wrench the legs put on the base, from the forces along the leg axes (massless legs).
void base_wrench_from_axial(const PlatformGeometry &g, const LegKinematics &legs,
                            const double force[STEWART_LEGS], stewart_inverse_output &out);

}  // namespace stewart
