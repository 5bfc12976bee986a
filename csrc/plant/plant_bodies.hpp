// Forward dynamics, kinematic part: every leg body's pose, velocity and acceleration in closed
// form from the platform's motion (the platform pose and twist are the independent coordinates).
#pragma once

#include <Eigen/Dense>

#include "kinematics/closed_form.hpp"

namespace stewart {
namespace plant {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
// The same with any scalar: every function below is a template on it (plant_bodies_impl.hpp),
// instantiated for double (the plant, plant_bodies.cpp) and for stewart::Dual (linearisation,
// linearize/plant_dual.cpp).
template <class S>
using Vec3T = Eigen::Matrix<S, 3, 1>;
template <class S>
using Mat3T = Eigen::Matrix<S, 3, 3>;

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
template <class S>
struct LegConfigurationT {
    Vec3T<S> arm;  // R b_k
    Vec3T<S> n;    // unit axis, base toward platform
    S length;
    S inverse_length;
    Vec3T<S> piston_arm;  // R s_k of the platform Cardan (the base arm is fixed)
    Vec3T<S> cylinder_x, piston_x;
    S cylinder_sin, piston_sin;  // |s x n| of each Cardan
};
using LegConfiguration = LegConfigurationT<double>;

// LegFault::None, or why leg k has no defined bodies at this pose. Without frames only the axis
// and length are filled (massless legs).
template <class S>
LegFault leg_configuration(const LegParameters &p, int k, const Vec3T<S> &position,
                           const Mat3T<S> &rotation, LegConfigurationT<S> &c, bool frames = true);

// Both bodies of leg k for the platform motion m (pose in c): poses, velocities, accelerations.
// Velocities are linear in the twist; accelerations are linear in the twist rate plus the
// velocity-product terms (zero twist rate gives those alone, zero twist gives the Jacobian).
template <class S>
void leg_body_motion(const LegParameters &p, int k, const LegConfigurationT<S> &c,
                     const MotionT<S> &m, MotionT<S> &cylinder, MotionT<S> &piston);

// The leg bodies' accelerations as linear maps of the platform point's acceleration P_ddot and
// the platform's angular acceleration alpha, as if every velocity were zero:
//   cylinder: a = cylinder_com N P_ddot,        alpha_c = cylinder_alpha P_ddot
//   piston:   a = (I - piston_com N) P_ddot,
//             alpha_p = piston_alpha P_ddot - n (piston_spin . alpha)
template <class S>
struct LegAccelerationMapT {
    Mat3T<S> N;  // n_ddot per unit P_ddot: (I - n n^T) / L
    Mat3T<S> cylinder_alpha, piston_alpha;
    Vec3T<S> piston_spin;
};
template <class S>
void leg_acceleration_map(const LegParameters &p, int k, const LegConfigurationT<S> &c,
                          LegAccelerationMapT<S> &map);

// The leg bodies' applied minus inertial wrenches (f_cyl, t_cyl, f_pis, t_pis: forces, torques
// about their centres of mass) as generalised forces: f_point on the platform point's
// acceleration P_ddot, f_alpha on the platform's angular acceleration (the piston's spin). The
// transposes of leg_acceleration_map's maps applied to them, in vector form (no 3 x 3 product:
// the cheap way for the linearisation's dual scalar).
template <class S>
void leg_point_forces(const LegParameters &p, int k, const LegConfigurationT<S> &c,
                      const Vec3T<S> &f_cyl, const Vec3T<S> &t_cyl, const Vec3T<S> &f_pis,
                      const Vec3T<S> &t_pis, Vec3T<S> &f_point, Vec3T<S> &f_alpha);

}  // namespace plant
}  // namespace stewart
