// Forward dynamics, kinetic part: the reduced equations in the platform twist nu = (v, omega),
// (sum J_b^T M_b J_b) nu_dot = sum J_b^T (f_b - M_b J_b_dot nu) + J_legs^T F, and the base wrench.
#pragma once

#include "drives/leg_drive.hpp"
#include "plant/plant_bodies.hpp"
#include "stewart/stewart_plant.h"

namespace stewart {
namespace plant {

// The legs' drives when the plant's input is a current or a voltage (plant_drive_rhs.cpp):
// input STEWART_PLANT_INPUT_FORCE leaves them unused and every equation as without drives.
struct DriveModel {
    int input = 0;               // stewart_plant_input_kind
    bool inductive = false;      // voltage input and a winding with inductance: currents are states
    double smoothing_speed = 0;  // [m/s]
    LegDrive legs[STEWART_LEGS];
    double reflected_mass[STEWART_LEGS] = {};  // J (2 pi N / lead)^2 [kg]
    // end stops on the Cardan-to-Cardan length (the stroke's), and their stiffness and damping
    double stop_min[STEWART_LEGS] = {}, stop_max[STEWART_LEGS] = {};
    double stop_stiffness[STEWART_LEGS] = {}, stop_damping[STEWART_LEGS] = {};
};

// What a driven evaluation found per leg (plant_drive_rhs.cpp): the step's drive outputs.
struct DriveTerms {
    double current[STEWART_LEGS];      // motor current [A]
    double length_rate[STEWART_LEGS];  // [m/s]
    double leg_force[STEWART_LEGS];    // axial force on the mechanism (F_k of force input) [N]
    double nut_force[STEWART_LEGS];    // the screw's nut on the leg [N]
    double friction[STEWART_LEGS];     // friction on the leg, opposing its speed [N]
    double stop_force[STEWART_LEGS];   // end stop on the leg [N]
    double ideal_force[STEWART_LEGS];  // the screw's torque from the motor side, as a force
                                       // (2 pi N / lead) (k_t i - J omega_dot) [N]
};

// The bodies' masses and inertias and what the leg bodies need; with_legs false drops the leg
// bodies (massless legs: the platform driven by the axial forces alone).
struct DynamicsModel {
    DriveModel drives;
    LegParameters legs;
    bool with_legs = true;
    double platform_mass = 0;
    Vec3 platform_com;      // plate frame
    Mat3 platform_inertia;  // about the centre of mass, plate frame
    Mat3 platform_inertia_inverse;
    double cylinder_mass = 0, piston_mass = 0;
    Vec3 cylinder_inertia, piston_inertia;  // principal, leg-body axes
    Vec3 gravity;
    // The double twist_rate takes the template formulation even for axisymmetric leg bodies
    // (tests compare the two formulations through the plant's integrator).
    bool reference_equations = false;
    // legs.platform_points and legs.base_points by coordinate (row i: the six legs' i-th
    // coordinate, side by side), as dynamics_model copies them: the massless right-hand side's
    // loops over the legs load them in pairs instead of one by one.
    double platform_point_rows[3][STEWART_LEGS] = {}, base_point_rows[3][STEWART_LEGS] = {};
};

// DynamicsModel from a built stewart_model; fidelity STEWART_MASSLESS or STEWART_FULL.
DynamicsModel dynamics_model(const stewart_model &model, int fidelity);

// What the closed-form right-hand side (plant_full_rhs.cpp) finds per leg at the state's
// velocities (zero twist rate), kept for the base wrench at the same state: the rest of a leg's
// accelerations is linear in its platform point's acceleration P_acc = v_dot + alpha x arm
// (n_ddot += N P_acc, P_ddot += P_acc, the cylinder's w_dot += h_cylinder . P_acc, the piston's
// w_dot += h_piston . P_acc - spin . alpha).
struct LegRateTerms {
    Vec3 n_dot, n_ddot, P_ddot;           // the axis's rates, the platform point's acceleration
    Vec3 h_cylinder, h_piston, spin;      // the spins' acceleration maps
    double w_cylinder, w_piston;          // the bodies' spins about the leg
    double w_dot_cylinder, w_dot_piston;  // their rates' velocity-product parts
};

// The kept terms of one closed-form evaluation: per leg, and the platform's centre of mass
// (from the origin) and inertia in the world.
struct KeptTerms {
    LegRateTerms legs[STEWART_LEGS];
    Vec3 platform_com;
    Mat3 platform_inertia;
    // massless_twist_rate's (every evaluation of it): the legs' axial forces summed, and their
    // moments about the platform's origin (the base wrench of massless legs)
    Vec3 legs_force, legs_moment;
};

// Results and workspace of one evaluation (any scalar, as plant_bodies.hpp).
template <class S>
struct EvaluationT {
    LegConfigurationT<S> legs[STEWART_LEGS];
    LegFault fault = LegFault::None;
    int fault_leg = -1;                 // 0-based
    Eigen::Matrix<S, 6, 1> twist_rate;  // (v_dot, omega_dot) at the platform origin, world
    // Asked of the closed-form right-hand side (double, axisymmetric leg bodies): keep its leg
    // terms in `kept` (the plant's integrator asks at the step's end, whose outputs reuse them);
    // terms_kept says whether this evaluation did.
    bool keep_terms = false;
    bool terms_kept = false;
    KeptTerms kept;
    // Asked of massless_twist_rate: fill legs[] (the arms, axes, lengths); the plant's integrator
    // does not ask (its evaluations' twist rates, faults and leg sums are all it reads).
    bool fill_legs = true;
    DriveTerms drive;  // a driven evaluation's (DriveModel input current or voltage)
    // The windings' currents of the state (DriveModel inductive: the integrator's states after
    // the platform's), read for the legs with an inductance; set by whoever evaluates.
    const double *winding_current = nullptr;
};
using Evaluation = EvaluationT<double>;

// The reduced equations M nu_dot = rhs for the state in m (pose and twist; its accelerations are
// ignored) under the leg forces: M the generalised mass matrix (symmetric positive definite), rhs
// the applied and velocity-product forces. False (fault set) as twist_rate.
template <class S>
bool reduced_equations(const DynamicsModel &d, const MotionT<S> &m, const S force[STEWART_LEGS],
                       EvaluationT<S> &e, Eigen::Matrix<S, 6, 6> &M, Eigen::Matrix<S, 6, 1> &rhs);

// The platform's twist rate for the state in m (pose and twist; its accelerations are ignored)
// under the leg forces. False (fault set) if a leg has no direction or a Cardan is locked.
// Instantiated for double (the plant) and stewart::Dual (linearisation).
template <class S>
bool twist_rate(const DynamicsModel &d, const MotionT<S> &m, const S force[STEWART_LEGS],
                EvaluationT<S> &e);

// twist_rate for the plant's scalar: with leg bodies whose principal inertias are axisymmetric
// (Ixx == Iyy, every catalogue platform) the same equations in closed form (plant_full_rhs.cpp:
// no rotation matrix per body, no 3 x 3 product; equal to twist_rate<double> to rounding); for
// the massless model massless_twist_rate (the integrator's); otherwise (or with
// d.reference_equations) twist_rate<double> itself.
bool twist_rate(const DynamicsModel &d, const Motion &m, const double force[STEWART_LEGS],
                Evaluation &e);

// base_wrench of body_motions' bodies for the platform motion m with its accelerations (e its
// configuration, twist_rate's evaluation), for the plant's scalar: in closed form for
// axisymmetric leg bodies (plant_full_rhs.cpp, without the 13 bodies' motions; equal to
// rounding), from e's kept terms when it kept them (m's pose and twist must then be e's state's),
// otherwise those two. For massless legs (massless_twist_rate's model) the base takes the legs'
// axial forces, from e's sums (m's position must be e's state's): equal to the bodies' momentum
// rates at e's accelerations to rounding.
void base_wrench(const DynamicsModel &d, const Motion &m, const Evaluation &e, Vec3 &force,
                 Vec3 &torque);

// The reduced equations' M (its upper triangle, row-major) and rhs under the given leg forces
// for the plant's scalar, by twist_rate's own assembly (closed form for axisymmetric leg bodies,
// else the template's; for the massless model the template's): what the drives add to
// (plant_full_rhs.cpp).
bool reduced_equations(const DynamicsModel &d, const Motion &m, const double force[STEWART_LEGS],
                       Evaluation &e, double M[6][6], double rhs[6]);

// x = (M + sum_k weight_k j_k j_k^T)^-1 rhs, M symmetric positive definite by its upper triangle
// and the weights >= 0 (the six legs' rank-one terms), by the written-out LDL^T.
void solve_with_rank_ones(const double M[6][6], const double rhs[6], const double (*j)[6],
                          const double *weight, double x[6]);

// The drives of a plant with these options (input FORCE: none). STEWART_ERR_PARAMETER, with a
// message naming the leg and the parameter, for a drive the plant cannot take.
stewart_status drive_model(const stewart_params &p, const stewart_plant_options &o, DriveModel &d,
                           char *msg, size_t size);

// d/dt of the windings' currents at the evaluation e of a driven state under the voltages:
// (V - R i - k_t omega) / L for a leg with an inductance, 0 for the others.
void winding_rates(const DynamicsModel &d, const double voltage[STEWART_LEGS], const Evaluation &e,
                   double rates[STEWART_LEGS]);

// twist_rate for a plant driven by currents or voltages (d.drives.input not FORCE): input holds
// each leg's current [A] or voltage [V]; the leg forces follow from the drives' law
// (plant_drive_rhs.cpp) into e.drive. False (fault set) as twist_rate.
bool driven_twist_rate(const DynamicsModel &d, const Motion &m, const double input[STEWART_LEGS],
                       Evaluation &e);

// twist_rate<double>'s equations for the massless model (d.with_legs false), written out in
// scalars with moments about the centre of mass and the gyroscopic term in the platform's axes
// (plant_massless.cpp): equal to twist_rate<double> to rounding (tests/unit/test_plant_rhs.cpp
// holds 1e-14), a third of its instructions. The plant's integrator calls it for every massless
// right-hand side, and twist_rate for double does too.
bool massless_twist_rate(const DynamicsModel &d, const Motion &m, const double force[STEWART_LEGS],
                         Evaluation &e);

// The reduced equations' residual at the motion m with its accelerations (v_dot at the origin,
// alpha): sum J_b^T (f_b - M_b a_b) + J_legs^T F, i.e. rhs - M nu_dot of twist_rate's equations,
// by Newton-Euler per body without forming M: zero at twist_rate's result, and linear in the
// twist rate with slope -M (what the linearisation differentiates). False (fault set) as
// twist_rate. Instantiated for the linearisation's 12-direction dual (linearize/plant_dual.cpp).
template <class S>
bool motion_residual(const DynamicsModel &d, const MotionT<S> &m, const double force[STEWART_LEGS],
                     EvaluationT<S> &e, Eigen::Matrix<S, 6, 1> &residual);

// The 13 moving bodies (platform, cylinders, pistons) for m including its accelerations; the leg
// bodies are left untouched for the massless model. e must hold the configuration of m.
template <class S>
void body_motions(const DynamicsModel &d, const MotionT<S> &m, const EvaluationT<S> &e,
                  MotionT<S> bodies[13]);

// The wrench the moving bodies put on the base (about the world origin): minus the rate of
// their momentum and angular momentum less gravity (the actuator forces are internal).
template <class S>
void base_wrench(const DynamicsModel &d, const MotionT<S> bodies[13], Vec3T<S> &force,
                 Vec3T<S> &torque);

}  // namespace plant
}  // namespace stewart
