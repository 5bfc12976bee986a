// The thesis' 14-body Stewart platform (docs/model.md) built on the multibody core: a builder that
// turns the parameters into bodies and joints, the closed-form initial guess, and the solve that
// fills stewart_inverse_output at the full fidelity level.
#pragma once

#include <memory>

#include "core/mbs_handles.hpp"
#include "kinematics/closed_form.hpp"

namespace stewart {

enum class FullDrive {
    ActuatorLengths,  // 6 distance drivers on the cylindrical joints: multipliers = -forces
    PlatformPose      // 7 pose drivers on the platform (the thesis' way)
};

// Which bodies and joints are which, and where the platform body sits in the plate frame.
struct FullLayout {
    FullDrive drive = FullDrive::ActuatorLengths;
    int base = 0, platform = 13;
    int base_fixed = -1;  // the joint that fixes the base
    int cylinder[STEWART_LEGS], piston[STEWART_LEGS];
    int base_cardan[STEWART_LEGS], cylindrical[STEWART_LEGS];
    int driver_joint[STEWART_LEGS];  // length drivers (ActuatorLengths)
    int pose_joint = -1;             // pose driver (PlatformPose)
    Eigen::Vector3d com;             // platform body origin (lumped centre of mass), plate frame
    Eigen::Matrix3d axes;            // platform body axes (principal) in the plate frame
    double cylinder_com = 0, piston_com = 0;
    Matrix36 base_arm;          // Cardan cross arm on the base, world (kinematics/joints.hpp)
    Matrix36 platform_arm;      // Cardan cross arm on the platform, plate frame
    PlatformGeometry geometry;  // in the length unit
    // The mechanism's lengths are in units of length_unit m: the power of two L0 with
    // max(base size, platform size, home_height) / L0 in (0.25, 0.5] (the sizes are the radii, or
    // the farthest joint from each frame's origin: JointGeometry; L0 = 1 for the thesis
    // platform). Scaling by a power of two is exact, and the Newton residual then floors at the
    // same few roundings at any size, so one tolerance serves every size (masses are kept:
    // forces are in units of L0 N, torques L0^2 N m, inertias L0^2 kg m^2).
    double length_unit = 1;
};

// The length unit L0 of a platform with these parameters (see FullLayout::length_unit).
double length_unit(const stewart_params &p);

// Builds and finalises the mechanism (in the length unit); null (message says why) on failure.
std::unique_ptr<mbs_model> build_full_platform(const stewart_params &p, FullDrive drive,
                                               FullLayout &layout, char *msg, size_t size);

// Every body placed in closed form for the platform motion (in the length unit), with its
// velocity and acceleration (q, q_dot, q_ddot: what solve_step_known_motion takes; Euler-parameter
// signs kept continuous with the previous solution, if any); and the drivers set for that motion.
void full_motion(const FullLayout &l, const Motion &motion, mbs::State &s);
void full_set_drivers(const FullLayout &l, const Motion &motion, const LegKinematics &legs,
                      mbs::State &s);

// Position, velocity, acceleration, multipliers; fills lengths, rates, accelerations, forces,
// iterations, residual and the base wrench (condition and warnings are the caller's). Motion,
// legs and outputs in SI; o.tolerance applies in the length unit.
stewart_status full_solve(const FullLayout &l, mbs::State &s, const stewart_inverse_options &o,
                          const Motion &motion, const LegKinematics &legs,
                          stewart_inverse_output &out, char *msg, size_t size);

// The thesis' way, on a PlatformPose model: the platform wrench from the 7 pose-driver
// multipliers, mapped to leg forces by virtual power (J^T F = wrench, 6 x 6).
void thesis_forces(const FullLayout &l, const mbs::State &s, double force[STEWART_LEGS]);

}  // namespace stewart
