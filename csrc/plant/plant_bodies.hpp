// Forward dynamics, kinematic part: every leg body's pose, velocity and acceleration in closed
// form from the platform's motion (the platform pose and twist are the independent coordinates).
#pragma once

#include <Eigen/Dense>

#include "kinematics/closed_form.hpp"

namespace stewart {
namespace fd {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// The platform frame's motion and each body's (centre of mass, axes as columns, and their rates):
// stewart::Motion (kinematics/motion.hpp), world frame.

// What the leg bodies need from the model (full_model.cpp places them the same way).
struct LegParameters {
    Matrix36 base_points;      // a_k, world
    Matrix36 platform_points;  // b_k, plate frame
    Matrix36 base_arm;         // Cardan cross arm on the base, world
    Matrix36 platform_arm;     // Cardan cross arm on the platform, plate frame
    double cylinder_com = 0, piston_com = 0;
    double min_length = 0;      // below it a leg has no direction [m]
    double min_cardan_sin = 0;  // |s x n| below it a Cardan is locked (leg along its arm)
};

enum class LegFault { None, ZeroLength, LockedBaseCardan, LockedPlatformCardan };

// Leg k at one platform pose: its axis, and the x axes of both leg bodies (x = s x n / |s x n|,
// y = n x x, z = n: the cross arm of each Cardan is perpendicular to the plate's arm s).
struct LegConfiguration {
    Vec3 arm;             // R b_k
    Vec3 n;               // unit axis, base toward platform
    double length;
    double inverse_length;
    Vec3 piston_arm;      // R s_k of the platform Cardan (the base arm is fixed)
    Vec3 cylinder_x, piston_x;
    double cylinder_sin, piston_sin;  // |s x n| of each Cardan
};

// LegFault::None, or why leg k has no defined bodies at this pose. Without frames only the axis
// and length are filled (massless legs).
LegFault leg_configuration(const LegParameters &p, int k, const Vec3 &position,
                           const Mat3 &rotation, LegConfiguration &c, bool frames = true);

// Both bodies of leg k for the platform motion m (pose in c): poses, velocities, accelerations.
// Velocities are linear in the twist; accelerations are linear in the twist rate plus the
// velocity-product terms (zero twist rate gives those alone, zero twist gives the Jacobian).
void leg_body_motion(const LegParameters &p, int k, const LegConfiguration &c,
                     const Motion &m, Motion &cylinder, Motion &piston);

// The leg bodies' accelerations as linear maps of the platform point's acceleration P_ddot and
// the platform's angular acceleration alpha, as if every velocity were zero:
//   cylinder: a = cylinder_com N P_ddot,        alpha_c = cylinder_alpha P_ddot
//   piston:   a = (I - piston_com N) P_ddot,
//             alpha_p = piston_alpha P_ddot - n (piston_spin . alpha)
struct LegAccelerationMap {
    Mat3 N;  // n_ddot per unit P_ddot: (I - n n^T) / L
    Mat3 cylinder_alpha, piston_alpha;
    Vec3 piston_spin;
};
void leg_acceleration_map(const LegParameters &p, int k, const LegConfiguration &c,
                          LegAccelerationMap &map);

}  // namespace fd
}  // namespace stewart
